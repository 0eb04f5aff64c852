// Shared by the node tests of the JavaScript API: where the modules, the native helper and the
// golden files are (from the environment ctest sets, with defaults for a run by hand from the
// repository root), and small helpers.
'use strict';
const path = require('path');
const fs = require('fs');
const { execFileSync } = require('child_process');

const root = path.resolve(__dirname, '..', '..', '..');
const build = process.env.LOCKBOX_WEB_BUILD || path.join(root, 'build', 'wasm', 'web');
const packageDir = path.join(build, 'package');
const pageDir = path.join(build, 'page');
const nativeTool = process.env.LOCKBOX_WEB_NATIVE || path.join(root, 'build', 'release', 'tests', 'web', 'lockbox_web_native');

/** The package's API (lockbox-wasm.wasm). */
async function loadPackage() {
    return require(path.join(packageDir, 'lockbox.js')).load();
}

/** The samples module's API (the package's plus scenes and replay verification). */
async function loadSamples() {
    return require(path.join(packageDir, 'lockbox.js')).load({ module: path.join(pageDir, 'lockbox-samples-wasm.js') });
}

/** tests/golden/hashes.txt as {scene: {step: '0x...'}}. */
function goldenHashes() {
    const table = {};
    for (const line of fs.readFileSync(path.join(root, 'tests', 'golden', 'hashes.txt'), 'utf8').split('\n')) {
        if (!line.trim() || line.startsWith('#')) continue;
        const [name, ...fields] = line.trim().split(/\s+/);
        table[name] = {};
        for (const f of fields) {
            const [key, value] = f.split('=');
            table[name][Number(key.replace('step', ''))] = value;
        }
    }
    return table;
}

/** Runs the native helper (tests/web/native) and returns its output line. */
function native(...args) {
    if (!fs.existsSync(nativeTool))
        throw new Error(`native helper ${nativeTool} not found: build the release preset first (or set LOCKBOX_WEB_NATIVE)`);
    return execFileSync(nativeTool, args.map(String), { encoding: 'utf8' }).trim();
}

/** A fresh temporary directory, removed when the process exits. */
const temporaries = [];
function tempDir() {
    const dir = fs.mkdtempSync(path.join(require('os').tmpdir(), 'lockbox-web-'));
    if (temporaries.length === 0) {
        process.on('exit', () => {
            for (const d of temporaries) fs.rmSync(d, { recursive: true, force: true });
        });
    }
    temporaries.push(dir);
    return dir;
}

module.exports = { root, packageDir, pageDir, loadPackage, loadSamples, goldenHashes, native, tempDir };
