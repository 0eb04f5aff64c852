// b2Stages runs a sequence of stages on a task system: every block of a stage runs once, after
// every block of the stage before; the run ends early when told to; workers' saturations are
// counted on the stepping thread. It must also finish on a task system that runs the items of
// its loop one after the other, in any order.

#include "dynamics/tasks/Stages.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "../../cross/ScrambledTasks.h"
#include "lockbox/dynamics/Tasks.h"
#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Overflow.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

// Records, for every block, the number of stages finished when it started, and counts the
// runs of each block.
struct Log {
    std::vector<int32> blockCounts;
    std::vector<std::unique_ptr<std::atomic<int32>[]>> runs;  // per stage, per block
    std::vector<std::unique_ptr<std::atomic<int32>[]>> seen;  // stages finished at the block's start
    std::atomic<int32> finished{0};
    int32 stopAfter = -1;              // the stage after which the run ends, or -1
    int32 jumpFrom = -1, jumpTo = -1;  // a stage after which the run goes on at another
    bool saturate = false;

    explicit Log(std::vector<int32> counts) : blockCounts(std::move(counts)) {
        for (const int32 n : blockCounts) {
            runs.push_back(std::make_unique<std::atomic<int32>[]>(static_cast<size_t>(n)));
            seen.push_back(std::make_unique<std::atomic<int32>[]>(static_cast<size_t>(n)));
        }
    }

    static void Block(int32 stage, int32 block, void* context) {
        Log& log = *static_cast<Log*>(context);
        log.seen[static_cast<size_t>(stage)][block].store(log.finished.load());
        log.runs[static_cast<size_t>(stage)][block].fetch_add(1);
        if (log.saturate) {
            volatile int32 big = Fixed::kMaxRaw;
            static_cast<void>(Fixed::FromRaw(big) + Fixed::FromRaw(big));  // one saturation
        }
    }
    static int32 Next(int32 stage, void* context) {
        Log& log = *static_cast<Log*>(context);
        log.finished.fetch_add(1);
        if (stage == log.jumpFrom) return log.jumpTo;
        return stage == log.stopAfter ? static_cast<int32>(log.blockCounts.size()) : stage + 1;
    }
};

void RunAndCheck(b2TaskSystem& tasks, const std::vector<int32>& counts, int32 stopAfter = -1) {
    Log log(counts);
    log.stopAfter = stopAfter;
    b2Stages stages;
    for (const int32 n : counts) stages.Add(n);
    stages.Run(tasks, &Log::Block, &Log::Next, &log);
    const int32 ran = stopAfter < 0 ? static_cast<int32>(counts.size()) : stopAfter + 1;
    EXPECT_EQ(log.finished.load(), ran);
    for (size_t s = 0; s < counts.size(); ++s) {
        for (int32 b = 0; b < counts[s]; ++b) {
            const bool expected = static_cast<int32>(s) < ran;
            EXPECT_EQ(log.runs[s][b].load(), expected ? 1 : 0) << "stage " << s << " block " << b;
            // Every stage before this one had finished, and none after it.
            if (expected) {
                EXPECT_EQ(log.seen[s][b].load(), static_cast<int32>(s)) << "stage " << s << " block " << b;
            }
        }
    }
}

const std::vector<int32> kCounts = {1, 7, 64, 3, 1, 200, 2, 33};

// Skips from stage 2 to stage 6: stages 3 to 5 never run, the ones after do.
TEST(Stages, GoesOnWhereToldTo) {
    b2ThreadPool pool(3);
    for (int repeat = 0; repeat < 10; ++repeat) {
        Log log(kCounts);
        log.jumpFrom = 2;
        log.jumpTo = 6;
        b2Stages stages;
        for (const int32 n : kCounts) stages.Add(n);
        stages.Run(pool, &Log::Block, &Log::Next, &log);
        EXPECT_EQ(log.finished.load(), 5);  // stages 0, 1, 2, 6 and 7
        for (size_t s = 0; s < kCounts.size(); ++s) {
            const bool skipped = s >= 3 && s <= 5;
            for (int32 b = 0; b < kCounts[s]; ++b) EXPECT_EQ(log.runs[s][b].load(), skipped ? 0 : 1) << s;
        }
    }
}

TEST(Stages, EveryBlockRunsOnceAfterTheStageBefore) {
    for (const int32 workers : {2, 3, 8}) {
        b2ThreadPool pool(workers);
        for (int repeat = 0; repeat < 20; ++repeat) RunAndCheck(pool, kCounts);
    }
}

TEST(Stages, EndsWhereToldTo) {
    b2ThreadPool pool(3);
    for (int32 stop = 0; stop < static_cast<int32>(kCounts.size()); ++stop) RunAndCheck(pool, kCounts, stop);
}

// A job system that runs the items of a loop one after the other (here four "workers", in a
// shuffled order): the first item does all the work, the others find it done.
TEST(Stages, FinishesWhenTheItemsRunOneAfterTheOther) {
    golden::ScrambledTasks tasks(4, 7);
    for (int repeat = 0; repeat < 5; ++repeat) RunAndCheck(tasks, kCounts);
    EXPECT_EQ(tasks.Loops(), 5u);
}

TEST(Stages, WorkersSaturationsAreCountedOnTheCallingThread) {
    if (kOverflowTraps) GTEST_SKIP() << "checked builds trap instead of counting";
    b2ThreadPool pool(4);
    Log log(kCounts);
    log.saturate = true;
    b2Stages stages;
    int32 blocks = 0;
    for (const int32 n : kCounts) {
        stages.Add(n);
        blocks += n;
    }
    ResetSaturationCount();
    stages.Run(pool, &Log::Block, nullptr, &log);
    EXPECT_EQ(SaturationCount(), static_cast<uint64_t>(blocks));
    ResetSaturationCount();
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
