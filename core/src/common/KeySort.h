#pragma once
// Sorting by an integer key in linear time: a least-significant-digit radix sort on the key's
// offset from the smallest key, for the large per-step sorts whose keys span a narrow range (list
// keys, which the world hands out consecutively; the broad phase's pairs, packed at the width of a
// proxy id). Stable, so on distinct keys the order is the one any comparison sort gives.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace lockbox::core_detail {

/// Sorts items ascending by key(item), an int64_t. scratch is a buffer of the same type that keeps
/// its capacity between calls. Keys spanning more than 44 bits fall back to std::stable_sort.
template <class T, class Key>
void SortByKey(std::vector<T>& items, std::vector<T>& scratch, Key key) {
    constexpr int kDigitBits = 11;
    constexpr size_t kBuckets = size_t{1} << kDigitBits;
    constexpr int kMaxPasses = 4;
    if (items.size() < 2) return;
    int64_t lo = key(items.front()), hi = lo;
    for (const T& item : items) {
        lo = std::min(lo, key(item));
        hi = std::max(hi, key(item));
    }
    // The span as an unsigned difference: exact for any two int64_t values.
    const uint64_t span = static_cast<uint64_t>(hi) - static_cast<uint64_t>(lo);
    int passes = 0;
    while (passes < kMaxPasses + 1 && (span >> (passes * kDigitBits)) != 0) ++passes;
    if (passes > kMaxPasses) {
        std::stable_sort(items.begin(), items.end(), [&](const T& a, const T& b) { return key(a) < key(b); });
        return;
    }
    const auto offset = [&](const T& item) { return static_cast<uint64_t>(key(item)) - static_cast<uint64_t>(lo); };
    scratch.resize(items.size());
    std::vector<T>* from = &items;
    std::vector<T>* to = &scratch;
    for (int pass = 0; pass < passes; ++pass) {
        const int shift = pass * kDigitBits;
        std::array<size_t, kBuckets> start{};
        for (const T& item : *from) ++start[(offset(item) >> shift) & (kBuckets - 1)];
        size_t sum = 0;
        for (size_t& count : start) {
            const size_t c = count;
            count = sum;
            sum += c;
        }
        for (const T& item : *from) (*to)[start[(offset(item) >> shift) & (kBuckets - 1)]++] = item;
        std::swap(from, to);
    }
    if (from != &items) items.swap(scratch);
}

}  // namespace lockbox::core_detail
