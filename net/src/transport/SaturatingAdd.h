#pragma once
// Due times of the simulated links (SimNet, LatencyTransport): a delay added to a clock already
// near the end of time stays there instead of wrapping round into the past.

#include <cstdint>
#include <limits>

namespace lockbox::net::transport_detail {

/// a + b, or the largest uint64_t where that sum overflows.
inline uint64_t SatAdd(uint64_t a, uint64_t b) {
    return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max() : a + b;
}

}  // namespace lockbox::net::transport_detail
