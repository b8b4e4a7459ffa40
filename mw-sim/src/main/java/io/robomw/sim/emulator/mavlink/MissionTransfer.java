package io.robomw.sim.emulator.mavlink;

import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.MissionResult;
import io.robomw.platform.mavlink.wire.Payload;

import java.util.ArrayList;
import java.util.List;
import java.util.function.Consumer;

/**
 * The vehicle's side of the mission protocol (mavlink.io/en/services/mission.html), for mission
 * type 0 (fences and rally points are answered MAV_MISSION_UNSUPPORTED):
 * <ul>
 *   <li><b>upload</b>: MISSION_COUNT from a ground station; this side asks for each item with
 *   MISSION_REQUEST_INT, again after {@value #RETRY_SECONDS} s without an answer (at most
 *   {@value #RETRIES} times, then the upload is dropped and MISSION_ACK OPERATION_CANCELLED
 *   sent); an item out of order is asked for again; the last one closes it with MISSION_ACK
 *   ACCEPTED and the mission replaces the old one;</li>
 *   <li><b>download</b>: MISSION_REQUEST_LIST is answered with MISSION_COUNT, each
 *   MISSION_REQUEST_INT (or the older MISSION_REQUEST) with MISSION_ITEM_INT;</li>
 *   <li>MISSION_CLEAR_ALL empties the mission; MISSION_SET_CURRENT chooses the item to go on
 *   from.</li>
 * </ul>
 * Every message is addressed to the ground station that started the exchange.
 *
 * <p>Not thread-safe: the simulation's thread.
 */
final class MissionTransfer {

    /** Seconds without an item before it is asked for again. */
    static final double RETRY_SECONDS = 1.5;
    /** How often it is asked for again before the upload is dropped. */
    static final int RETRIES = 5;
    /** The most items a mission may have. */
    static final int MAX_ITEMS = 1000;

    private final Autopilot autopilot;
    private final Consumer<Payload> out;
    private List<MissionItem> incoming;
    private int expected;
    private int count;
    private int partnerSystem;
    private int partnerComponent;
    private double askedAt;
    private int retries;

    MissionTransfer(Autopilot autopilot, Consumer<Payload> out) {
        this.autopilot = autopilot;
        this.out = out;
    }

    /**
     * @param f    a mission message
     * @param p    its fields
     * @param time now, simulated seconds
     * @return whether it was a mission message
     */
    boolean handle(Frame f, Payload p, double time) {
        if (f.is(Messages.MissionCount.MESSAGE)) {
            int type = (int) p.getLong(Messages.MissionCount.MISSION_TYPE);
            if (type != 0) {
                ack(f, type, MissionResult.UNSUPPORTED);
                return true;
            }
            int n = (int) p.getLong(Messages.MissionCount.COUNT);
            if (n > MAX_ITEMS) {
                ack(f, 0, MissionResult.NO_SPACE);
                return true;
            }
            if (n == 0) {
                autopilot.mission(List.of());
                incoming = null;
                ack(f, 0, MissionResult.ACCEPTED);
                return true;
            }
            incoming = new ArrayList<>();
            count = n;
            expected = 0;
            partnerSystem = f.systemId();
            partnerComponent = f.componentId();
            retries = 0;
            ask(time);
        } else if (f.is(Messages.MissionItemInt.MESSAGE)) {
            if (incoming == null || f.systemId() != partnerSystem || p.getLong(Messages.MissionItemInt.MISSION_TYPE) != 0) {
                return true;
            }
            int seq = (int) p.getLong(Messages.MissionItemInt.SEQ);
            if (seq != expected) {
                ask(time);
                return true;
            }
            incoming.add(new MissionItem(seq, (int) p.getLong(Messages.MissionItemInt.FRAME), (int) p.getLong(Messages.MissionItemInt.COMMAND),
                    (int) p.getLong(Messages.MissionItemInt.CURRENT), (int) p.getLong(Messages.MissionItemInt.AUTOCONTINUE),
                    p.getFloat(Messages.MissionItemInt.PARAM1), p.getFloat(Messages.MissionItemInt.PARAM2),
                    p.getFloat(Messages.MissionItemInt.PARAM3), p.getFloat(Messages.MissionItemInt.PARAM4),
                    (int) p.getLong(Messages.MissionItemInt.X), (int) p.getLong(Messages.MissionItemInt.Y), p.getFloat(Messages.MissionItemInt.Z)));
            expected++;
            retries = 0;
            if (expected == count) {
                autopilot.mission(incoming);
                incoming = null;
                ack(f, 0, MissionResult.ACCEPTED);
            } else {
                ask(time);
            }
        } else if (f.is(Messages.MissionRequestList.MESSAGE)) {
            int type = (int) p.getLong(Messages.MissionRequestList.MISSION_TYPE);
            out.accept(Payload.of(Messages.MissionCount.MESSAGE)
                    .set(Messages.MissionCount.TARGET_SYSTEM, f.systemId())
                    .set(Messages.MissionCount.TARGET_COMPONENT, f.componentId())
                    .set(Messages.MissionCount.COUNT, type == 0 ? autopilot.mission().size() : 0)
                    .set(Messages.MissionCount.MISSION_TYPE, type));
        } else if (f.is(Messages.MissionRequestInt.MESSAGE) || f.is(Messages.MissionRequest.MESSAGE)) {
            int seq = (int) (f.is(Messages.MissionRequestInt.MESSAGE) ? p.getLong(Messages.MissionRequestInt.SEQ)
                    : p.getLong(Messages.MissionRequest.SEQ));
            List<MissionItem> mission = autopilot.mission();
            if (seq < 0 || seq >= mission.size()) {
                ack(f, 0, MissionResult.INVALID_SEQUENCE);
                return true;
            }
            MissionItem i = mission.get(seq);
            out.accept(Payload.of(Messages.MissionItemInt.MESSAGE)
                    .set(Messages.MissionItemInt.TARGET_SYSTEM, f.systemId())
                    .set(Messages.MissionItemInt.TARGET_COMPONENT, f.componentId())
                    .set(Messages.MissionItemInt.SEQ, seq)
                    .set(Messages.MissionItemInt.FRAME, i.frame())
                    .set(Messages.MissionItemInt.COMMAND, i.command())
                    .set(Messages.MissionItemInt.CURRENT, seq == autopilot.currentItem() ? 1 : 0)
                    .set(Messages.MissionItemInt.AUTOCONTINUE, i.autocontinue())
                    .set(Messages.MissionItemInt.PARAM1, i.param1())
                    .set(Messages.MissionItemInt.PARAM2, i.param2())
                    .set(Messages.MissionItemInt.PARAM3, i.param3())
                    .set(Messages.MissionItemInt.PARAM4, i.param4())
                    .set(Messages.MissionItemInt.X, i.x())
                    .set(Messages.MissionItemInt.Y, i.y())
                    .set(Messages.MissionItemInt.Z, i.z()));
        } else if (f.is(Messages.MissionClearAll.MESSAGE)) {
            autopilot.mission(List.of());
            ack(f, (int) p.getLong(Messages.MissionClearAll.MISSION_TYPE), MissionResult.ACCEPTED);
        } else if (f.is(Messages.MissionSetCurrent.MESSAGE)) {
            autopilot.setCurrentItem((int) p.getLong(Messages.MissionSetCurrent.SEQ));
        } else {
            return f.is(Messages.MissionAck.MESSAGE);
        }
        return true;
    }

    /**
     * Asks again for an item that did not come, or drops the upload.
     *
     * @param time now
     */
    void step(double time) {
        if (incoming != null && time - askedAt > RETRY_SECONDS) {
            if (++retries > RETRIES) {
                incoming = null;
                out.accept(Payload.of(Messages.MissionAck.MESSAGE)
                        .set(Messages.MissionAck.TARGET_SYSTEM, partnerSystem)
                        .set(Messages.MissionAck.TARGET_COMPONENT, partnerComponent)
                        .set(Messages.MissionAck.TYPE, MissionResult.OPERATION_CANCELLED.code()));
                return;
            }
            ask(time);
        }
    }

    private void ask(double time) {
        askedAt = time;
        out.accept(Payload.of(Messages.MissionRequestInt.MESSAGE)
                .set(Messages.MissionRequestInt.TARGET_SYSTEM, partnerSystem)
                .set(Messages.MissionRequestInt.TARGET_COMPONENT, partnerComponent)
                .set(Messages.MissionRequestInt.SEQ, expected));
    }

    private void ack(Frame to, int type, MissionResult result) {
        out.accept(Payload.of(Messages.MissionAck.MESSAGE)
                .set(Messages.MissionAck.TARGET_SYSTEM, to.systemId())
                .set(Messages.MissionAck.TARGET_COMPONENT, to.componentId())
                .set(Messages.MissionAck.TYPE, result.code())
                .set(Messages.MissionAck.MISSION_TYPE, type));
    }
}
