// The lockbox web page: runs any library scene in a canvas through the JavaScript API, shows
// the step time and the state hash live, and verifies replay files in the browser.
//
// URL parameters (for links and the headless test): scene=NAME, vel=N, pos=N, hz=N,
// pauseAt=STEP, run=1.
'use strict';

(function () {
    const $ = (id) => document.getElementById(id);
    const canvas = $('view');
    const ctx = canvas.getContext('2d');
    const params = new URLSearchParams(location.search);

    let lb = null;
    let scene = null;
    let running = false;
    let stepTimes = [];
    const view = { x: 0, y: 10, scale: 12 }; // centre (m) and pixels per metre

    function setStatus(text) {
        $('status').textContent = text;
    }

    function intInput(id, min, max, fallback) {
        const v = Number($(id).value);
        return Number.isInteger(v) && v >= min && v <= max ? v : fallback;
    }

    // --- scene ----------------------------------------------------------------------------

    function loadScene(name) {
        if (scene) scene.destroy();
        scene = lb.scenes.create(name);
        stepTimes = [];
        $('vel').value = params.get('vel') || scene.info.velocityIterations;
        $('pos').value = params.get('pos') || scene.info.positionIterations;
        $('hz').value = params.get('hz') || scene.info.hz;
        fitView();
        showState();
        draw();
    }

    function stepOnce() {
        const hz = intInput('hz', 1, 1000, scene.info.hz);
        const vel = intInput('vel', 0, 100, scene.info.velocityIterations);
        const pos = intInput('pos', 0, 100, scene.info.positionIterations);
        const t0 = performance.now();
        scene.step(hz, vel, pos);
        stepTimes.push(performance.now() - t0);
        if (stepTimes.length > 60) stepTimes.shift();
    }

    function showState() {
        $('steps').textContent = String(scene.stepCount);
        $('hash').textContent = scene.world.hashHex();
        $('bodies').textContent = String(scene.world.getBodyCount());
        $('contacts').textContent = String(scene.world.getContactCount());
        if (stepTimes.length) {
            const last = stepTimes[stepTimes.length - 1];
            const mean = stepTimes.reduce((a, b) => a + b, 0) / stepTimes.length;
            $('stepTime').textContent = `${last.toFixed(2)} ms (mean of ${stepTimes.length}: ${mean.toFixed(2)} ms)`;
        } else {
            $('stepTime').textContent = '–';
        }
    }

    function setRunning(flag) {
        running = flag;
        $('run').textContent = running ? 'Pause' : 'Run';
        if (running) {
            lastFrame = performance.now();
            owed = 0;
            requestAnimationFrame(frame);
        }
    }

    // Steps as many times as the scene's Hz asks for the time elapsed (at most 4 per frame),
    // then draws.
    let lastFrame = 0;
    let owed = 0;
    function frame(now) {
        if (!running) return;
        const hz = intInput('hz', 1, 1000, scene.info.hz);
        owed = Math.min(owed + ((now - lastFrame) / 1000) * hz, 4);
        lastFrame = now;
        const pauseAt = intInput('pauseAt', 0, 1e9, 0);
        let steps = Math.max(1, Math.floor(owed));
        owed -= steps;
        while (steps-- > 0) {
            if (pauseAt > 0 && scene.stepCount >= pauseAt) break;
            stepOnce();
        }
        showState();
        draw();
        if (pauseAt > 0 && scene.stepCount >= pauseAt) {
            setRunning(false);
            setStatus(`paused at step ${scene.stepCount}`);
            return;
        }
        requestAnimationFrame(frame);
    }

    // --- drawing --------------------------------------------------------------------------

    const toX = (raw) => (raw / 65536 - view.x) * view.scale + canvas.width / 2;
    const toY = (raw) => canvas.height / 2 - (raw / 65536 - view.y) * view.scale;

    function colours(bodyType, flags) {
        if (flags & 2) return ['rgba(80, 160, 220, 0.15)', '#3a8fd0'];
        if (bodyType === 0) return ['#d9dcd3', '#6e7466'];
        if (bodyType === 1) return ['#cfe8d2', '#3f8f4f'];
        return flags & 1 ? ['#f2c38b', '#b8661a'] : ['#d8d0c6', '#8f8578'];
    }

    // The records of World.debugDraw (web/src/QueryApi.cpp): per fixture its shape, body and
    // points; per joint its anchors.
    function draw() {
        const d = scene.world.debugDraw();
        ctx.clearRect(0, 0, canvas.width, canvas.height);
        ctx.lineWidth = 1;
        let i = 0;
        while (i < d.length) {
            const kind = d[i];
            if (kind >= 10) {
                ctx.strokeStyle = '#1d8a8a';
                ctx.beginPath();
                ctx.moveTo(toX(d[i + 1]), toY(d[i + 2]));
                ctx.lineTo(toX(d[i + 3]), toY(d[i + 4]));
                ctx.stroke();
                i += 5;
                continue;
            }
            const [fill, stroke] = colours(d[i + 2], d[i + 3]);
            const n = d[i + 4];
            const at = i + 5;
            ctx.fillStyle = fill;
            ctx.strokeStyle = stroke;
            ctx.beginPath();
            if (kind === 0) {
                const cx = toX(d[at]);
                const cy = toY(d[at + 1]);
                const r = (d[at + 2] / 65536) * view.scale;
                ctx.arc(cx, cy, Math.max(r, 0.5), 0, 2 * Math.PI);
                ctx.fill();
                ctx.moveTo(cx, cy);
                ctx.lineTo(toX(d[at + 3]), toY(d[at + 4]));
                ctx.stroke();
                i = at + 5;
                continue;
            }
            for (let k = 0; k < n; ++k) {
                const x = toX(d[at + 2 * k]);
                const y = toY(d[at + 2 * k + 1]);
                if (k === 0) ctx.moveTo(x, y);
                else ctx.lineTo(x, y);
            }
            if (kind === 2) {
                ctx.closePath();
                ctx.fill();
            }
            ctx.stroke();
            i = at + 2 * n;
        }
    }

    // Centres the view on the scene's geometry (at most 60 m wide; long grounds are clipped).
    function fitView() {
        const d = scene.world.debugDraw();
        let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
        const grow = (x, y) => {
            minX = Math.min(minX, x / 65536);
            maxX = Math.max(maxX, x / 65536);
            minY = Math.min(minY, y / 65536);
            maxY = Math.max(maxY, y / 65536);
        };
        let i = 0;
        while (i < d.length) {
            if (d[i] >= 10) {
                grow(d[i + 1], d[i + 2]);
                i += 5;
                continue;
            }
            const n = d[i + 4];
            for (let k = 0; k < n; ++k) grow(d[i + 5 + 2 * k], d[i + 6 + 2 * k]);
            i += 5 + 2 * n + (d[i] === 0 ? 3 : 0);
        }
        if (!Number.isFinite(minX)) return;
        const width = Math.min(Math.max(maxX - minX, 4), 60);
        const height = Math.min(Math.max(maxY - minY, 4), 60);
        view.x = Math.max(minX, Math.min(maxX, (minX + maxX) / 2));
        view.y = (minY + maxY) / 2;
        view.scale = 0.9 * Math.min(canvas.width / width, canvas.height / height);
    }

    // Pan with the mouse, zoom with the wheel around the cursor.
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => {
        drag = { x: e.clientX, y: e.clientY };
        canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointermove', (e) => {
        if (!drag) return;
        view.x -= (e.clientX - drag.x) / view.scale;
        view.y += (e.clientY - drag.y) / view.scale;
        drag = { x: e.clientX, y: e.clientY };
        if (!running) draw();
    });
    canvas.addEventListener('pointerup', () => (drag = null));
    canvas.addEventListener('wheel', (e) => {
        e.preventDefault();
        const rect = canvas.getBoundingClientRect();
        const mx = ((e.clientX - rect.left) * canvas.width) / rect.width - canvas.width / 2;
        const my = canvas.height / 2 - ((e.clientY - rect.top) * canvas.height) / rect.height;
        const before = { x: view.x + mx / view.scale, y: view.y + my / view.scale };
        view.scale = Math.min(Math.max(view.scale * Math.exp(-e.deltaY * 0.0015), 0.5), 2000);
        view.x = before.x - mx / view.scale;
        view.y = before.y - my / view.scale;
        if (!running) draw();
    }, { passive: false });

    // --- replays --------------------------------------------------------------------------

    async function verifyReplay(file) {
        const verdict = $('replayVerdict');
        verdict.className = 'verdict';
        verdict.textContent = `verifying ${file.name}…`;
        $('replayReport').textContent = '';
        const bytes = new Uint8Array(await file.arrayBuffer());
        const t0 = performance.now();
        const r = lb.replay.verify(bytes);
        const ms = performance.now() - t0;
        if (r.error) {
            verdict.className = 'verdict bad';
            verdict.textContent = `${file.name}: ${r.error}`;
            return;
        }
        if (r.ok) {
            verdict.className = 'verdict ok';
            verdict.textContent = `${file.name}: ${r.message}`;
        } else {
            verdict.className = 'verdict bad';
            let text = `${file.name}: DIVERGED at frame ${r.firstBadFrame}`;
            if (r.body >= 0) text += `, body ${r.body}`;
            if (r.fields.length) text += `, field ${r.fields[0].field}`;
            verdict.textContent = text;
        }
        $('replayReport').textContent = `${r.report}verified ${r.frames} frames in ${ms.toFixed(0)} ms in this browser`;
    }

    // --- start ----------------------------------------------------------------------------

    lockbox
        .load()
        .then((api) => {
            lb = api;
            const select = $('scene');
            for (const name of lb.scenes.names()) {
                const option = document.createElement('option');
                option.value = option.textContent = name;
                select.appendChild(option);
            }
            const wanted = params.get('scene');
            select.value = wanted && lb.scenes.names().includes(wanted) ? wanted : 'pyramid20';
            if (params.get('pauseAt')) $('pauseAt').value = params.get('pauseAt');
            loadScene(select.value);
            select.addEventListener('change', () => {
                setRunning(false);
                loadScene(select.value);
            });
            $('run').addEventListener('click', () => setRunning(!running));
            $('step').addEventListener('click', () => {
                setRunning(false);
                stepOnce();
                showState();
                draw();
            });
            $('restart').addEventListener('click', () => {
                setRunning(false);
                loadScene(select.value);
                setStatus('restarted');
            });
            $('fit').addEventListener('click', () => {
                fitView();
                draw();
            });
            $('replayFile').addEventListener('change', (e) => {
                if (e.target.files.length) verifyReplay(e.target.files[0]);
            });
            setStatus('ready');
            document.body.dataset.ready = '1';
            if (params.get('run') === '1') setRunning(true);
        })
        .catch((e) => {
            setStatus(`could not load lockbox: ${e.message}`);
            document.body.dataset.ready = 'error';
        });
})();
