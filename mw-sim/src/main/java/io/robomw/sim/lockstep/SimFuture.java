package io.robomw.sim.lockstep;

import io.robomw.api.RobotException;

import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * A future of the simulator: a program thread blocking on it tells the {@link Lockstep} that it
 * waits for simulated time. Futures derived from it ({@code thenApply}, {@code whenComplete}...)
 * are {@code SimFuture}s too, so the Configuration Layer's conversions keep the property. Once
 * the world's stepping thread has died ({@link Lockstep#fail}), a wait on one ends at once with
 * that failure.
 *
 * @param <T> the value type
 */
public final class SimFuture<T> extends CompletableFuture<T> {

    private final Lockstep lockstep;

    SimFuture(Lockstep lockstep) {
        this.lockstep = lockstep;
    }

    @Override
    public <U> CompletableFuture<U> newIncompleteFuture() {
        return new SimFuture<>(lockstep);
    }

    @Override
    public T get() throws InterruptedException, ExecutionException {
        if (isDone()) {
            return super.get();
        }
        checkCanWait();
        lockstep.blocking(this);
        try {
            return super.get();
        } finally {
            lockstep.woke(this);
        }
    }

    @Override
    public T get(long timeout, TimeUnit unit) throws InterruptedException, ExecutionException, TimeoutException {
        if (isDone()) {
            return super.get();
        }
        checkCanWait();
        lockstep.blocking(this);
        try {
            return super.get(timeout, unit);
        } finally {
            lockstep.woke(this);
        }
    }

    @Override
    public T join() {
        if (isDone()) {
            return super.join();
        }
        checkCanWait();
        lockstep.blocking(this);
        try {
            return super.join();
        } finally {
            lockstep.woke(this);
        }
    }

    private void checkCanWait() {
        if (!lockstep.canWait()) {
            throw new RobotException("waiting for a simulated robot, but nothing advances simulated time: call robots from a program given to "
                    + "Simulation.run(...), or start the simulation in real time (Simulation.startRealTime)");
        }
    }
}
