#pragma once
// Per-source token buckets for datagrams that arrive before their sender is admitted: a source
// may send `burst` at once and `perSecond` on average; the rest is dropped unread (no token
// check, no answer). The table is bounded: when it is full, idle sources (whose bucket refilled)
// are forgotten, and if none is idle a new source is refused until one is.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace lockbox::server {

class RateLimiter {
public:
    RateLimiter(uint32_t perSecond, uint32_t burst, size_t maxSources = 65536);

    /// True when `source` may send one more datagram at `nowMicros` (monotonic).
    bool Allow(const std::string& source, uint64_t nowMicros);
    /// Sources remembered now.
    size_t Sources() const noexcept { return m_buckets.size(); }

private:
    struct Bucket {
        uint64_t credit = 0;  // millionths of a datagram
        uint64_t last = 0;    // when credit was last brought up to date
    };
    void Refill(Bucket& b, uint64_t now) const;
    void ForgetIdle(uint64_t now);

    uint64_t m_perSecond;
    uint64_t m_capacity;  // burst, in millionths
    size_t m_maxSources;
    std::map<std::string, Bucket> m_buckets;
};

}  // namespace lockbox::server
