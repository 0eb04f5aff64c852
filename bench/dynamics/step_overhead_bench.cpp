// The fixed cost of a step in a small world, with the profile's stage timers on (the default)
// and off (b2World::SetProfileTimers): a row of boxes resting on the ground, kept awake, each box
// an island of its own. With the timers on a step reads the clock ten times and six more per
// island; the difference between the two rows is what those reads cost on this machine.
//
//   lockbox_step_overhead_bench [--benchmark_repetitions=7 --benchmark_report_aggregates_only]
#include <benchmark/benchmark.h>

#include "lockbox/lockbox.h"

namespace {

using namespace lockbox;

void SmallWorldStep(benchmark::State& state) {
    const int boxes = static_cast<int>(state.range(0));
    const bool timers = state.range(1) != 0;
    b2World world(b2Vec2(0, -10));
    world.SetAllowSleeping(false);
    world.SetProfileTimers(timers);
    b2BodyDef groundDef;
    b2PolygonShape groundBox;
    groundBox.SetAsBox(Fixed(60), Fixed(1));
    world.CreateBody(&groundDef)->CreateFixture(&groundBox, Fixed(0));
    for (int i = 0; i < boxes; ++i) {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position = b2Vec2(Fixed(-45 + 3 * i), Fixed(2));
        b2PolygonShape box;
        box.SetAsBox(Fixed(1), Fixed(1));
        world.CreateBody(&def)->CreateFixture(&box, Fixed(1));
    }
    const Fixed dt = Fixed::FromRaw(1092);  // 1/60 s
    // Let the boxes land and settle, so that every timed step does the same work.
    for (int i = 0; i < 200; ++i) world.Step(dt, 8, 3);
    for (auto _ : state) world.Step(dt, 8, 3);
    state.counters["islands"] = world.GetProfile().islandsSolved;
}
BENCHMARK(SmallWorldStep)->ArgNames({"boxes", "timers"})->ArgsProduct({{1, 10}, {1, 0}});

}  // namespace

BENCHMARK_MAIN();
