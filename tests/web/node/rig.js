// Every joint type and every shape type in one world, built with the JavaScript API; the
// native helper builds the same rig with the C++ API (tests/web/native/web_native.cpp,
// BuildRig) from the same decimal values, so equal hashes show that every definition field
// crosses the bindings intact.
'use strict';

function buildRig(lb, world) {
    const ground = world.createBody();
    ground.createFixture({ type: 'edge', v1: [-30, 0], v2: [30, 0] }, 0);
    ground.createFixture({
        shape: { type: 'chain', loop: true, vertices: [[-29, 1], [-27, 1], [-27, 3], [-29, 3]] },
        friction: 0.4,
    });
    const box = (x, y, hx, hy) => {
        const b = world.createBody({ type: 'dynamic', position: { x, y } });
        b.createFixture({ type: 'box', hx, hy }, 1);
        return b;
    };
    const circle = (x, y, radius) => {
        const b = world.createBody({ type: 'dynamic', position: { x, y } });
        b.createFixture({ shape: { type: 'circle', center: [0, 0], radius }, density: 2, restitution: 0.25 });
        return b;
    };

    const a = box(-20, 5, 0.5, 0.125);
    world.createJoint({
        type: 'revolute', bodyA: ground, bodyB: a, anchor: [-20.5, 5],
        enableLimit: true, lowerAngle: -0.75, upperAngle: 0.5, enableMotor: true, motorSpeed: 1.5, maxMotorTorque: 40,
    });
    const slider = box(-15, 4, 0.5, 0.5);
    const prismatic = world.createJoint({
        type: 'prismatic', bodyA: ground, bodyB: slider, anchor: [-15, 4], axis: [1, 1],
        enableLimit: true, lowerTranslation: -1, upperTranslation: 2.5, enableMotor: true, maxMotorForce: 100, motorSpeed: 0.75,
    });
    const wheel = circle(-12, 4, 0.75);
    const revolute = world.createJoint({ type: 'revolute', bodyA: ground, bodyB: wheel, anchor: [-12, 4] });
    world.createJoint({ type: 'gear', joint1: prismatic, joint2: revolute, ratio: 0.5 });

    const d1 = circle(-8, 6, 0.25);
    world.createJoint({ type: 'distance', bodyA: ground, bodyB: d1, anchorA: [-8, 9], anchorB: [-8, 6], frequencyHz: 3, dampingRatio: 0.2 });
    const r1 = box(-5, 7, 0.25, 0.25);
    world.createJoint({ type: 'rope', bodyA: ground, bodyB: r1, localAnchorA: [-5, 10], localAnchorB: [0, 0.25], maxLength: 3.5 });

    const p1 = box(-1, 5, 0.5, 0.5);
    const p2 = box(2, 6, 0.5, 0.5);
    world.createJoint({
        type: 'pulley', bodyA: p1, bodyB: p2, groundAnchorA: [-1, 10], groundAnchorB: [2, 10], anchorA: [-1, 5.5], anchorB: [2, 6.5], ratio: 1.5,
    });

    const w1 = box(6, 2, 1, 0.25);
    const w2 = world.createBody({ type: 'dynamic', position: [7, 2.5], angle: 0.3 });
    w2.createFixture({ type: 'polygon', vertices: [[0, 0], [1, 0], [0, 0.75]] }, 1.5);
    world.createJoint({ type: 'weld', bodyA: w1, bodyB: w2, anchor: [7, 2.25], frequencyHz: 4, dampingRatio: 0.5 });
    const f1 = box(10, 0.5, 0.5, 0.5);
    world.createJoint({ type: 'friction', bodyA: ground, bodyB: f1, anchor: [10, 0.5], maxForce: 3, maxTorque: 1 });
    f1.applyLinearImpulse([4, 0], f1.getWorldCenter());

    const chassis = box(14, 2, 1, 0.25);
    const tyre = circle(14.5, 1.25, 0.4);
    world.createJoint({
        type: 'wheel', bodyA: chassis, bodyB: tyre, anchor: [14.5, 1.25], axis: [0, 1],
        enableMotor: true, maxMotorTorque: 10, motorSpeed: -4, frequencyHz: 5, dampingRatio: 0.7,
    });

    const m1 = box(20, 3, 0.5, 0.5);
    const mouse = world.createJoint({ type: 'mouse', bodyA: ground, bodyB: m1, target: [20, 3], maxForce: 500, frequencyHz: 2, dampingRatio: 0.5 });
    mouse.setTarget([22, 6]);
}

module.exports = { buildRig };
