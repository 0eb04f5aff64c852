// Step time of library scenes in WebAssembly under node beside the native build, in the same
// run, and the sizes of the .wasm modules (docs/benchmarks.md, "In the browser").
//
// Each rep builds the scene and runs its default number of steps (rain: 1,000 steps, 2,000
// bodies by the end) once natively (tests/web/native, `time`) and once in the samples module
// under node, alternating, and records the mean step time of the run; the table gives the
// medians over the reps and their ratio. Both runs must end on the same state hash.
//
// Usage: node bench/web/step_time.js [--reps N] [--scenes a,b] [--out CSV]
//        (environment as tests/web/node/common.js: LOCKBOX_WEB_BUILD, LOCKBOX_WEB_NATIVE)
'use strict';
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');
const { packageDir, pageDir, loadSamples, native } = require('../../tests/web/node/common');

function option(name, fallback) {
    const i = process.argv.indexOf(name);
    return i > 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}

const median = (values) => [...values].sort((a, b) => a - b)[values.length >> 1];

async function main() {
    const reps = Number(option('--reps', '5'));
    const names = option('--scenes', 'pyramid20,rain,chain60').split(',');
    const out = option('--out', '');
    const lb = await loadSamples();
    const rows = [];
    for (const name of names) {
        const steps = lb.scenes.create(name).info.steps;
        const nativeMs = [];
        const wasmMs = [];
        let nativeHash = '';
        let wasmHash = '';
        for (let r = 0; r < reps; ++r) {
            const [ms, hash] = native('time', name, steps, 1).split(' ');
            nativeMs.push(Number(ms));
            nativeHash = hash;
            const scene = lb.scenes.create(name);
            const t0 = process.hrtime.bigint();
            for (let i = 0; i < steps; ++i) scene.step();
            const t1 = process.hrtime.bigint();
            wasmMs.push(Number(t1 - t0) / 1e6 / steps);
            wasmHash = scene.world.hashHex();
            scene.destroy();
        }
        if (nativeHash !== wasmHash) throw new Error(`${name}: native ended on ${nativeHash}, wasm on ${wasmHash}`);
        const row = { scene: name, steps, reps, native_ms: median(nativeMs), wasm_ms: median(wasmMs), hash: wasmHash };
        row.ratio = row.wasm_ms / row.native_ms;
        rows.push(row);
        console.log(`${name.padEnd(10)} ${String(steps).padStart(5)} steps  native ${row.native_ms.toFixed(3)} ms  ` +
                    `wasm (node ${process.versions.node}) ${row.wasm_ms.toFixed(3)} ms  ratio ${row.ratio.toFixed(2)}  ${row.hash}`);
    }
    for (const file of [path.join(packageDir, 'lockbox-wasm.wasm'), path.join(pageDir, 'lockbox-samples-wasm.wasm')]) {
        const bytes = fs.readFileSync(file);
        console.log(`${path.basename(file)}: ${bytes.length} bytes, ${zlib.gzipSync(bytes, { level: 9 }).length} gzipped`);
    }
    if (out) {
        const header = 'scene,steps,reps,native_ms_per_step,wasm_ms_per_step,wasm_over_native,final_hash,node';
        const lines = rows.map((r) => [r.scene, r.steps, r.reps, r.native_ms.toFixed(4), r.wasm_ms.toFixed(4), r.ratio.toFixed(3), r.hash, process.versions.node].join(','));
        fs.writeFileSync(out, [header, ...lines].join('\n') + '\n');
    }
}

main().catch((e) => {
    console.error(e.message);
    process.exit(1);
});
