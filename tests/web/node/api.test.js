// The JavaScript API under node: scenes built through it reach the native scene library's
// hashes, every joint and shape type crosses the bindings intact, snapshots cross between
// node and a native world both ways, and events, queries and errors behave.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('fs');
const path = require('path');
const { loadPackage, goldenHashes, native, tempDir } = require('./common');
const { buildPyramid20, buildCar } = require('./scenes');
const { buildRig } = require('./rig');

const golden = goldenHashes();

async function world(build) {
    const lb = await loadPackage();
    const w = new lb.World({ gravity: { x: 0, y: -10 } });
    build(lb, w);
    return { lb, w };
}

for (const [name, build] of [['pyramid20', buildPyramid20], ['car', buildCar]]) {
    test(`${name} built through the JavaScript API reaches the golden and native hashes`, async () => {
        const { lb, w } = await world(build);
        const dt = lb.ratio(1, 60);
        for (let step = 1; step <= 600; ++step) {
            w.step(dt, 8, 3);
            if (golden[name][step]) assert.equal(w.hashHex(), golden[name][step], `${name} step ${step}`);
        }
        assert.equal(w.hashHex(), native('scene-hash', name, 600));
        w.destroy();
    });
}

test('every joint and shape type: the JavaScript rig matches the native rig', async () => {
    const { lb, w } = await world(buildRig);
    assert.equal(w.getJointCount(), 11);
    for (let i = 0; i < 120; ++i) w.step(1 / 60, 8, 3);
    assert.equal(w.hashHex(), native('joint-rig', 120));
    assert.equal(w.getSaturationCount(), 0n);
    const types = w.joints().map((j) => j.getType()).sort();
    assert.deepEqual(types, ['distance', 'friction', 'gear', 'mouse', 'prismatic', 'pulley', 'revolute', 'revolute', 'rope', 'weld', 'wheel']);
    void lb;
    w.destroy();
});

test('a snapshot saved in node restores in a native world and steps on to the same hash', async () => {
    const { lb, w } = await world(buildCar);
    for (let i = 0; i < 60; ++i) w.step(lb.ratio(1, 60), 8, 3);
    const file = path.join(tempDir(), 'node.snapshot');
    fs.writeFileSync(file, w.save());
    for (let i = 0; i < 60; ++i) w.step(lb.ratio(1, 60), 8, 3);
    assert.equal(native('continue', file, 60), w.hashHex());
    assert.equal(w.hashHex(), golden.car[120] || native('scene-hash', 'car', 120));
    w.destroy();
});

test('a snapshot saved natively restores in node and steps on to the same hash', async () => {
    const lb = await loadPackage();
    const file = path.join(tempDir(), 'native.snapshot');
    const savedHash = native('save', 'ragdolls', 60, file);
    const w = new lb.World();
    assert.equal(w.restore(new Uint8Array(fs.readFileSync(file))), undefined);
    assert.equal(w.hashHex(), savedHash);
    for (let i = 0; i < 60; ++i) w.step(lb.ratio(1, 60), 8, 3);
    assert.equal(w.hashHex(), native('scene-hash', 'ragdolls', 120));
    // The bytes node saves are the bytes the native world saved.
    assert.deepEqual(Buffer.from(new lb.World().save()).length > 0, true);
    const again = new lb.World();
    again.restore(new Uint8Array(fs.readFileSync(file)));
    assert.deepEqual(Buffer.from(again.save()), fs.readFileSync(file));
    w.destroy();
    again.destroy();
});

test('restore refuses a damaged snapshot and leaves the world as it was', async () => {
    const { lb, w } = await world(buildPyramid20);
    for (let i = 0; i < 10; ++i) w.step(lb.ratio(1, 60));
    const image = w.save();
    const before = w.hash();
    const bad = image.slice();
    bad[bad.length >> 1] ^= 0xff;
    const message = w.restore(bad);
    assert.equal(typeof message, 'string');
    assert.ok(message.length > 0);
    assert.equal(w.hash(), before);
    assert.equal(typeof w.restore(new Uint8Array([1, 2, 3])), 'string');
    assert.equal(w.restore(image), undefined);
    assert.throws(() => w.restore([1, 2, 3]), TypeError);
    w.destroy();
});

test('contact events, AABB queries and ray casts', async () => {
    const lb = await loadPackage();
    const w = new lb.World();
    const ground = w.createBody();
    const floor = ground.createFixture({ type: 'edge', v1: [-10, 0], v2: [10, 0] }, 0);
    const ball = w.createBody({ type: 'dynamic', position: [0, 2] });
    const ballFixture = ball.createFixture({ shape: { type: 'circle', radius: 0.5 }, density: 1, restitution: 0.5 });
    const sensorBody = w.createBody({ position: [5, 0.5] });
    sensorBody.createFixture({ shape: { type: 'box', hx: 1, hy: 1 }, isSensor: true });
    let begins = 0;
    let ends = 0;
    for (let i = 0; i < 120; ++i) {
        w.step(1 / 60);
        for (const e of w.takeContactEvents()) {
            const ids = [e.fixtureA.id, e.fixtureB.id].sort();
            assert.deepEqual(ids, [floor.id, ballFixture.id].sort());
            if (e.begin) ++begins;
            else ++ends;
        }
    }
    assert.ok(begins >= 1, 'the ball touched the floor');
    assert.ok(ends >= 1, 'and bounced off it');
    const inBox = w.queryAABB([-1, -1], [1, 3]).map((f) => f.id).sort();
    assert.ok(inBox.includes(ballFixture.id) && inBox.includes(floor.id));
    const [hit] = w.rayCast([-3, 0.25], [3, 0.25]);
    assert.equal(w.rayCast([-3, 5], [3, 5]).length, 0);
    if (hit) assert.ok(hit.fraction > 0 && hit.fraction < 1);
    const down = w.rayCast([0, 10], [0, -1]);
    assert.equal(down.length, 1);
    assert.deepEqual(down[0].normal, { x: 0, y: 1 });
    assert.ok(w.rayCast([-20, 0.5], [20, 0.5], 'all').length >= 2);
    assert.equal(w.rayCast([-20, 0.5], [20, 0.5], 'any').length, 1);
    w.destroy();
});

test('bodies, fixtures and joints read back what was given', async () => {
    const lb = await loadPackage();
    const w = new lb.World({ gravity: [0, -9.5] });
    assert.deepEqual(w.getGravity(), { x: 0, y: lb.fromFixedRaw(lb.toFixedRaw(-9.5)) });
    const b = w.createBody({
        type: 'kinematic', position: [1.25, -2], angle: 0.5, linearVelocity: [3, 0], angularVelocity: -1,
        linearDamping: 0.1, angularDamping: 0.2, gravityScale: 2, bullet: true, userData: 42n,
    });
    const s = b.getState();
    assert.equal(s.type, 'kinematic');
    assert.deepEqual(s.position, { x: 1.25, y: -2 });
    assert.equal(s.raw[2], lb.toFixedRaw(0.5));
    assert.equal(s.bullet, true);
    assert.equal(s.userData, 42n);
    assert.equal(s.linearDamping, lb.toFixedRaw(0.1) / 65536);
    const f = b.createFixture({ shape: { type: 'box', hx: 1, hy: 0.5, center: [0.5, 0], angle: 0.25 }, density: 3, friction: 0.75, filter: { categoryBits: 2, maskBits: 5, groupIndex: -3 } });
    assert.equal(f.getType(), 'polygon');
    assert.deepEqual(f.getFilterData(), { categoryBits: 2, maskBits: 5, groupIndex: -3 });
    assert.equal(f.getFriction(), lb.toFixedRaw(0.75) / 65536);
    assert.equal(f.getBody().id, b.id);
    assert.deepEqual(b.fixtures().map((x) => x.id), [f.id]);
    b.setType('dynamic');
    assert.ok(b.getMass() > 0);
    const other = w.createBody({ type: 'dynamic', position: [3, -2] });
    other.createFixture({ type: 'circle', radius: 0.5 }, 1);
    const j = w.createJoint({ type: 'revolute', bodyA: b, bodyB: other, anchor: [2, -2], enableMotor: true, motorSpeed: 2, maxMotorTorque: 10 });
    assert.equal(j.getState().motorEnabled, true);
    j.setMotorSpeed(-1);
    j.enableLimit(true);
    j.setLimits(-0.5, 0.5);
    assert.equal(j.getState().limitEnabled, true);
    assert.deepEqual(j.getAnchorA(), { x: 2, y: -2 });
    assert.throws(() => j.setTarget([0, 0]), /no setting/);
    w.step(1 / 60);
    assert.ok(w.getContactCount() >= 0);
    assert.equal(w.bodies().length, 2);
    w.destroyBody(other);
    assert.equal(w.getJointCount(), 0);
    assert.equal(w.getBody(other.id), null);
    w.destroy();
});

test('bad definitions throw with the field named; the world is unchanged', async () => {
    const lb = await loadPackage();
    const w = new lb.World();
    const b = w.createBody({ type: 'dynamic' });
    const before = w.hash();
    assert.throws(() => w.createBody({ type: 'flying' }), /body.type/);
    assert.throws(() => w.createBody({ positon: [0, 0] }), /unknown field 'positon'/);
    assert.throws(() => w.createBody({ position: [0, NaN] }), /body.position\[1\]: NaN is not a finite number/);
    assert.throws(() => w.createBody({ angle: 1e6 }), /body.angle: 1000000 is out of range/);
    assert.throws(() => w.createBody({ position: { x: 1 } }), TypeError);
    assert.throws(() => b.createFixture({ shape: { type: 'polygon', vertices: [[0, 0], [1, 0], [2, 0]] } }), /polygon refused/);
    assert.throws(() => b.createFixture({ shape: { type: 'circle', radius: -1 } }), /circle refused/);
    assert.throws(() => b.createFixture({ shape: { type: 'blob' } }), /shape.type/);
    assert.throws(() => w.createJoint({ type: 'revolute', bodyA: b, bodyB: b, anchor: [0, 0] }), /same body/);
    assert.throws(() => w.createJoint({ type: 'spring' }), /unknown joint type/);
    assert.throws(() => w.createJoint({ type: 'weld', bodyA: b, bodyB: 7 }), /expected a Body/);
    assert.throws(() => w.step(-1 / 60), /negative time step/);
    assert.equal(w.hash(), before);
    w.destroy();
    assert.throws(() => w.step(1 / 60), /destroyed/);
});
