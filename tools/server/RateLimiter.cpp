// Per-source token buckets (RateLimiter.h), in whole millionths of a datagram.
#include "RateLimiter.h"

#include <algorithm>

namespace lockbox::server {

namespace {
constexpr uint64_t kUnit = 1'000'000;
}

RateLimiter::RateLimiter(uint32_t perSecond, uint32_t burst, size_t maxSources)
    : m_perSecond(std::max<uint32_t>(perSecond, 1)),
      m_capacity(static_cast<uint64_t>(std::max<uint32_t>(burst, 1)) * kUnit),
      m_maxSources(std::max<size_t>(maxSources, 1)) {}

void RateLimiter::Refill(Bucket& b, uint64_t now) const {
    if (now <= b.last) return;
    // Past the time a bucket takes to fill, more elapsed time changes nothing (and this bound
    // keeps the product below 2^64).
    const uint64_t fill = m_capacity / m_perSecond + 1;
    const uint64_t elapsed = std::min(now - b.last, fill);
    b.credit = std::min(m_capacity, b.credit + elapsed * m_perSecond);
    b.last = now;
}

void RateLimiter::ForgetIdle(uint64_t now) {
    for (auto it = m_buckets.begin(); it != m_buckets.end();) {
        Refill(it->second, now);
        if (it->second.credit >= m_capacity)
            it = m_buckets.erase(it);
        else
            ++it;
    }
}

bool RateLimiter::Allow(const std::string& source, uint64_t nowMicros) {
    auto it = m_buckets.find(source);
    if (it == m_buckets.end()) {
        if (m_buckets.size() >= m_maxSources) ForgetIdle(nowMicros);
        if (m_buckets.size() >= m_maxSources) return false;
        it = m_buckets.emplace(source, Bucket{m_capacity, nowMicros}).first;
    }
    Bucket& b = it->second;
    Refill(b, nowMicros);
    if (b.credit < kUnit) return false;
    b.credit -= kUnit;
    return true;
}

}  // namespace lockbox::server
