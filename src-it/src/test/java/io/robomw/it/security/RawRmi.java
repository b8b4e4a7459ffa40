package io.robomw.it.security;

import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.ObjectOutputStream;
import java.io.OutputStream;
import java.lang.reflect.Proxy;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.rmi.Remote;
import java.rmi.server.RemoteObject;
import java.security.MessageDigest;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * An attacker's RMI client, byte by byte (JRMP, the Java RMI wire protocol): the handshake, and a
 * call that announces a byte array of any length and then sends as little of it as it likes, as
 * nobody's RMI client would. The object id of the call's target is read from its stub (which
 * anyone gets from the registry).
 */
final class RawRmi {

    /** JRMP: the magic "JRMI", version 2, the stream protocol; the server answers ProtocolAck. */
    static final int MAGIC = 0x4a524d49;
    static final int VERSION = 2;
    static final int STREAM_PROTOCOL = 0x4b;
    static final int PROTOCOL_ACK = 0x4e;
    /** The message that starts a call. */
    static final int CALL = 0x50;

    /** The parts of an exported object's id: {@code java.rmi.server.ObjID}'s number and its {@code UID}. */
    record ObjectId(long number, int unique, long time, short count) {

        private static final Pattern FORM = Pattern.compile("objID:\\[(-?[0-9a-f]+):(-?[0-9a-f]+):(-?[0-9a-f]+), (-?\\d+)]");

        /** Reads it from the stub's reference (its text form, the only public view of it). */
        static ObjectId of(Remote stub) {
            String ref = ((RemoteObject) Proxy.getInvocationHandler(stub)).getRef().remoteToString();
            Matcher m = FORM.matcher(ref);
            if (!m.find()) {
                throw new IllegalStateException("no object id in " + ref);
            }
            return new ObjectId(Long.parseLong(m.group(4)), Integer.parseInt(m.group(1), 16), Long.parseLong(m.group(2), 16),
                    (short) Integer.parseInt(m.group(3), 16));
        }
    }

    private RawRmi() {
    }

    /** Connects and does the client's half of the JRMP handshake. */
    static Socket connect(int port) throws IOException {
        Socket s = new Socket();
        s.connect(new InetSocketAddress("127.0.0.1", port), 10_000);
        s.setSoTimeout(60_000);
        DataOutputStream out = new DataOutputStream(s.getOutputStream());
        DataInputStream in = new DataInputStream(s.getInputStream());
        out.writeInt(MAGIC);
        out.writeShort(VERSION);
        out.writeByte(STREAM_PROTOCOL);
        out.flush();
        int ack = in.read();
        if (ack != PROTOCOL_ACK) {
            s.close();
            throw new IOException("no JRMP ProtocolAck (" + ack + ")");
        }
        in.readUTF();
        in.readInt();
        out.writeUTF("127.0.0.1");
        out.writeInt(0);
        out.flush();
        return s;
    }

    /**
     * The start of a call of {@code method} on the object whose one argument is a byte array, up
     * to and with the array's length: what follows is the array's bytes.
     *
     * @param target     the object
     * @param method     the method's name and descriptor, e.g. {@code call([B)[B}
     * @param announced  the array length to announce
     * @return the bytes to send
     */
    static byte[] callAnnouncing(ObjectId target, String method, int announced) throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        bytes.write(CALL);
        try (ObjectOutputStream out = new RmiObjectStream(bytes)) {
            out.writeLong(target.number());
            out.writeInt(target.unique());
            out.writeLong(target.time());
            out.writeShort(target.count());
            out.writeInt(-1); // a method named by its hash
            out.writeLong(methodHash(method));
            out.writeObject(new byte[0]);
            out.flush();
        }
        byte[] b = bytes.toByteArray();
        // the array's length is the last four bytes: announce another
        b[b.length - 4] = (byte) (announced >>> 24);
        b[b.length - 3] = (byte) (announced >>> 16);
        b[b.length - 2] = (byte) (announced >>> 8);
        b[b.length - 1] = (byte) announced;
        return b;
    }

    /** RMI's method hash: the first 8 bytes (little-endian) of SHA-1 over the UTF form of name and descriptor. */
    static long methodHash(String nameAndDescriptor) throws IOException {
        try {
            ByteArrayOutputStream utf = new ByteArrayOutputStream();
            new DataOutputStream(utf).writeUTF(nameAndDescriptor);
            byte[] sha = MessageDigest.getInstance("SHA-1").digest(utf.toByteArray());
            long hash = 0;
            for (int i = 0; i < 8; i++) {
                hash += ((long) (sha[i] & 0xFF)) << (i * 8);
            }
            return hash;
        } catch (java.security.NoSuchAlgorithmException e) {
            throw new IllegalStateException(e);
        }
    }

    /**
     * @return what the server answered, as text (a serialized exception's message shows in it): what came
     *         until the server closed the connection, an exception's name appeared, or the socket's timeout passed
     */
    static String answer(Socket s) {
        ByteArrayOutputStream got = new ByteArrayOutputStream();
        byte[] buf = new byte[4096];
        try {
            for (int n; (n = s.getInputStream().read(buf)) > 0; ) {
                got.write(buf, 0, n);
                String text = got.toString(StandardCharsets.ISO_8859_1);
                if (text.contains("REJECTED") || text.contains("Error")) {
                    break;
                }
            }
        } catch (IOException e) {
            got.writeBytes((" (" + e + ")").getBytes(StandardCharsets.ISO_8859_1));
        }
        return got.toString(StandardCharsets.ISO_8859_1);
    }

    /** An object stream as RMI's marshal streams write one: each class descriptor annotated with its code base (none). */
    private static final class RmiObjectStream extends ObjectOutputStream {
        RmiObjectStream(OutputStream out) throws IOException {
            super(out);
        }

        @Override
        protected void annotateClass(Class<?> cl) throws IOException {
            writeObject(null);
        }
    }
}
