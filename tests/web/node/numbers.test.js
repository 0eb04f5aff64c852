// The one number conversion (docs/numerics.md, web/README.md): a JavaScript number becomes the
// Q16.16 value Fixed::Parse gives for its exact decimal expansion, with integer arithmetic on
// its IEEE-754 bits; decimal strings go through Fixed::Parse itself; raw integers pass as they
// are; NaN, infinities and out-of-range values are refused.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const { loadPackage } = require('./common');

// The exact decimal expansion of a finite double, with BigInt: significand * 2^e.
function exactDecimal(value) {
    const view = new DataView(new ArrayBuffer(8));
    view.setFloat64(0, value);
    const bits = view.getBigUint64(0);
    const negative = bits >> 63n === 1n;
    const biased = Number((bits >> 52n) & 0x7ffn);
    const fraction = bits & ((1n << 52n) - 1n);
    const significand = biased === 0 ? fraction : fraction | (1n << 52n);
    const exponent = (biased === 0 ? 1 : biased) - 1075;
    let text;
    if (exponent >= 0) text = (significand << BigInt(exponent)).toString();
    else {
        const digits = (significand * 5n ** BigInt(-exponent)).toString().padStart(-exponent + 1, '0');
        text = digits.slice(0, digits.length + exponent) + '.' + digits.slice(digits.length + exponent);
    }
    return (negative ? '-' : '') + text;
}

// Both conversions: {raw} or {refused: true}.
function viaNumber(lb, value) {
    try {
        return { raw: lb.toFixedRaw(value) };
    } catch (e) {
        assert.ok(e instanceof RangeError, String(e));
        return { refused: true };
    }
}
function viaParse(lb, text) {
    try {
        return { raw: lb.parse(text).raw };
    } catch (e) {
        return { refused: true };
    }
}

test('decimal strings: Number(text) converts as Fixed::Parse(text)', async () => {
    const lb = await loadPackage();
    const cases = [
        // halves of a unit (ties, away from zero) and their neighbours
        '0.00000762939453125', '-0.00000762939453125', '0.00002288818359375', '-0.00002288818359375',
        '0.5', '-0.5', '1.5', '-2.5', '12.50000762939453125', '-12.50000762939453125',
        // ordinary decimals
        '0', '-0', '0.1', '-0.1', '0.2', '0.3', '0.7', '1.15', '-1.15', '9.81', '123.456', '-4095.999',
        '0.016666666666666666', '1e-3', '-2.5e-3', '1e-10', '3.141592653589793',
        // the range limits: the largest value, and the tie with 2^31 that rounds out of range
        '32767.999984741211', '-32767.999984741211', '32767.99998474121', '32767.99999237060546875',
        '-32767.99999237060546875', '32768', '-32768', '1e5', '-1e300',
    ];
    for (const text of cases) {
        assert.deepEqual(viaNumber(lb, Number(text)), viaParse(lb, text), text);
    }
    assert.equal(lb.toFixedRaw(0.5), 32768);
    assert.equal(lb.toFixedRaw(-0.00000762939453125), -1);
    assert.equal(lb.toFixedRaw(32767.999984741211), 2147483647);
    assert.deepEqual(viaNumber(lb, 32767.99999237060546875), { refused: true });
    assert.deepEqual(viaParse(lb, '32767.99999237060546875'), { refused: true });
});

test('values that must be refused', async () => {
    const lb = await loadPackage();
    for (const v of [NaN, Infinity, -Infinity, 32768, -32768, 1e20, -Number.MAX_VALUE]) {
        assert.throws(() => lb.toFixedRaw(v), RangeError, String(v));
    }
    assert.throws(() => lb.toFixedRaw('NaN'), RangeError);
    assert.throws(() => lb.toFixedRaw('1.2.3'), RangeError);
    assert.throws(() => lb.toFixedRaw(undefined), TypeError);
    assert.throws(() => lb.toFixedRaw(1n), TypeError);
    assert.throws(() => lb.raw(2 ** 31), RangeError);
    assert.throws(() => lb.raw(-(2 ** 31)), RangeError);
    assert.throws(() => lb.raw(0.5), RangeError);
    assert.throws(() => lb.ratio(1, 0), /zero denominator/);
    assert.throws(() => lb.ratio(40000, 1), /out of range/);
    assert.throws(() => lb.toWideRaw(2 ** 31), RangeError);
});

test('exact expansions of random doubles convert as Fixed::Parse parses them', async () => {
    const lb = await loadPackage();
    const view = new DataView(new ArrayBuffer(8));
    let state = 0x243f6a8885a308d3n;
    const next = () => {
        state = (state + 0x9e3779b97f4a7c15n) & 0xffffffffffffffffn;
        let z = state;
        z = ((z ^ (z >> 30n)) * 0xbf58476d1ce4e5b9n) & 0xffffffffffffffffn;
        z = ((z ^ (z >> 27n)) * 0x94d049bb133111ebn) & 0xffffffffffffffffn;
        return z ^ (z >> 31n);
    };
    let checked = 0;
    for (let biased = 1023 - 40; biased <= 1023 + 17; ++biased) {
        for (let i = 0; i < 40; ++i) {
            const r = next();
            // Random significands, and short ones (ties are likely).
            const fraction = i % 2 ? r & ((1n << 52n) - 1n) : r & (0xffn << 44n);
            view.setBigUint64(0, (r & (1n << 63n)) | (BigInt(biased) << 52n) | fraction);
            const value = view.getFloat64(0);
            assert.deepEqual(viaNumber(lb, value), viaParse(lb, exactDecimal(value)), exactDecimal(value));
            ++checked;
        }
    }
    assert.ok(checked > 2000);
});

test('raw values pass unchanged; Q32.32 for the one Wide field', async () => {
    const lb = await loadPackage();
    assert.equal(lb.toFixedRaw(lb.raw(12345)), 12345);
    assert.equal(lb.toFixedRaw(lb.raw(-2147483647)), -2147483647);
    assert.equal(lb.ratio(1, 60).raw, 1092);
    assert.equal(lb.toFixedRaw(1 / 60), 1092);
    assert.equal(lb.parse('-12.375').raw, -811008);
    assert.equal(lb.fromFixedRaw(lb.toFixedRaw(0.1)), 6554 / 65536);
    assert.equal(lb.toWideRaw(0.1), 429496730n);
    assert.equal(lb.toWideRaw(lb.raw(1)), 65536n);
    assert.equal(lb.toWideRaw(lb.rawWide(-5n)), -5n);
    assert.equal(lb.toWideRaw(-2147483647.5), -(2147483647n << 32n) - (1n << 31n));
});
