package io.robomw.agents.host.code;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.net.URL;
import java.util.HashMap;
import java.util.Map;
import java.util.zip.ZipEntry;
import java.util.zip.ZipInputStream;

/**
 * Loads the classes of one {@link CodeArchive}, child-first: a class the archive holds is defined
 * from the archive even if the host's own class path has one of the same name, so two versions of
 * an agent class live side by side in two loaders. The JDK, the Instruction Layer API
 * ({@code io.robomw.api}) and SLF4J always come from the parent, so agents and hosts share
 * {@code Agent}, {@code Robot} and the rest. Classes the archive lacks come from the parent.
 */
public final class ArchiveClassLoader extends ClassLoader {

    private static final String[] PARENT_FIRST = {"java.", "javax.", "jdk.", "sun.", "com.sun.", "io.robomw.api.", "org.slf4j."};

    static {
        registerAsParallelCapable();
    }

    private final CodeArchive archive;
    private final Map<String, byte[]> entries;
    /** Classes already resolved by name through this loader, for {@link #resolve}. */
    private final Map<String, Class<?>> resolved = new java.util.concurrent.ConcurrentHashMap<>();

    /**
     * @param archive the archive
     * @param parent  the host's class loader
     * @throws IOException if the archive is not a readable zip
     */
    public ArchiveClassLoader(CodeArchive archive, ClassLoader parent) throws IOException {
        super("agent-archive-" + archive.digest().hex().substring(0, 12), parent);
        this.archive = archive;
        this.entries = read(archive.bytes());
    }

    /** @return the archive this loader loads from */
    public CodeArchive archive() {
        return archive;
    }

    /**
     * @param className a binary class name
     * @return whether the archive holds that class
     */
    public boolean holds(String className) {
        return entries.containsKey(className.replace('.', '/') + ".class");
    }

    /**
     * {@code Class.forName(name, false, this)}, remembered: reading an agent's state resolves the
     * same few classes on every hop, and each lookup through the loaders (locks, native lookups,
     * the parent's) cost about a microsecond. A loader always answers the same class for a name
     * once it has answered, so the remembered answer is the answer.
     *
     * @param name a binary class name
     * @return the class
     * @throws ClassNotFoundException if neither the archive nor the parent has it
     */
    public Class<?> resolve(String name) throws ClassNotFoundException {
        Class<?> c = resolved.get(name);
        if (c == null) {
            c = Class.forName(name, false, this);
            resolved.put(name, c);
        }
        return c;
    }

    @Override
    protected Class<?> loadClass(String name, boolean resolve) throws ClassNotFoundException {
        for (String prefix : PARENT_FIRST) {
            if (name.startsWith(prefix)) {
                return super.loadClass(name, resolve);
            }
        }
        synchronized (getClassLoadingLock(name)) {
            Class<?> c = findLoadedClass(name);
            if (c == null) {
                byte[] code = entries.get(name.replace('.', '/') + ".class");
                c = code != null ? defineClass(name, code, 0, code.length) : getParent().loadClass(name);
            }
            if (resolve) {
                resolveClass(c);
            }
            return c;
        }
    }

    @Override
    public InputStream getResourceAsStream(String name) {
        byte[] data = entries.get(name);
        return data != null ? new ByteArrayInputStream(data) : super.getResourceAsStream(name);
    }

    @Override
    protected URL findResource(String name) {
        return null; // archive resources are served by getResourceAsStream
    }

    private static Map<String, byte[]> read(byte[] jar) throws IOException {
        Map<String, byte[]> out = new HashMap<>();
        try (ZipInputStream zip = new ZipInputStream(new ByteArrayInputStream(jar))) {
            ZipEntry e;
            while ((e = zip.getNextEntry()) != null) {
                if (!e.isDirectory()) {
                    ByteArrayOutputStream data = new ByteArrayOutputStream();
                    zip.transferTo(data);
                    out.put(e.getName(), data.toByteArray());
                }
            }
        }
        if (out.isEmpty()) {
            throw new IOException("the archive holds no entries (not a jar?)");
        }
        return out;
    }
}
