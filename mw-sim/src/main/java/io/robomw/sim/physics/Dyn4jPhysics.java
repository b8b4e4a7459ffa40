package io.robomw.sim.physics;

import org.dyn4j.dynamics.Body;
import org.dyn4j.dynamics.Settings;
import org.dyn4j.dynamics.contact.ContactConstraint;
import org.dyn4j.dynamics.contact.SolvedContact;
import org.dyn4j.geometry.Geometry;
import org.dyn4j.geometry.MassType;
import org.dyn4j.geometry.Transform;
import org.dyn4j.geometry.Vector2;
import org.dyn4j.world.World;

import java.util.ArrayList;
import java.util.List;

/**
 * The dyn4j library's rigid-body world: general shapes, islands, at-rest detection; steps on the
 * stepping thread alone. The simulator's first engine and its default.
 */
public final class Dyn4jPhysics implements Physics {

    private final World<Body> world = new World<>();
    private final List<Body> bodies = new ArrayList<>();

    /**
     * @param stepSeconds the fixed step the world will be stepped with
     */
    public Dyn4jPhysics(double stepSeconds) {
        world.setGravity(World.ZERO_GRAVITY);
        Settings settings = world.getSettings();
        settings.setStepFrequency(stepSeconds);
        settings.setAtRestDetectionEnabled(true);
        // Robots move at most a few centimetres per step and walls are thick: continuous collision
        // detection (tunnelling prevention) buys nothing and costs a pass over every moving body.
        settings.setContinuousDetectionMode(org.dyn4j.dynamics.ContinuousDetectionMode.NONE);
    }

    @Override
    public void addStaticBox(double x, double y, double width, double height, double angle) {
        Body body = new Body();
        body.addFixture(Geometry.createRectangle(width, height));
        body.rotate(angle);
        body.translate(x, y);
        body.setMass(MassType.INFINITE);
        world.addBody(body);
    }

    @Override
    public void addStaticCircle(double x, double y, double radius) {
        Body body = new Body();
        body.addFixture(Geometry.createCircle(radius));
        body.translate(x, y);
        body.setMass(MassType.INFINITE);
        world.addBody(body);
    }

    @Override
    public void addStaticPolygon(double[][] points) {
        Vector2[] v = new Vector2[points.length];
        for (int i = 0; i < v.length; i++) {
            v[i] = new Vector2(points[i][0], points[i][1]);
        }
        Body body = new Body();
        body.addFixture(Geometry.createPolygon(v));
        body.setMass(MassType.INFINITE);
        world.addBody(body);
    }

    @Override
    public int addBody(double length, double width, double mass, double friction, double x, double y, double heading) {
        Body body = new Body();
        body.addFixture(Geometry.createRectangle(length, width), mass / (length * width), friction, 0);
        body.setMass(MassType.NORMAL);
        body.rotate(heading);
        body.translate(x, y);
        body.setAtRestDetectionEnabled(true);
        world.addBody(body);
        bodies.add(body);
        return bodies.size() - 1;
    }

    @Override
    public void step(double dt) {
        world.step(1, dt);
    }

    @Override
    public double x(int body) {
        return bodies.get(body).getTransform().getTranslationX();
    }

    @Override
    public double y(int body) {
        return bodies.get(body).getTransform().getTranslationY();
    }

    @Override
    public double cos(int body) {
        return bodies.get(body).getTransform().getCost();
    }

    @Override
    public double sin(int body) {
        return bodies.get(body).getTransform().getSint();
    }

    @Override
    public double vx(int body) {
        return bodies.get(body).getLinearVelocity().x;
    }

    @Override
    public double vy(int body) {
        return bodies.get(body).getLinearVelocity().y;
    }

    @Override
    public boolean atRest(int body) {
        return bodies.get(body).isAtRest();
    }

    @Override
    public void drive(int index, double v, double w) {
        Body body = bodies.get(index);
        if (v == 0 && w == 0 && body.isAtRest()) {
            return;
        }
        Transform t = body.getTransform();
        body.setLinearVelocity(v * t.getCost(), v * t.getSint());
        body.setAngularVelocity(w);
        if (v != 0 || w != 0) {
            body.setAtRest(false);
        }
    }

    @Override
    public void setVelocity(int index, double vx, double vy, double w) {
        Body body = bodies.get(index);
        if (vx == 0 && vy == 0 && w == 0 && body.isAtRest()) {
            return;
        }
        body.setLinearVelocity(vx, vy);
        body.setAngularVelocity(w);
        if (vx != 0 || vy != 0 || w != 0) {
            body.setAtRest(false);
        }
    }

    @Override
    public void contacts(int index, ContactSink sink) {
        Body body = bodies.get(index);
        for (ContactConstraint<Body> c : world.getContacts(body)) {
            if (!c.isEnabled() || c.isSensor()) {
                continue;
            }
            for (SolvedContact contact : c.getContacts()) {
                Vector2 local = body.getTransform().getInverseTransformed(contact.getPoint());
                sink.point(local.x, local.y);
            }
        }
    }

    /** @return the dyn4j world, for the benchmark's naive ray casts */
    public World<Body> world() {
        return world;
    }

    /**
     * @param index a body's number
     * @return its dyn4j body
     */
    public Body body(int index) {
        return bodies.get(index);
    }
}
