// The samples module (the web page's): the scene library in WebAssembly gives the golden
// hashes, and replays verify in it as `lockbox_replay verify` does, naming the frame, stage,
// body and field of a divergence.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const fs = require('fs');
const path = require('path');
const { root, loadSamples, goldenHashes, native, tempDir } = require('./common');

const golden = goldenHashes();

test('every light library scene reaches its golden hashes at steps 1 and 60', async () => {
    const lb = await loadSamples();
    const names = lb.scenes.names();
    assert.ok(names.includes('pyramid20') && names.includes('car') && names.includes('rain'));
    for (const name of names) {
        const scene = lb.scenes.create(name);
        if (scene.info.heavy) {
            scene.destroy();
            continue;
        }
        for (let step = 1; step <= 60; ++step) {
            scene.step();
            if (step === 1 || step === 60) assert.equal(scene.world.hashHex(), golden[name][step], `${name} step ${step}`);
        }
        scene.destroy();
    }
    assert.throws(() => lb.scenes.create('no_such_scene'), /no scene named/);
});

test('rain (spawns bodies every few steps) reaches its golden hash at step 120', async () => {
    const lb = await loadSamples();
    const scene = lb.scenes.create('rain');
    for (let step = 1; step <= 120; ++step) scene.step();
    assert.equal(scene.world.hashHex(), golden.rain[120]);
    scene.destroy();
});

test('the committed replays verify', async () => {
    const lb = await loadSamples();
    const dir = path.join(root, 'tests', 'golden', 'replays');
    const files = fs.readdirSync(dir).filter((f) => f.endsWith('.lbr'));
    assert.ok(files.length >= 4);
    for (const f of files) {
        const r = lb.replay.verify(new Uint8Array(fs.readFileSync(path.join(dir, f))));
        assert.equal(r.ok, true, `${f}: ${r.error || r.report}`);
        assert.equal(r.frames, r.frameCount);
        assert.match(r.message, new RegExp(`^OK frames=${r.frames} hash=${r.finalHash}$`));
    }
});

test('a divergent replay: first frame, stage, body and field', async () => {
    const lb = await loadSamples();
    const file = path.join(tempDir(), 'divergent.lbr');
    const frame = Number(native('record-divergent', 'car', 240, 100, file));
    const r = lb.replay.verify(new Uint8Array(fs.readFileSync(file)));
    assert.equal(r.ok, false);
    assert.equal(r.firstBadFrame, frame);
    assert.match(r.message, new RegExp(`^DIVERGED at frame ${frame}: recorded 0x[0-9a-f]{16}, re-simulated 0x[0-9a-f]{16}$`));
    assert.ok(r.stage >= 0, r.report);
    assert.equal(r.keyframe, 120);
    assert.ok(r.body >= 0, r.report);
    assert.ok(r.fieldCount > 0, r.report);
    assert.equal(r.fields.length, r.fieldCount);
    assert.match(r.fields[0].recorded, /^-?\d+\.\d+ \(raw 0x[0-9a-f]{8}\)$/);
    assert.notEqual(r.fields[0].recorded, r.fields[0].resimulated);
    assert.match(r.report, /body {6}\d+/);
    assert.match(r.report, /field {5}\S+: A /);
});

test('files that are not replays are refused with the reason', async () => {
    const lb = await loadSamples();
    const r = lb.replay.verify(new Uint8Array([1, 2, 3, 4]));
    assert.equal(r.ok, false);
    assert.match(r.error, /truncated|magic/);
    const car = fs.readFileSync(path.join(root, 'tests', 'golden', 'replays', 'car.lbr'));
    const cut = new Uint8Array(car.subarray(0, 5000));
    assert.match(lb.replay.verify(cut).error, /truncated/);
});
