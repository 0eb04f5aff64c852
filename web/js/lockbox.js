/*
 * lockbox.js: the JavaScript API of lockbox (README.md). It loads the WebAssembly module made
 * by Emscripten (lockbox-wasm.js and .wasm) and wraps its C functions (web/src) in classes:
 * World, Body, Fixture, Joint, plus the scenes and replay verification when the module has
 * them (the samples module of the web page).
 *
 * Numbers. Every number given to lockbox becomes a Q16.16 `Fixed` (or, for the mouse joint's
 * maxForce, a Q32.32 `Wide`) through one conversion: the IEEE-754 bits of the JavaScript
 * number are read from a DataView and decoded in the module with integer arithmetic, rounded
 * to nearest with ties away from zero (web/src/NumberConversion.h). So 0.1 gives raw 6554 on
 * every engine and machine. A decimal string ('0.1') is parsed exactly by Fixed::Parse, and
 * lockbox.raw(n) passes a raw Q16.16 integer through unchanged. NaN, infinities and values
 * beyond +-32767.99998 are refused with a RangeError. Numbers read back are raw / 65536,
 * which a double holds exactly.
 *
 * Works as a CommonJS module (node: require('lockbox-wasm')) and as a plain script in a page,
 * after the loader's script (a global `lockbox`).
 */
(function (root, factory) {
    if (typeof module === 'object' && module.exports) module.exports = factory(true, root);
    else root.lockbox = factory(false, root);
})(typeof globalThis !== 'undefined' ? globalThis : this, function (isNode, root) {
    'use strict';

    const ONE = 65536;
    const MAX_RAW = 2147483647;

    /** A raw Q16.16 value, passed to lockbox unchanged (lockbox.raw). */
    class Raw {
        constructor(raw) {
            if (!Number.isInteger(raw) || raw < -MAX_RAW || raw > MAX_RAW)
                throw new RangeError(`raw Q16.16 value must be an integer in [-${MAX_RAW}, ${MAX_RAW}], got ${raw}`);
            this.raw = raw;
            Object.freeze(this);
        }
        /** The value in units (exact). */
        toNumber() {
            return this.raw / ONE;
        }
    }

    /** A raw Q32.32 value (BigInt), for the one Wide input (the mouse joint's maxForce). */
    class RawWide {
        constructor(raw) {
            const limit = (1n << 63n) - 1n;
            if (typeof raw !== 'bigint' || raw < -limit || raw > limit)
                throw new RangeError('raw Q32.32 value must be a BigInt in [-(2^63 - 1), 2^63 - 1]');
            this.raw = raw;
            Object.freeze(this);
        }
    }

    const BODY_TYPES = { static: 0, kinematic: 1, dynamic: 2 };
    const BODY_TYPE_NAMES = ['static', 'kinematic', 'dynamic'];
    const SHAPE_NAMES = ['circle', 'edge', 'polygon', 'chain'];
    const SHAPE_KINDS = { circle: 0, edge: 1, polygon: 2, box: 3, chain: 4 };
    const JOINT_TYPES = {
        revolute: 1,
        prismatic: 2,
        distance: 3,
        pulley: 4,
        mouse: 5,
        gear: 6,
        wheel: 7,
        weld: 8,
        friction: 9,
        rope: 10,
    };
    const JOINT_NAMES = ['unknown'].concat(Object.keys(JOINT_TYPES));

    // Definition tables: each field's name and kind, in the order web/src reads them (its
    // presence bit is the field's index). Fields left out keep lockbox's default.
    const BODY_FIELDS = [
        ['type', 'bodyType'],
        ['position', 'vec'],
        ['angle', 'fixed'],
        ['linearVelocity', 'vec'],
        ['angularVelocity', 'fixed'],
        ['linearDamping', 'fixed'],
        ['angularDamping', 'fixed'],
        ['allowSleep', 'bool'],
        ['awake', 'bool'],
        ['fixedRotation', 'bool'],
        ['bullet', 'bool'],
        ['active', 'bool'],
        ['gravityScale', 'fixed'],
        ['userData', 'u64'],
    ];
    const FIXTURE_FIELDS = [
        ['friction', 'fixed'],
        ['restitution', 'fixed'],
        ['density', 'fixed'],
        ['isSensor', 'bool'],
        ['categoryBits', 'int'],
        ['maskBits', 'int'],
        ['groupIndex', 'int'],
        ['userData', 'u64'],
    ];
    const SHAPE_FIELDS = {
        circle: [
            ['center', 'vec'],
            ['radius', 'fixed'],
        ],
        edge: [
            ['v1', 'vec'],
            ['v2', 'vec'],
            ['v0', 'vec'],
            ['v3', 'vec'],
        ],
        polygon: [
            ['vertices', 'points'],
            ['hull', 'bool'],
        ],
        box: [
            ['hx', 'fixed'],
            ['hy', 'fixed'],
            ['center', 'vec'],
            ['angle', 'fixed'],
        ],
        chain: [
            ['vertices', 'points'],
            ['loop', 'bool'],
            ['prevVertex', 'vec'],
            ['nextVertex', 'vec'],
        ],
    };
    const JOINT_HEADER = [
        ['bodyA', 'body'],
        ['bodyB', 'body'],
        ['collideConnected', 'bool'],
        ['userData', 'u64'],
    ];
    // Fields marked by the comments "init" call the definition's Initialize (the manual's
    // helper that computes local anchors, axis and reference angle from world values).
    const JOINT_FIELDS = {
        revolute: [
            ['anchor', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['referenceAngle', 'fixed'],
            ['enableLimit', 'bool'],
            ['lowerAngle', 'fixed'],
            ['upperAngle', 'fixed'],
            ['enableMotor', 'bool'],
            ['motorSpeed', 'fixed'],
            ['maxMotorTorque', 'fixed'],
        ],
        prismatic: [
            ['anchor', 'vec'], // init
            ['axis', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['localAxisA', 'vec'],
            ['referenceAngle', 'fixed'],
            ['enableLimit', 'bool'],
            ['lowerTranslation', 'fixed'],
            ['upperTranslation', 'fixed'],
            ['enableMotor', 'bool'],
            ['maxMotorForce', 'fixed'],
            ['motorSpeed', 'fixed'],
        ],
        distance: [
            ['anchorA', 'vec'], // init
            ['anchorB', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['length', 'fixed'],
            ['frequencyHz', 'fixed'],
            ['dampingRatio', 'fixed'],
        ],
        pulley: [
            ['groundAnchorA', 'vec'],
            ['groundAnchorB', 'vec'],
            ['anchorA', 'vec'], // init
            ['anchorB', 'vec'], // init
            ['ratio', 'fixed'],
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['lengthA', 'fixed'],
            ['lengthB', 'fixed'],
        ],
        mouse: [
            ['target', 'vec'],
            ['maxForce', 'wide'],
            ['frequencyHz', 'fixed'],
            ['dampingRatio', 'fixed'],
        ],
        gear: [
            ['joint1', 'joint'],
            ['joint2', 'joint'],
            ['ratio', 'fixed'],
        ],
        wheel: [
            ['anchor', 'vec'], // init
            ['axis', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['localAxisA', 'vec'],
            ['enableMotor', 'bool'],
            ['maxMotorTorque', 'fixed'],
            ['motorSpeed', 'fixed'],
            ['frequencyHz', 'fixed'],
            ['dampingRatio', 'fixed'],
        ],
        weld: [
            ['anchor', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['referenceAngle', 'fixed'],
            ['frequencyHz', 'fixed'],
            ['dampingRatio', 'fixed'],
        ],
        friction: [
            ['anchor', 'vec'], // init
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['maxForce', 'fixed'],
            ['maxTorque', 'fixed'],
        ],
        rope: [
            ['localAnchorA', 'vec'],
            ['localAnchorB', 'vec'],
            ['maxLength', 'fixed'],
        ],
    };

    /**
     * Loads the module and returns the API bound to it. Options: `module` (node: path of an
     * Emscripten loader, default the package's lockbox-wasm.js), `factory` (the loader's
     * factory function; in a page, default the global LockboxWasm), `wasmBinary` (the .wasm
     * bytes), `locateFile` (page: where the .wasm is).
     */
    async function load(options = {}) {
        let factory = options.factory;
        const moduleOptions = {};
        if (isNode) {
            const path = require('path');
            const fs = require('fs');
            const file = options.module ? path.resolve(options.module) : path.join(__dirname, 'lockbox-wasm.js');
            if (!factory) factory = require(file);
            // The .wasm is read here, so node never needs fetch() for a file path.
            moduleOptions.wasmBinary = options.wasmBinary || fs.readFileSync(file.replace(/\.js$/, '.wasm'));
        } else {
            if (!factory) factory = root.LockboxWasm;
            if (options.wasmBinary) moduleOptions.wasmBinary = options.wasmBinary;
            if (options.locateFile) moduleOptions.locateFile = options.locateFile;
        }
        if (typeof factory !== 'function') throw new Error('lockbox: the Emscripten loader (LockboxWasm) is not loaded');
        return bind(await factory(moduleOptions));
    }

    /** The API over one instance of the module. */
    function bind(m) {
        const utf8 = new TextDecoder();
        const encoder = new TextEncoder();
        const bits = new DataView(new ArrayBuffer(8));
        let scratchWords = 1 << 14;
        let scratch = m._lb_alloc(scratchWords * 4); // argument words
        const out = m._lb_alloc(64 * 4); // result words

        const heap32 = () => m.HEAP32;
        const heapU8 = () => m.HEAPU8;
        const cString = (ptr) => {
            const h = heapU8();
            let end = ptr;
            while (h[end] !== 0) ++end;
            return utf8.decode(h.subarray(ptr, end));
        };
        const lastError = () => cString(m._lb_last_error());
        const check = (result) => {
            if (result === -1) throw new Error(`lockbox: ${lastError()}`);
            return result;
        };
        const outWords = (n) => heap32().slice(out >> 2, (out >> 2) + n);
        const readWords = (ptr, n) => heap32().slice(ptr >> 2, (ptr >> 2) + n);
        // Copies `words` into the argument buffer (grown when needed); returns its address.
        const putWords = (words) => {
            if (words.length > scratchWords) {
                m._lb_free(scratch);
                scratchWords = words.length;
                scratch = m._lb_alloc(scratchWords * 4);
            }
            heap32().set(words, scratch >> 2);
            return scratch;
        };
        // Bytes into module memory for one call; the caller frees the address.
        const putBytes = (bytes) => {
            const ptr = m._lb_alloc(Math.max(1, bytes.length));
            heapU8().set(bytes, ptr);
            return ptr;
        };
        const withString = (text, fn) => {
            const bytes = encoder.encode(String(text));
            const ptr = m._lb_alloc(bytes.length + 1);
            heapU8().set(bytes, ptr);
            heapU8()[ptr + bytes.length] = 0;
            try {
                return fn(ptr);
            } finally {
                m._lb_free(ptr);
            }
        };
        const u64 = (lo, hi) => (BigInt(hi >>> 0) << 32n) | BigInt(lo >>> 0);
        const i64 = (lo, hi) => BigInt.asIntN(64, u64(lo, hi));
        const hex64 = (lo, hi) => '0x' + u64(lo, hi).toString(16).padStart(16, '0');

        // --- numbers ----------------------------------------------------------------------

        /** `value` (number, decimal string or Raw) as raw Q16.16; `what` names it in errors. */
        function toFixedRaw(value, what = 'value') {
            if (value instanceof Raw) return value.raw;
            if (typeof value === 'number') {
                bits.setFloat64(0, value, true);
                const code = m._lb_number_to_fixed(bits.getUint32(0, true), bits.getUint32(4, true), out);
                if (code !== 0) throw new RangeError(`lockbox: ${what}: ${value} is ${cString(m._lb_number_error(code))}`);
                return heap32()[out >> 2];
            }
            if (typeof value === 'string') {
                const r = withString(value, (ptr) => m._lb_fixed_parse(ptr, out));
                if (r !== 0) throw new RangeError(`lockbox: ${what}: ${lastError()}`);
                return heap32()[out >> 2];
            }
            throw new TypeError(`lockbox: ${what}: expected a number, a decimal string or lockbox.raw(n), got ${typeof value}`);
        }

        /** `value` as raw Q32.32: two words, low half first. */
        function toWideWords(value, what = 'value') {
            let big;
            if (value instanceof RawWide) big = value.raw;
            else if (value instanceof Raw) big = BigInt(value.raw) << 16n;
            else if (typeof value === 'number') {
                bits.setFloat64(0, value, true);
                const code = m._lb_number_to_wide(bits.getUint32(0, true), bits.getUint32(4, true), out);
                if (code !== 0) throw new RangeError(`lockbox: ${what}: ${value} is ${cString(m._lb_number_error(code))}`);
                return [heap32()[out >> 2], heap32()[(out >> 2) + 1]];
            } else if (typeof value === 'string') big = BigInt(toFixedRaw(value, what)) << 16n;
            else throw new TypeError(`lockbox: ${what}: expected a number, a decimal string or lockbox.raw(n)`);
            const u = BigInt.asUintN(64, big);
            return [Number(BigInt.asIntN(32, u)), Number(BigInt.asIntN(32, u >> 32n))];
        }

        const vecOf = (v, what) => {
            if (Array.isArray(v) && v.length === 2) return [toFixedRaw(v[0], what + '[0]'), toFixedRaw(v[1], what + '[1]')];
            if (v && typeof v === 'object' && 'x' in v && 'y' in v)
                return [toFixedRaw(v.x, what + '.x'), toFixedRaw(v.y, what + '.y')];
            throw new TypeError(`lockbox: ${what}: expected {x, y} or [x, y]`);
        };
        const vecOut = (x, y) => ({ x: x / ONE, y: y / ONE });
        const u64Words = (v, what) => {
            let big;
            if (typeof v === 'bigint') big = v;
            else if (Number.isSafeInteger(v) && v >= 0) big = BigInt(v);
            else throw new TypeError(`lockbox: ${what}: expected a non-negative safe integer or a BigInt`);
            if (big < 0n || big >= 1n << 64n) throw new RangeError(`lockbox: ${what}: outside 0 .. 2^64 - 1`);
            return [Number(BigInt.asIntN(32, big)), Number(BigInt.asIntN(32, big >> 32n))];
        };
        const intOf = (v, what) => {
            if (!Number.isInteger(v) || v < -2147483648 || v > 2147483647)
                throw new TypeError(`lockbox: ${what}: expected a 32-bit integer, got ${v}`);
            return v;
        };

        // Encodes `def` by `table` into words (presence mask first); unknown keys are errors.
        function encode(table, def, what, words = []) {
            const known = new Set(table.map((f) => f[0]));
            for (const key of Object.keys(def))
                if (!known.has(key) && def[key] !== undefined) throw new TypeError(`lockbox: ${what}: unknown field '${key}'`);
            const maskAt = words.length;
            words.push(0);
            let mask = 0;
            table.forEach(([name, kind], index) => {
                const v = def[name];
                const given = v !== undefined;
                if (given) mask |= 1 << index;
                const label = `${what}.${name}`;
                switch (kind) {
                    case 'fixed':
                        words.push(given ? toFixedRaw(v, label) : 0);
                        break;
                    case 'wide':
                        words.push(...(given ? toWideWords(v, label) : [0, 0]));
                        break;
                    case 'vec':
                        words.push(...(given ? vecOf(v, label) : [0, 0]));
                        break;
                    case 'bool':
                        words.push(given ? (v ? 1 : 0) : 0);
                        break;
                    case 'int':
                        words.push(given ? intOf(v, label) : 0);
                        break;
                    case 'u64':
                        words.push(...(given ? u64Words(v, label) : [0, 0]));
                        break;
                    case 'bodyType': {
                        const t = typeof v === 'string' ? BODY_TYPES[v] : v;
                        if (given && ![0, 1, 2].includes(t))
                            throw new TypeError(`lockbox: ${label}: expected 'static', 'kinematic' or 'dynamic'`);
                        words.push(given ? t : 0);
                        break;
                    }
                    case 'body':
                    case 'joint':
                        if (given && !(v instanceof (kind === 'body' ? Body : Joint)))
                            throw new TypeError(`lockbox: ${label}: expected a ${kind === 'body' ? 'Body' : 'Joint'}`);
                        words.push(given ? v.id : 0);
                        break;
                    case 'points': {
                        const list = given ? Array.from(v) : [];
                        words.push(list.length);
                        list.forEach((p, i) => words.push(...vecOf(p, `${label}[${i}]`)));
                        break;
                    }
                    default:
                        throw new Error(`lockbox: internal: unknown field kind ${kind}`);
                }
            });
            words[maskAt] = mask;
            return words;
        }

        // --- world objects ------------------------------------------------------------------

        /** A body of a world, named by its id (valid across snapshot restores). */
        class Body {
            constructor(world, id) {
                this.world = world;
                this.id = id;
            }
            _state() {
                check(m._lb_body_state(this.world._ptr, this.id, out));
                return outWords(22);
            }
            /** Every field at once: numbers in units, and the raw words. */
            getState() {
                const s = this._state();
                return {
                    position: vecOut(s[0], s[1]),
                    angle: s[2] / ONE,
                    linearVelocity: vecOut(s[3], s[4]),
                    angularVelocity: s[5] / ONE,
                    worldCenter: vecOut(s[6], s[7]),
                    localCenter: vecOut(s[8], s[9]),
                    type: BODY_TYPE_NAMES[s[10]],
                    awake: (s[11] & 1) !== 0,
                    active: (s[11] & 2) !== 0,
                    bullet: (s[11] & 4) !== 0,
                    sleepingAllowed: (s[11] & 8) !== 0,
                    fixedRotation: (s[11] & 16) !== 0,
                    outOfBounds: (s[11] & 32) !== 0,
                    mass: Number(i64(s[12], s[13])) / 4294967296,
                    inertia: Number(i64(s[14], s[15])) / 4294967296,
                    linearDamping: s[16] / ONE,
                    angularDamping: s[17] / ONE,
                    gravityScale: s[18] / ONE,
                    userData: u64(s[19], s[20]),
                    raw: s,
                };
            }
            getPosition() {
                const s = this._state();
                return vecOut(s[0], s[1]);
            }
            getAngle() {
                return this._state()[2] / ONE;
            }
            getLinearVelocity() {
                const s = this._state();
                return vecOut(s[3], s[4]);
            }
            getAngularVelocity() {
                return this._state()[5] / ONE;
            }
            getWorldCenter() {
                const s = this._state();
                return vecOut(s[6], s[7]);
            }
            getType() {
                return BODY_TYPE_NAMES[this._state()[10]];
            }
            isAwake() {
                return (this._state()[11] & 1) !== 0;
            }
            /** Mass in kg (Q32.32 shown as a double: for display). */
            getMass() {
                const s = this._state();
                return Number(i64(s[12], s[13])) / 4294967296;
            }
            getUserData() {
                const s = this._state();
                return u64(s[19], s[20]);
            }
            setTransform(position, angle) {
                const [x, y] = vecOf(position, 'setTransform position');
                check(m._lb_body_set_transform(this.world._ptr, this.id, x, y, toFixedRaw(angle, 'setTransform angle')));
            }
            _apply(kind, v, p, what) {
                const [x, y] = v === null ? [0, 0] : vecOf(v, what);
                const [px, py] = p === null ? [0, 0] : vecOf(p, what + ' point');
                check(m._lb_body_apply(this.world._ptr, this.id, kind, x, y, px, py));
            }
            _applyScalar(kind, value, what) {
                check(m._lb_body_apply(this.world._ptr, this.id, kind, toFixedRaw(value, what), 0, 0, 0));
            }
            setLinearVelocity(v) {
                this._apply(0, v, null, 'setLinearVelocity');
            }
            setAngularVelocity(w) {
                this._applyScalar(1, w, 'setAngularVelocity');
            }
            applyForce(force, point) {
                this._apply(2, force, point, 'applyForce');
            }
            applyForceToCenter(force) {
                this._apply(3, force, null, 'applyForceToCenter');
            }
            applyTorque(torque) {
                this._applyScalar(4, torque, 'applyTorque');
            }
            applyLinearImpulse(impulse, point) {
                this._apply(5, impulse, point, 'applyLinearImpulse');
            }
            applyAngularImpulse(impulse) {
                this._applyScalar(6, impulse, 'applyAngularImpulse');
            }
            _set(kind, value, hi = 0) {
                check(m._lb_body_set(this.world._ptr, this.id, kind, value, hi));
            }
            setType(type) {
                const t = typeof type === 'string' ? BODY_TYPES[type] : type;
                if (![0, 1, 2].includes(t)) throw new TypeError(`lockbox: setType: unknown type ${type}`);
                this._set(0, t);
            }
            setAwake(flag) {
                this._set(1, flag ? 1 : 0);
            }
            setActive(flag) {
                this._set(2, flag ? 1 : 0);
            }
            setBullet(flag) {
                this._set(3, flag ? 1 : 0);
            }
            setSleepingAllowed(flag) {
                this._set(4, flag ? 1 : 0);
            }
            setFixedRotation(flag) {
                this._set(5, flag ? 1 : 0);
            }
            setLinearDamping(d) {
                this._set(6, toFixedRaw(d, 'setLinearDamping'));
            }
            setAngularDamping(d) {
                this._set(7, toFixedRaw(d, 'setAngularDamping'));
            }
            setGravityScale(s) {
                this._set(8, toFixedRaw(s, 'setGravityScale'));
            }
            setUserData(data) {
                const [lo, hi] = u64Words(data, 'setUserData');
                this._set(9, lo, hi);
            }
            _point(kind, p, what) {
                const [x, y] = vecOf(p, what);
                check(m._lb_body_transform_point(this.world._ptr, this.id, kind, x, y, out));
                const r = outWords(2);
                return vecOut(r[0], r[1]);
            }
            getWorldPoint(p) {
                return this._point(0, p, 'getWorldPoint');
            }
            getLocalPoint(p) {
                return this._point(1, p, 'getLocalPoint');
            }
            getWorldVector(v) {
                return this._point(2, v, 'getWorldVector');
            }
            getLocalVector(v) {
                return this._point(3, v, 'getLocalVector');
            }
            getLinearVelocityFromWorldPoint(p) {
                return this._point(4, p, 'getLinearVelocityFromWorldPoint');
            }
            /** Creates a fixture: createFixture(fixtureDef) or createFixture(shape, density). */
            createFixture(def, density) {
                if (density !== undefined) def = { shape: def, density };
                if (!def || typeof def !== 'object' || !def.shape) throw new TypeError('lockbox: createFixture: a shape is required');
                const { shape, filter, ...rest } = def;
                const flat = Object.assign({}, rest, filter || {});
                const words = encode(FIXTURE_FIELDS, flat, 'fixture');
                const kind = SHAPE_KINDS[shape.type];
                if (kind === undefined)
                    throw new TypeError(`lockbox: fixture.shape.type: expected circle, edge, polygon, box or chain, got ${shape.type}`);
                words.push(kind);
                const { type, ...fields } = shape;
                encode(SHAPE_FIELDS[type], fields, `fixture.shape(${type})`, words);
                const id = check(m._lb_fixture_create(this.world._ptr, this.id, putWords(words), words.length));
                return new Fixture(this.world, id);
            }
            destroyFixture(fixture) {
                check(m._lb_fixture_destroy(this.world._ptr, fixture.id));
            }
            /** The body's fixtures, newest first (as the manual's list). */
            fixtures() {
                const n = check(m._lb_body_fixtures(this.world._ptr, this.id));
                return Array.from(readWords(m._lb_world_results(this.world._ptr), n), (id) => new Fixture(this.world, id));
            }
        }

        /** A fixture of a world, named by its id. */
        class Fixture {
            constructor(world, id) {
                this.world = world;
                this.id = id;
            }
            _state() {
                check(m._lb_fixture_state(this.world._ptr, this.id, out));
                return outWords(11);
            }
            getBody() {
                return new Body(this.world, this._state()[0]);
            }
            getType() {
                return SHAPE_NAMES[this._state()[1]];
            }
            isSensor() {
                return this._state()[2] !== 0;
            }
            getDensity() {
                return this._state()[3] / ONE;
            }
            getFriction() {
                return this._state()[4] / ONE;
            }
            getRestitution() {
                return this._state()[5] / ONE;
            }
            getFilterData() {
                const s = this._state();
                return { categoryBits: s[6], maskBits: s[7], groupIndex: s[8] };
            }
            getUserData() {
                const s = this._state();
                return u64(s[9], s[10]);
            }
            _set(kind, value, hi = 0) {
                check(m._lb_fixture_set(this.world._ptr, this.id, kind, value, hi));
            }
            setDensity(d) {
                this._set(0, toFixedRaw(d, 'setDensity'));
            }
            setFriction(f) {
                this._set(1, toFixedRaw(f, 'setFriction'));
            }
            setRestitution(r) {
                this._set(2, toFixedRaw(r, 'setRestitution'));
            }
            setSensor(flag) {
                this._set(3, flag ? 1 : 0);
            }
            setFilterData(filter) {
                const f = Object.assign({ categoryBits: 1, maskBits: 0xffff, groupIndex: 0 }, filter);
                const c = intOf(f.categoryBits, 'categoryBits') & 0xffff;
                const k = intOf(f.maskBits, 'maskBits') & 0xffff;
                this._set(4, c | (k << 16), intOf(f.groupIndex, 'groupIndex'));
            }
            setUserData(data) {
                const [lo, hi] = u64Words(data, 'setUserData');
                this._set(5, lo, hi);
            }
            testPoint(p) {
                const [x, y] = vecOf(p, 'testPoint');
                return check(m._lb_fixture_test_point(this.world._ptr, this.id, x, y)) === 1;
            }
        }

        /** A joint of a world, named by its id. */
        class Joint {
            constructor(world, id) {
                this.world = world;
                this.id = id;
            }
            _state(invDt) {
                check(m._lb_joint_state(this.world._ptr, this.id, invDt === undefined ? 0 : toFixedRaw(invDt, 'invDt'), out));
                return outWords(18);
            }
            getType() {
                return JOINT_NAMES[this._state()[0]];
            }
            getBodyA() {
                return new Body(this.world, this._state()[1]);
            }
            getBodyB() {
                return new Body(this.world, this._state()[2]);
            }
            getAnchorA() {
                const s = this._state();
                return vecOut(s[4], s[5]);
            }
            getAnchorB() {
                const s = this._state();
                return vecOut(s[6], s[7]);
            }
            /** Reaction force (N) for the inverse time step invDt (1/s). */
            getReactionForce(invDt) {
                const s = this._state(invDt);
                return vecOut(s[8], s[9]);
            }
            getReactionTorque(invDt) {
                return this._state(invDt)[10] / ONE;
            }
            getUserData() {
                const s = this._state();
                return u64(s[11], s[12]);
            }
            /**
             * The joint's own coordinates: revolute {angle, speed, motorTorque}, prismatic and
             * wheel {translation, speed, motorForce or motorTorque}, distance {length}, pulley
             * {lengthA, lengthB}, gear {coordinateA, coordinateB}, rope {maxLength, limitState},
             * mouse {target}; with motorEnabled and limitEnabled where they apply.
             */
            getState(invDt) {
                const s = this._state(invDt);
                const type = JOINT_NAMES[s[0]];
                const a = s[13] / ONE;
                const b = s[14] / ONE;
                const c = s[15] / ONE;
                switch (type) {
                    case 'revolute':
                        return { type, angle: a, speed: b, motorTorque: c, motorEnabled: s[16] !== 0, limitEnabled: s[17] !== 0 };
                    case 'prismatic':
                        return { type, translation: a, speed: b, motorForce: c, motorEnabled: s[16] !== 0, limitEnabled: s[17] !== 0 };
                    case 'wheel':
                        return { type, translation: a, speed: b, motorTorque: c, motorEnabled: s[16] !== 0 };
                    case 'distance':
                        return { type, length: a };
                    case 'pulley':
                        return { type, lengthA: a, lengthB: b };
                    case 'gear':
                        return { type, coordinateA: a, coordinateB: b };
                    case 'rope':
                        return { type, maxLength: a, limitState: s[14] };
                    case 'mouse':
                        return { type, target: vecOut(s[13], s[14]) };
                    default:
                        return { type };
                }
            }
            _set(kind, a, b = 0) {
                check(m._lb_joint_set(this.world._ptr, this.id, kind, a, b));
            }
            enableMotor(flag) {
                this._set(0, flag ? 1 : 0);
            }
            setMotorSpeed(speed) {
                this._set(1, toFixedRaw(speed, 'setMotorSpeed'));
            }
            /** Max motor torque (revolute, wheel) or force (prismatic). */
            setMaxMotorTorque(effort) {
                this._set(2, toFixedRaw(effort, 'setMaxMotorTorque'));
            }
            setMaxMotorForce(effort) {
                this._set(2, toFixedRaw(effort, 'setMaxMotorForce'));
            }
            enableLimit(flag) {
                this._set(3, flag ? 1 : 0);
            }
            setLimits(lower, upper) {
                this._set(4, toFixedRaw(lower, 'setLimits lower'), toFixedRaw(upper, 'setLimits upper'));
            }
            /** The mouse joint's target (world point, m). */
            setTarget(target) {
                const [x, y] = vecOf(target, 'setTarget');
                this._set(5, x, y);
            }
            setFrequency(hz) {
                this._set(6, toFixedRaw(hz, 'setFrequency'));
            }
            setDampingRatio(ratio) {
                this._set(7, toFixedRaw(ratio, 'setDampingRatio'));
            }
            /** Length (distance joint) or max length (rope joint), m. */
            setLength(length) {
                this._set(8, toFixedRaw(length, 'setLength'));
            }
            setMaxLength(length) {
                this._set(8, toFixedRaw(length, 'setMaxLength'));
            }
            setRatio(ratio) {
                this._set(9, toFixedRaw(ratio, 'setRatio'));
            }
            /** Max force: friction joint (Q16.16) or mouse joint (Q32.32). */
            setMaxForce(force) {
                if (this.getType() === 'mouse') {
                    const [lo, hi] = toWideWords(force, 'setMaxForce');
                    this._set(10, lo, hi);
                } else {
                    this._set(10, toFixedRaw(force, 'setMaxForce'));
                }
            }
            setMaxTorque(torque) {
                this._set(11, toFixedRaw(torque, 'setMaxTorque'));
            }
            setUserData(data) {
                const [lo, hi] = u64Words(data, 'setUserData');
                this._set(12, lo, hi);
            }
        }

        /** A world: new World({gravity}) owns one; a scene's world belongs to its scene. */
        class World {
            constructor(def = {}, internal) {
                if (internal) {
                    this._ptr = internal.ptr;
                    this._owned = false;
                    return;
                }
                const { gravity = { x: 0, y: -10 }, ...rest } = def;
                if (Object.keys(rest).length) throw new TypeError(`lockbox: World: unknown field '${Object.keys(rest)[0]}'`);
                const [gx, gy] = vecOf(gravity, 'World.gravity');
                this._ptr = m._lb_world_create(gx, gy);
                this._owned = true;
            }
            _live() {
                if (!this._ptr) throw new Error('lockbox: this world was destroyed');
                return this._ptr;
            }
            /** Frees an owned world; its bodies, fixtures and joints go with it. */
            destroy() {
                if (this._ptr && this._owned) m._lb_world_destroy(this._ptr);
                this._ptr = 0;
            }
            /** One step of dt seconds (number, decimal string or raw; 1/60 is raw 1092). */
            step(dt, velocityIterations = 8, positionIterations = 3) {
                const raw = toFixedRaw(dt, 'step dt');
                check(m._lb_world_step(this._live(), raw, intOf(velocityIterations, 'velocityIterations'),
                                       intOf(positionIterations, 'positionIterations')));
            }
            clearForces() {
                m._lb_world_clear_forces(this._live());
            }
            createBody(def = {}) {
                const words = encode(BODY_FIELDS, def, 'body');
                return new Body(this, check(m._lb_body_create(this._live(), putWords(words), words.length)));
            }
            destroyBody(body) {
                check(m._lb_body_destroy(this._live(), body.id));
            }
            /** Creates a joint from {type: 'revolute' | 'prismatic' | ... , bodyA, bodyB, ...}. */
            createJoint(def) {
                const { type, ...fields } = def || {};
                const code = JOINT_TYPES[type];
                if (!code) throw new TypeError(`lockbox: createJoint: unknown joint type ${type}`);
                const words = encode(JOINT_HEADER.concat(JOINT_FIELDS[type]), fields, `joint(${type})`, [code]);
                return new Joint(this, check(m._lb_joint_create(this._live(), putWords(words), words.length)));
            }
            destroyJoint(joint) {
                check(m._lb_joint_destroy(this._live(), joint.id));
            }
            /** The body with this id, or null. */
            getBody(id) {
                return m._lb_body_state(this._live(), intOf(id, 'getBody id'), out) === 0 ? new Body(this, id) : null;
            }
            _list(which) {
                const n = check(m._lb_world_list(this._live(), which));
                return readWords(m._lb_world_results(this._ptr), n);
            }
            /** Bodies in list order (newest first). */
            bodies() {
                return Array.from(this._list(0), (id) => new Body(this, id));
            }
            joints() {
                return Array.from(this._list(1), (id) => new Joint(this, id));
            }
            /** Contacts in list order: {fixtureA, fixtureB, touching}. */
            contacts() {
                const w = this._list(2);
                const list = [];
                for (let i = 0; i < w.length; i += 3)
                    list.push({ fixtureA: new Fixture(this, w[i]), fixtureB: new Fixture(this, w[i + 1]), touching: w[i + 2] !== 0 });
                return list;
            }
            _info() {
                m._lb_world_info(this._live(), out);
                return outWords(8);
            }
            getGravity() {
                const s = this._info();
                return vecOut(s[0], s[1]);
            }
            setGravity(g) {
                const [x, y] = vecOf(g, 'setGravity');
                m._lb_world_set_gravity(this._live(), x, y);
            }
            getBodyCount() {
                return this._info()[2];
            }
            getJointCount() {
                return this._info()[3];
            }
            getContactCount() {
                return this._info()[4];
            }
            getProxyCount() {
                return this._info()[5];
            }
            /** Fixed-point saturations inside this world's steps (0 in a healthy world). */
            getSaturationCount() {
                const s = this._info();
                return u64(s[6], s[7]);
            }
            _switch(which, value) {
                return check(m._lb_world_switch(this._live(), which, value)) === 1;
            }
            setAllowSleeping(flag) {
                this._switch(0, flag ? 1 : 0);
            }
            getAllowSleeping() {
                return this._switch(0, -1);
            }
            setWarmStarting(flag) {
                this._switch(1, flag ? 1 : 0);
            }
            getWarmStarting() {
                return this._switch(1, -1);
            }
            setContinuousPhysics(flag) {
                this._switch(2, flag ? 1 : 0);
            }
            getContinuousPhysics() {
                return this._switch(2, -1);
            }
            setSubStepping(flag) {
                this._switch(3, flag ? 1 : 0);
            }
            getSubStepping() {
                return this._switch(3, -1);
            }
            setAutoClearForces(flag) {
                this._switch(4, flag ? 1 : 0);
            }
            getAutoClearForces() {
                return this._switch(4, -1);
            }
            /** The state hash (XXH3-64 of everything that decides future steps), a BigInt. */
            hash() {
                m._lb_world_hash(this._live(), out);
                const h = outWords(2);
                return u64(h[0], h[1]);
            }
            /** The state hash as '0x' and 16 hex digits (as lockbox's tools print it). */
            hashHex() {
                m._lb_world_hash(this._live(), out);
                const h = outWords(2);
                return hex64(h[0], h[1]);
            }
            /** A snapshot: the same bytes on every platform, native or not. */
            save() {
                const n = m._lb_world_save(this._live());
                const ptr = m._lb_world_bytes(this._ptr);
                return heapU8().slice(ptr, ptr + n);
            }
            /** Restores a snapshot: undefined when the world now holds it, else the reason it
             *  was refused (the world is then unchanged). */
            restore(bytes) {
                if (!(bytes instanceof Uint8Array)) throw new TypeError('lockbox: restore: expected a Uint8Array');
                const ptr = putBytes(bytes);
                try {
                    return m._lb_world_restore(this._live(), ptr, bytes.length) === 0 ? undefined : lastError();
                } finally {
                    m._lb_free(ptr);
                }
            }
            /** Contact events since the last call: {begin, fixtureA, fixtureB, bodyA, bodyB,
             *  childA, childB}, in the order the engine reported them. */
            takeContactEvents() {
                const n = m._lb_world_take_events(this._live());
                const w = readWords(m._lb_world_results(this._ptr), 7 * n);
                const events = [];
                for (let i = 0; i < w.length; i += 7) {
                    events.push({
                        begin: w[i] === 1,
                        fixtureA: new Fixture(this, w[i + 1]),
                        fixtureB: new Fixture(this, w[i + 2]),
                        childA: w[i + 3],
                        childB: w[i + 4],
                        bodyA: new Body(this, w[i + 5]),
                        bodyB: new Body(this, w[i + 6]),
                    });
                }
                return events;
            }
            /** Fixtures whose broad-phase boxes overlap the box [lower, upper]. */
            queryAABB(lower, upper) {
                const [lx, ly] = vecOf(lower, 'queryAABB lower');
                const [ux, uy] = vecOf(upper, 'queryAABB upper');
                const n = check(m._lb_world_query_aabb(this._live(), lx, ly, ux, uy));
                return Array.from(readWords(m._lb_world_results(this._ptr), n), (id) => new Fixture(this, id));
            }
            /** Ray cast from p1 to p2: mode 'closest' (default; [] or one hit), 'all' or 'any'.
             *  Hits are {fixture, point, normal, fraction}. */
            rayCast(p1, p2, mode = 'closest') {
                const code = { closest: 0, all: 1, any: 2 }[mode];
                if (code === undefined) throw new TypeError(`lockbox: rayCast: unknown mode ${mode}`);
                const [x1, y1] = vecOf(p1, 'rayCast p1');
                const [x2, y2] = vecOf(p2, 'rayCast p2');
                const n = check(m._lb_world_ray_cast(this._live(), x1, y1, x2, y2, code));
                const w = readWords(m._lb_world_results(this._ptr), 6 * n);
                const hits = [];
                for (let i = 0; i < w.length; i += 6)
                    hits.push({ fixture: new Fixture(this, w[i]), point: vecOut(w[i + 1], w[i + 2]), normal: vecOut(w[i + 3], w[i + 4]), fraction: w[i + 5] / ONE });
                return hits;
            }
            /** The world's geometry for drawing (raw words; format in web/src/QueryApi.cpp and
             *  README.md). */
            debugDraw() {
                const n = m._lb_world_draw(this._live());
                return readWords(m._lb_world_results(this._ptr), n);
            }
        }

        /** A library scene built into a world (samples module only). */
        class Scene {
            constructor(name) {
                const ptr = withString(name, (p) => m._lb_scene_create(p, out));
                if (!ptr) throw new Error(`lockbox: ${lastError()}`);
                const d = outWords(6);
                this._ptr = ptr;
                this.name = name;
                this.info = { steps: d[0], velocityIterations: d[1], positionIterations: d[2], hz: d[3], allowSleep: d[4] !== 0, heavy: d[5] !== 0 };
                this.world = new World({}, { ptr: m._lb_scene_world(ptr) });
                this.stepCount = 0;
            }
            /** The scene's pre-step action, then one step at 1/hz (defaults: the scene's). */
            step(hz = this.info.hz, velocityIterations = this.info.velocityIterations, positionIterations = this.info.positionIterations) {
                if (!this._ptr) throw new Error('lockbox: this scene was destroyed');
                this.stepCount = check(m._lb_scene_step(this._ptr, intOf(hz, 'hz'), intOf(velocityIterations, 'velocityIterations'),
                                                        intOf(positionIterations, 'positionIterations')));
            }
            destroy() {
                if (this._ptr) m._lb_scene_destroy(this._ptr);
                this._ptr = 0;
                this.world._ptr = 0;
            }
        }

        const hasScenes = typeof m._lb_scene_count === 'function';
        const scenes = hasScenes
            ? {
                  /** Names of the library's scenes. */
                  names() {
                      const list = [];
                      for (let i = 0, n = m._lb_scene_count(); i < n; ++i) list.push(cString(m._lb_scene_name(i)));
                      return list;
                  },
                  /** Builds a scene by name. */
                  create(name) {
                      return new Scene(name);
                  },
              }
            : null;

        const replay = typeof m._lb_replay_verify === 'function'
            ? {
                  /**
                   * Verifies a replay file (Uint8Array) of a library scene as `lockbox_replay
                   * verify` does. Returns {ok, message, report, frames, hashesChecked, frameCount,
                   * tickRate, finalHash} and, on a divergence, firstBadFrame, expected, actual,
                   * stage, solvePhase (-1: unknown), and at the first keyframe after it keyframe,
                   * body (-1: none), fieldCount and fields ({field, recorded, resimulated}); or
                   * {ok: false, error} when the file cannot be played.
                   */
                  verify(bytes) {
                      if (!(bytes instanceof Uint8Array)) throw new TypeError('lockbox: replay.verify: expected a Uint8Array');
                      const ptr = putBytes(bytes);
                      let r;
                      try {
                          r = m._lb_replay_verify(ptr, bytes.length, out);
                      } finally {
                          m._lb_free(ptr);
                      }
                      if (r !== 0) return { ok: false, error: lastError() };
                      const w = outWords(18);
                      const report = cString(m._lb_replay_report());
                      const fields = [];
                      for (let i = 0; i < Math.max(w[17], 0); ++i) {
                          const [field, recorded, resimulated] = cString(m._lb_replay_field(i)).split('\t');
                          fields.push({ field, recorded, resimulated });
                      }
                      return {
                          ok: w[0] === 1,
                          message: report.split('\n')[0],
                          report,
                          frames: w[1],
                          hashesChecked: w[2],
                          firstBadFrame: w[3],
                          expected: hex64(w[4], w[5]),
                          actual: hex64(w[6], w[7]),
                          finalHash: hex64(w[8], w[9]),
                          frameCount: w[10],
                          tickRate: w[11],
                          stage: w[12],
                          solvePhase: w[13],
                          keyframe: w[14],
                          body: w[15],
                          category: w[16],
                          fieldCount: w[17],
                          fields,
                      };
                  },
              }
            : null;

        return {
            World,
            Body,
            Fixture,
            Joint,
            Raw,
            RawWide,
            scenes,
            replay,
            /** A raw Q16.16 integer, passed unchanged wherever lockbox takes a number. */
            raw: (n) => new Raw(n),
            /** A raw Q32.32 BigInt (the mouse joint's maxForce). */
            rawWide: (n) => new RawWide(n),
            /** num/den rounded once to Q16.16 (Fixed::FromRatio), e.g. ratio(1, 60) for a step. */
            ratio(num, den) {
                check(m._lb_fixed_ratio(intOf(num, 'ratio num'), intOf(den, 'ratio den'), out));
                return new Raw(heap32()[out >> 2]);
            },
            /** Decimal text parsed exactly (Fixed::Parse), as a Raw. */
            parse: (text) => new Raw(toFixedRaw(String(text), 'parse')),
            /** The raw Q16.16 value lockbox makes of a number, string or Raw. */
            toFixedRaw,
            /** The raw Q32.32 value (BigInt) lockbox makes of a number, string or Raw. */
            toWideRaw(value) {
                const [lo, hi] = toWideWords(value, 'toWideRaw');
                return i64(lo, hi);
            },
            /** A raw Q16.16 value in units (exact). */
            fromFixedRaw: (raw) => raw / ONE,
        };
    }

    return { load, Raw, RawWide };
});
