// lockbox_pool_bench: what one loop of the built-in thread pool (b2ThreadPool::ParallelFor)
// costs the stepping thread, after a stretch of serial work as a step has between its parallel
// stages. The loop's blocks do next to nothing, so the time is the hand-over itself: posting
// the loop, the workers noticing it, and the caller seeing its last block end.
//
//   lockbox_pool_bench [--benchmark_repetitions=5 --benchmark_report_aggregates_only=true]
#include <chrono>
#include <cstdint>

#include <benchmark/benchmark.h>

#include "lockbox/dynamics/Tasks.h"

namespace {

using Clock = std::chrono::steady_clock;

// Each item adds its index to the block's own slot: a store per block, nothing to optimise away.
struct Sink {
    alignas(64) int64_t slots[64] = {};
};

void Touch(lockbox::int32 begin, lockbox::int32 end, void* context) {
    auto* sink = static_cast<Sink*>(context);
    int64_t sum = 0;
    for (lockbox::int32 i = begin; i < end; ++i) sum += i;
    sink->slots[begin % 64] += sum;
}

// Busy work on the calling thread alone, as a step's serial stages are.
void SerialWork(std::chrono::microseconds span) {
    const Clock::time_point until = Clock::now() + span;
    while (Clock::now() < until) {
    }
}

// One loop of 64 items in blocks of 8 on `workers` threads, after `gap` microseconds of serial
// work; only the loop is timed.
void BM_PoolLoop(benchmark::State& state) {
    const auto workers = static_cast<lockbox::int32>(state.range(0));
    const std::chrono::microseconds gap(state.range(1));
    lockbox::b2ThreadPool pool(workers);
    Sink sink;
    for (auto _ : state) {
        SerialWork(gap);
        const Clock::time_point start = Clock::now();
        pool.ParallelFor(64, 8, &Touch, &sink);
        state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
    }
    benchmark::DoNotOptimize(sink.slots);
}
BENCHMARK(BM_PoolLoop)
    ->ArgNames({"workers", "gap_us"})
    ->ArgsProduct({{2}, {0, 20, 50, 200, 1000}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
