// The web page in a real browser: serves build/<preset>/web/page on 127.0.0.1 with python3's
// http.server, opens it in headless Chromium driven over the DevTools protocol (a pipe, so no
// port and no WebSocket library), runs pyramid20 for 600 steps and compares the hash the page
// shows with tests/golden/hashes.txt, opens committed replays through the page's file input
// and checks its verdict (OK, and the frame, body and field of a divergent one), runs a
// second scene picked from the list, and takes screenshots whose canvas must not be blank.
//
// Usage: node tests/web/page_test.js   (environment: LOCKBOX_WEB_BUILD, LOCKBOX_WEB_NATIVE,
// LOCKBOX_WEB_SCREENSHOTS = directory for the PNGs, CHROMIUM = the browser)
'use strict';
const { spawn } = require('child_process');
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');
const { root, pageDir, goldenHashes, native, tempDir } = require('./node/common');

const shots = process.env.LOCKBOX_WEB_SCREENSHOTS || path.join(pageDir, '..', 'screenshots');
const chromium = process.env.CHROMIUM || 'chromium';

function fail(message) {
    throw new Error(message);
}

// python3 -m http.server on a free port of 127.0.0.1; resolves to {port, stop}.
function serve(dir) {
    return new Promise((resolve, reject) => {
        const server = spawn('python3', ['-u', '-m', 'http.server', '0', '--bind', '127.0.0.1', '--directory', dir], {
            stdio: ['ignore', 'pipe', 'pipe'],
        });
        let text = '';
        const timer = setTimeout(() => reject(new Error('http.server did not start')), 20000);
        server.stdout.on('data', (chunk) => {
            text += chunk;
            const m = /port (\d+)/.exec(text);
            if (m) {
                clearTimeout(timer);
                resolve({ port: Number(m[1]), stop: () => server.kill() });
            }
        });
        server.stderr.resume();
        server.on('exit', (code) => reject(new Error(`http.server exited (${code})`)));
    });
}

// Headless Chromium with the DevTools protocol on fds 3 (commands) and 4 (replies, events).
// Chromium refuses to run as root with its sandbox: --no-sandbox, and everything that would
// reach the network off.
function launch(profile) {
    const args = [
        '--headless',
        '--no-sandbox',
        '--disable-gpu',
        '--disable-quic',
        '--no-first-run',
        '--no-default-browser-check',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
        '--disable-extensions',
        '--disable-breakpad',
        '--disable-crash-reporter',
        '--disable-dev-shm-usage',
        '--mute-audio',
        '--hide-scrollbars',
        '--window-size=1400,900',
        '--force-device-scale-factor=1',
        `--user-data-dir=${profile}`,
        '--remote-debugging-pipe',
        'about:blank',
    ];
    const browser = spawn(chromium, args, { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
    let log = '';
    browser.stderr.on('data', (c) => (log += c));
    const writer = browser.stdio[3];
    const reader = browser.stdio[4];
    let buffer = Buffer.alloc(0);
    let nextId = 1;
    const pending = new Map();
    reader.on('data', (chunk) => {
        buffer = Buffer.concat([buffer, chunk]);
        let end;
        while ((end = buffer.indexOf(0)) >= 0) {
            const message = JSON.parse(buffer.subarray(0, end).toString('utf8'));
            buffer = buffer.subarray(end + 1);
            if (message.id && pending.has(message.id)) {
                const { resolve, reject, method } = pending.get(message.id);
                pending.delete(message.id);
                if (message.error) reject(new Error(`${method}: ${message.error.message}`));
                else resolve(message.result);
            }
        }
    });
    browser.on('exit', (code) => {
        for (const { reject } of pending.values()) reject(new Error(`chromium exited (${code}): ${log.slice(-2000)}`));
        pending.clear();
    });
    const send = (method, params = {}, sessionId) =>
        new Promise((resolve, reject) => {
            const id = nextId++;
            pending.set(id, { resolve, reject, method });
            writer.write(JSON.stringify({ id, method, params, sessionId }) + '\0');
        });
    return { browser, send, log: () => log };
}

// A PNG decoded to RGBA rows (8-bit RGB or RGBA, no interlace: what Chromium writes).
function decodePng(png) {
    let at = 8;
    let width = 0;
    let height = 0;
    let channels = 0;
    const idat = [];
    while (at < png.length) {
        const length = png.readUInt32BE(at);
        const type = png.toString('latin1', at + 4, at + 8);
        const data = png.subarray(at + 8, at + 8 + length);
        if (type === 'IHDR') {
            width = data.readUInt32BE(0);
            height = data.readUInt32BE(4);
            if (data[8] !== 8 || data[12] !== 0) fail('unexpected PNG format');
            channels = { 2: 3, 6: 4 }[data[9]] || fail(`unexpected PNG colour type ${data[9]}`);
        } else if (type === 'IDAT') idat.push(data);
        at += 12 + length;
    }
    const raw = zlib.inflateSync(Buffer.concat(idat));
    const stride = width * channels;
    const pixels = Buffer.alloc(width * height * 4);
    let prev = Buffer.alloc(stride);
    for (let y = 0; y < height; ++y) {
        const filter = raw[y * (stride + 1)];
        const line = Buffer.from(raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1)));
        for (let i = 0; i < stride; ++i) {
            const a = i >= channels ? line[i - channels] : 0;
            const b = prev[i];
            const c = i >= channels ? prev[i - channels] : 0;
            let add = 0;
            if (filter === 1) add = a;
            else if (filter === 2) add = b;
            else if (filter === 3) add = (a + b) >> 1;
            else if (filter === 4) {
                const p = a + b - c;
                const pa = Math.abs(p - a);
                const pb = Math.abs(p - b);
                const pc = Math.abs(p - c);
                add = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            }
            line[i] = (line[i] + add) & 0xff;
        }
        for (let x = 0; x < width; ++x) {
            for (let k = 0; k < 4; ++k) pixels[(y * width + x) * 4 + k] = k < channels ? line[x * channels + k] : 255;
        }
        prev = line;
    }
    return { width, height, pixels };
}

// "Not blank": inside the canvas, at least 0.5 % of the pixels differ from its white
// background and at least 4 distinct colours appear (bodies, ground, outlines). A canvas
// that drew nothing, or filled itself with one colour, fails.
function checkNotBlank(png, rect) {
    const { width, pixels } = decodePng(png);
    let drawn = 0;
    let total = 0;
    const colours = new Set();
    for (let y = Math.ceil(rect.y) + 2; y < Math.floor(rect.y + rect.height) - 2; ++y) {
        for (let x = Math.ceil(rect.x) + 2; x < Math.floor(rect.x + rect.width) - 2; ++x) {
            const i = (y * width + x) * 4;
            const rgb = (pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2];
            ++total;
            if (rgb !== 0xffffff) ++drawn;
            if (colours.size < 1000) colours.add(rgb);
        }
    }
    const share = drawn / Math.max(total, 1);
    if (share < 0.005 || colours.size < 4)
        fail(`the canvas looks blank: ${(100 * share).toFixed(2)} % drawn, ${colours.size} colours`);
    return { share, colours: colours.size };
}

async function main() {
    const started = Date.now();
    const golden = goldenHashes();
    fs.mkdirSync(shots, { recursive: true });
    const work = tempDir();
    const divergent = path.join(work, 'car_divergent.lbr');
    const divergentFrame = Number(native('record-divergent', 'car', 240, 100, divergent));

    const server = await serve(pageDir);
    const { browser, send, log } = launch(path.join(work, 'profile'));
    const deadline = (ms) => Date.now() + ms;
    try {
        const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
        const { sessionId } = await send('Target.attachToTarget', { targetId, flatten: true });
        const call = (method, params) => send(method, params, sessionId);
        const evaluate = async (expression) => {
            const r = await call('Runtime.evaluate', { expression, returnByValue: true, awaitPromise: true });
            if (r.exceptionDetails) fail(`page error in ${expression}: ${r.exceptionDetails.text}`);
            return r.result.value;
        };
        const waitFor = async (expression, ms, what) => {
            const until = deadline(ms);
            for (;;) {
                const v = await evaluate(expression);
                if (v) return v;
                if (Date.now() > until) fail(`timed out waiting for ${what}; status: ${await evaluate("document.getElementById('status').textContent")}`);
                await new Promise((r) => setTimeout(r, 100));
            }
        };
        const text = (id) => evaluate(`document.getElementById('${id}').textContent`);
        const screenshot = async (name) => {
            const { data } = await call('Page.captureScreenshot', { format: 'png' });
            const png = Buffer.from(data, 'base64');
            fs.writeFileSync(path.join(shots, name), png);
            return png;
        };

        await call('Page.enable');
        await call('Runtime.enable');
        const url = `http://127.0.0.1:${server.port}/index.html?scene=pyramid20&pauseAt=600`;
        await call('Page.navigate', { url });
        const ready = await waitFor("document.body && document.body.dataset.ready", 60000, 'the module to load');
        if (ready !== '1') fail(`the page could not load lockbox: ${await text('status')}`);

        // pyramid20 for 600 steps through the page's own Run button and pause field.
        await evaluate("document.getElementById('run').click()");
        await waitFor("document.getElementById('steps').textContent === '600' && document.getElementById('run').textContent === 'Run'", 240000, 'step 600');
        const hash = await text('hash');
        if (hash !== golden.pyramid20[600]) fail(`pyramid20 step 600: the page shows ${hash}, tests/golden/hashes.txt has ${golden.pyramid20[600]}`);
        console.log(`page: pyramid20 step 600 hash ${hash} (golden), step time ${await text('stepTime')}`);
        const rect = await evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect(); return {x: r.x, y: r.y, width: r.width, height: r.height}; })()");
        const blank = checkNotBlank(await screenshot('web-page-pyramid20.png'), rect);
        console.log(`page: screenshot not blank (${(100 * blank.share).toFixed(1)} % of the canvas drawn, ${blank.colours} colours)`);

        // Another scene picked from the list: ragdolls (revolute joints) to its golden step 60.
        await evaluate("(() => { const s = document.getElementById('scene'); s.value = 'ragdolls'; s.dispatchEvent(new Event('change')); document.getElementById('pauseAt').value = '60'; document.getElementById('run').click(); })()");
        await waitFor("document.getElementById('steps').textContent === '60' && document.getElementById('run').textContent === 'Run'", 120000, 'ragdolls step 60');
        const ragdolls = await text('hash');
        if (ragdolls !== golden.ragdolls[60]) fail(`ragdolls step 60: the page shows ${ragdolls}, tests/golden/hashes.txt has ${golden.ragdolls[60]}`);
        const moving = checkNotBlank(await screenshot('web-page-ragdolls.png'), rect);
        console.log(`page: ragdolls step 60 hash ${ragdolls} (golden); screenshot not blank (${(100 * moving.share).toFixed(1)} %)`);

        // Replays, opened through the file input as a person would.
        const { root: doc } = await call('DOM.getDocument', { depth: 1 });
        const { nodeId } = await call('DOM.querySelector', { nodeId: doc.nodeId, selector: '#replayFile' });
        const open = async (file) => {
            await evaluate("document.getElementById('replayVerdict').textContent = ''");
            await call('DOM.setFileInputFiles', { nodeId, files: [file] });
            return waitFor("(() => { const t = document.getElementById('replayVerdict').textContent; return t && !t.startsWith('verifying') ? t : ''; })()", 120000, `the verdict on ${path.basename(file)}`);
        };
        const car = path.join(root, 'tests', 'golden', 'replays', 'car.lbr');
        const ok = await open(car);
        if (!/^car\.lbr: OK frames=240 hash=0x[0-9a-f]{16}$/.test(ok)) fail(`car.lbr: the page says '${ok}'`);
        console.log(`page: ${ok}`);
        const bad = await open(divergent);
        const expected = new RegExp(`^car_divergent\\.lbr: DIVERGED at frame ${divergentFrame}, body \\d+, field \\S+$`);
        if (!expected.test(bad)) fail(`divergent replay: the page says '${bad}'`);
        const report = await text('replayReport');
        if (!/field {5}\S+: A /.test(report)) fail(`divergent replay: no field in the report:\n${report}`);
        console.log(`page: ${bad}`);
        await screenshot('web-page-replay.png');
        console.log(`page test passed in ${((Date.now() - started) / 1000).toFixed(1)} s; screenshots in ${shots}`);
        await send('Browser.close').catch(() => {});
    } catch (e) {
        console.error(`chromium log (tail):\n${log().slice(-3000)}`);
        throw e;
    } finally {
        server.stop();
        // Let the browser finish writing its profile before the directory goes.
        if (browser.exitCode === null) {
            const exited = new Promise((resolve) => browser.once('exit', resolve));
            setTimeout(() => browser.kill(), 5000).unref();
            await exited;
        }
        // Helper processes may still be closing files in the profile: retry, then leave it.
        try {
            fs.rmSync(work, { recursive: true, force: true, maxRetries: 20, retryDelay: 250 });
        } catch (e) {
            console.warn(`page test: could not remove ${work}: ${e.message}`);
        }
    }
}

main().catch((e) => {
    console.error(`page test FAILED: ${e.message}`);
    process.exit(1);
});
