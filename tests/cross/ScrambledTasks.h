#pragma once
// A b2TaskSystem for tests that claims several workers and runs a loop's blocks one after
// another on the calling thread, in an order drawn from a seeded generator: whatever a world
// computes in parallel must not depend on which block runs first.

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "lockbox/dynamics/Tasks.h"

namespace lockbox::golden {

class ScrambledTasks final : public b2TaskSystem {
public:
    ScrambledTasks(int32 workers, uint64_t seed) : workers_(workers), random_(seed) {}

    int32 GetWorkerCount() const noexcept override { return workers_; }

    void ParallelFor(int32 itemCount, int32 blockSize, b2TaskRange range, void* context) override {
        const int32 blocks = 1 + (itemCount - 1) / blockSize;
        order_.resize(static_cast<size_t>(blocks));
        std::iota(order_.begin(), order_.end(), 0);
        std::shuffle(order_.begin(), order_.end(), random_);
        for (const int32 k : order_) range(k * blockSize, std::min((k + 1) * blockSize, itemCount), context);
        ++loops_;
        blocks_ += static_cast<uint64_t>(blocks);
    }

    uint64_t Loops() const { return loops_; }    ///< ParallelFor calls so far
    uint64_t Blocks() const { return blocks_; }  ///< blocks run so far

private:
    int32 workers_;
    std::mt19937_64 random_;
    std::vector<int32> order_;
    uint64_t loops_ = 0;
    uint64_t blocks_ = 0;
};

}  // namespace lockbox::golden
