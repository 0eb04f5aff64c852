#include "lockbox/collision/BroadPhase.h"

#include <algorithm>
#include <bit>

#include "common/KeySort.h"
#include "lockbox/fixed/Assert.h"

namespace lockbox {

namespace {
/// Initial buffer capacities, as 2.2.1 (they grow by doubling and never shrink).
constexpr size_t kInitialMoveCapacity = 16;
constexpr size_t kInitialPairCapacity = 16;
/// From this many pairs on, the radix sort's fixed cost (its digit counts) is repaid.
constexpr size_t kRadixSortMinPairs = 256;
}  // namespace

b2BroadPhase::b2BroadPhase() {
    m_moveBuffer.reserve(kInitialMoveCapacity);
    m_pairBuffer.reserve(kInitialPairCapacity);
}

int32 b2BroadPhase::CreateProxy(const b2AABB& aabb, uint64 userData) {
    const int32 proxyId = m_tree.CreateProxy(aabb, userData);
    ++m_proxyCount;
    BufferMove(proxyId);
    return proxyId;
}

void b2BroadPhase::DestroyProxy(int32 proxyId) {
    UnBufferMove(proxyId);
    --m_proxyCount;
    m_tree.DestroyProxy(proxyId);
}

void b2BroadPhase::MoveProxy(int32 proxyId, const b2AABB& aabb, const b2Vec2& displacement) {
    if (m_tree.MoveProxy(proxyId, aabb, displacement)) BufferMove(proxyId);
}

void b2BroadPhase::TouchProxy(int32 proxyId) { BufferMove(proxyId); }

void b2BroadPhase::BufferMove(int32 proxyId) {
    LOCKBOX_ASSERT(proxyId >= 0, "b2BroadPhase: buffering a null proxy");
    m_moveBuffer.push_back(proxyId);
}

void b2BroadPhase::UnBufferMove(int32 proxyId) {
    // Null every entry, not only the first (a proxy moved and touched in the same step is
    // buffered twice; a surviving entry would query a freed node).
    for (int32& id : m_moveBuffer) {
        if (id == proxyId) id = e_nullProxy;
    }
}

void b2BroadPhase::MarkMoved(bool moved) {
    // Sized to the tree's node capacity, which grows only when proxies are created.
    const size_t capacity = m_tree.GetNodes().size();
    if (m_moved.size() < capacity) m_moved.resize(capacity, 0);
    const uint8 flag = moved ? 1 : 0;
    for (const int32 proxyId : m_moveBuffer) {
        if (proxyId != e_nullProxy) m_moved[static_cast<size_t>(proxyId)] = flag;
    }
}

void b2BroadPhase::BeginPairs() {
    m_pairBuffer.clear();
    MarkMoved(true);
}

const std::vector<b2Pair>& b2BroadPhase::CollectPairs() {
    BeginPairs();
    QueryMoves(0, static_cast<int32>(m_moveBuffer.size()), &m_pairBuffer);
    return FinishPairs();
}

void b2BroadPhase::QueryMoves(int32 begin, int32 end, std::vector<b2Pair>* out) const {
    // Query the tree with every moved proxy's fat AABB, in buffer order. Two moved proxies that
    // overlap find each other; only the query of the larger id records the pair (the overlap
    // test is symmetric), which halves the pairs to sort without changing the distinct set.
    PairCollector collector{this, e_nullProxy, out};
    for (int32 i = begin; i < end; ++i) {
        const int32 proxyId = m_moveBuffer[static_cast<size_t>(i)];
        if (proxyId == e_nullProxy) continue;
        collector.queryProxyId = proxyId;
        m_tree.Query(&collector, m_tree.GetFatAABB(proxyId));
    }
}

void b2BroadPhase::QueryBlock(int32 begin, int32 end, void* self) {
    auto* broadPhase = static_cast<b2BroadPhase*>(self);
    std::vector<b2Pair>& found = broadPhase->m_blockPairs[static_cast<size_t>(begin / kMovesPerBlock)];
    found.clear();
    broadPhase->QueryMoves(begin, end, &found);
}

const std::vector<b2Pair>& b2BroadPhase::FinishPairs() {
    MarkMoved(false);
    m_moveBuffer.clear();

    // Total order on (A, B): equal elements are identical, so any sort gives the same sequence.
    // Proxy ids are never negative here, so (A, B) packed into one unsigned key orders exactly
    // as b2PairLessThan does, in one comparison the sort can inline.
    if (m_pairBuffer.size() < kRadixSortMinPairs) {
        std::sort(m_pairBuffer.begin(), m_pairBuffer.end(),
                  [](const b2Pair& p1, const b2Pair& p2) noexcept { return PairKey(p1) < PairKey(p2); });
    } else {
        // Every id is below the tree's node count, so (A, B) packed at B's bit width orders as
        // PairKey does, over a span narrow enough for a few radix passes.
        const int idBits = std::bit_width(m_tree.GetNodes().size());
        core_detail::SortByKey(m_pairBuffer, m_pairScratch, [idBits](const b2Pair& p) noexcept {
            return (int64_t{p.proxyIdA} << idBits) | p.proxyIdB;
        });
    }
    // Each distinct pair once.
    const auto last =
        std::unique(m_pairBuffer.begin(), m_pairBuffer.end(),
                    [](const b2Pair& p1, const b2Pair& p2) noexcept { return PairKey(p1) == PairKey(p2); });
    m_pairBuffer.erase(last, m_pairBuffer.end());
    return m_pairBuffer;
}

bool b2BroadPhase::PairCollector::QueryCallback(int32 proxyId) {
    // A proxy cannot form a pair with itself.
    if (proxyId == queryProxyId) return true;
    // A moved proxy with a larger id records this pair in its own query.
    if (proxyId > queryProxyId && broadPhase->m_moved[static_cast<size_t>(proxyId)] != 0) return true;
    const int32 a = proxyId < queryProxyId ? proxyId : queryProxyId;
    const int32 b = proxyId < queryProxyId ? queryProxyId : proxyId;
    out->push_back(b2Pair{a, b});
    return true;
}

}  // namespace lockbox
