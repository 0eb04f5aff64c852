// The radix sort by integer key gives the order of a stable comparison sort, for keys of every
// span it takes in passes (one to four digits, negative keys, the int64 extremes) and for the
// spans it hands to the comparison sort.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/KeySort.h"

namespace LOCKBOX_TEST_FILE {

struct Item {
    int64_t key = 0;
    int32_t tag = 0;  // the item's place before the sort, to check stability
    bool operator==(const Item&) const = default;
};

std::vector<Item> Draw(std::mt19937_64& random, size_t count, int64_t base, uint64_t span) {
    std::vector<Item> items(count);
    for (size_t i = 0; i < count; ++i) {
        const uint64_t offset = span == 0 ? 0 : random() % span;
        items[i] = Item{static_cast<int64_t>(static_cast<uint64_t>(base) + offset), static_cast<int32_t>(i)};
    }
    return items;
}

void ExpectLikeStableSort(std::vector<Item> items, std::vector<Item>& scratch) {
    std::vector<Item> expected = items;
    std::stable_sort(expected.begin(), expected.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
    lockbox::core_detail::SortByKey(items, scratch, [](const Item& item) { return item.key; });
    ASSERT_EQ(items, expected);
}

TEST(KeySort, OrdersLikeAStableSortAtEverySpan) {
    std::mt19937_64 random(0x50f7);
    std::vector<Item> scratch;
    constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
    constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
    // Spans of 0 to 64 bits (1 to 4 passes, then the fallback), around zero and at both ends of
    // int64, with many equal keys at the narrow spans.
    for (int bits = 0; bits <= 64; bits += 3) {
        const uint64_t span = bits == 64 ? 0 : (uint64_t{1} << bits);
        for (const int64_t base : {int64_t{-1000}, kMin, kMax - static_cast<int64_t>(span == 0 ? 0 : span - 1)}) {
            std::vector<Item> items = Draw(random, 3000, base, span);
            if (bits == 64) {
                // Any key at all.
                for (Item& item : items) item.key = static_cast<int64_t>(random());
            }
            ExpectLikeStableSort(items, scratch);
        }
    }
    // The extremes together, and tiny inputs.
    ExpectLikeStableSort({{kMax, 0}, {kMin, 1}, {0, 2}, {kMin, 3}, {kMax, 4}}, scratch);
    ExpectLikeStableSort({}, scratch);
    ExpectLikeStableSort({{7, 0}}, scratch);
    ExpectLikeStableSort({{7, 0}, {-7, 1}}, scratch);
}

TEST(KeySort, ListKeysOfContactsMadeAtTheHead) {
    // The world's contact list keys: each new contact takes one less than the head's, so the
    // keys of a step's candidates are distinct and close together but come in slot order.
    std::mt19937_64 random(7);
    std::vector<Item> items;
    for (int32_t i = 0; i < 20000; ++i) items.push_back({-static_cast<int64_t>(i) * 3 - 5000, i});
    std::shuffle(items.begin(), items.end(), random);
    std::vector<Item> scratch;
    ExpectLikeStableSort(items, scratch);
}

}  // namespace LOCKBOX_TEST_FILE
