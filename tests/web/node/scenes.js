// Two library scenes written with the JavaScript API, statement for statement as their C++
// definitions (scenes/include/lockbox/scenes/Pyramid20.h and Car.h): the same bodies
// in the same order with the same numbers (lb.ratio(n, d) is the scenes' E::R(n, d)).
'use strict';

/** pyramid20: 210 boxes in 20 rows on an edge. */
function buildPyramid20(lb, world) {
    const ground = world.createBody();
    ground.createFixture({ type: 'edge', v1: { x: -40, y: 0 }, v2: { x: 40, y: 0 } }, 0);
    const box = { type: 'box', hx: lb.ratio(1, 2), hy: lb.ratio(1, 2) };
    for (let i = 0; i < 20; ++i) {
        for (let j = i; j < 20; ++j) {
            const body = world.createBody({
                type: 'dynamic',
                position: { x: lb.ratio(-112 + 9 * i + 18 * (j - i), 16), y: lb.ratio(12 + 20 * i, 16) },
            });
            body.createFixture(box, 5);
        }
    }
}

/** car: a chassis on two wheel joints over chain-shape hills. */
function buildCar(lb, world) {
    const ground = world.createBody();
    const heights = [0, 1, 4, 5, 0, 0, -4, -8, -5, 0];
    const points = [];
    for (let i = 0; i <= 44; ++i) points.push({ x: -20 + 5 * i, y: lb.ratio(i < 4 ? 0 : heights[(i - 4) % 10], 4) });
    ground.createFixture({ shape: { type: 'chain', vertices: points }, friction: lb.ratio(6, 10) });

    const R = lb.ratio;
    const hull = [
        { x: R(-3, 2), y: R(-1, 2) },
        { x: R(3, 2), y: R(-1, 2) },
        { x: R(3, 2), y: 0 },
        { x: 0, y: R(9, 10) },
        { x: R(-23, 20), y: R(9, 10) },
        { x: R(-3, 2), y: R(1, 5) },
    ];
    const car = world.createBody({ type: 'dynamic', position: { x: 0, y: 1 } });
    car.createFixture({ type: 'polygon', vertices: hull }, 1);

    const wheelPos = [
        { x: -1, y: R(7, 20) },
        { x: 1, y: R(2, 5) },
    ];
    for (let k = 0; k < 2; ++k) {
        const w = world.createBody({ type: 'dynamic', position: wheelPos[k] });
        w.createFixture({ shape: { type: 'circle', radius: R(2, 5) }, density: 1, friction: R(9, 10) });
        world.createJoint({
            type: 'wheel',
            bodyA: car,
            bodyB: w,
            anchor: w.getPosition(),
            axis: { x: 0, y: 1 },
            motorSpeed: -10,
            maxMotorTorque: k === 0 ? 20 : 0,
            enableMotor: k === 0,
            frequencyHz: 4,
            dampingRatio: R(7, 10),
        });
    }
    return car;
}

module.exports = { buildPyramid20, buildCar };
