#pragma once
/// @file
/// b2BroadPhase: Box2D v2.2.1's broad-phase on top of b2DynamicTree. It buffers the proxies that
/// moved and, once per step, reports every new pair of overlapping fat AABBs.
///
/// Deterministic pair contract (relied on by the contact manager and by the golden hashes):
/// - The move buffer holds proxy ids in the order of the CreateProxy, MoveProxy (only when the
///   proxy left its fat AABB) and TouchProxy calls since the last UpdatePairs; a proxy may
///   appear more than once. DestroyProxy nulls every entry of that proxy (2.3's fix; 2.2.1
///   nulled only the first, leaving a dangling id behind a Move followed by a Touch).
/// - UpdatePairs queries the tree with the fat AABB of each buffered proxy in buffer order and
///   records a pair (min(id, other), max(id, other)) for every other proxy whose fat AABB
///   overlaps it (touching counts). Pairs are sorted by (proxyIdA, proxyIdB) ascending, a total
///   order on distinct pairs, and each distinct pair is reported exactly once, in that order,
///   as AddPair(userData(proxyIdA), userData(proxyIdB)). So the sequence depends only on the
///   proxy ids and fat AABBs, never on addresses, traversal order or the sort algorithm.
/// - Pairs are reported again in later steps while they stay overlapping and one of them moves:
///   the client (the contact manager) filters pairs it already has, as in 2.2.1.
///
/// State (docs/determinism.md): the tree (see b2DynamicTree), the proxy count and the move
/// buffer (GetMoveBuffer) carry over between steps; the pair buffer does not (it is cleared at
/// the start of UpdatePairs). Buffers are std::vectors that keep their capacity, so a warm
/// broad-phase does not allocate.

#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

/// A candidate pair of proxies, proxyIdA < proxyIdB.
struct b2Pair {
    int32 proxyIdA = -1;  ///< the smaller proxy id
    int32 proxyIdB = -1;  ///< the larger proxy id
};

/// (proxyIdA, proxyIdB) as one key; for ids >= 0 its order is b2PairLessThan's.
constexpr uint64 PairKey(const b2Pair& pair) noexcept {
    return (uint64{static_cast<uint32>(pair.proxyIdA)} << 32) | static_cast<uint32>(pair.proxyIdB);
}

/// Lexicographic order on (proxyIdA, proxyIdB): the pair order of UpdatePairs.
constexpr bool b2PairLessThan(const b2Pair& pair1, const b2Pair& pair2) noexcept {
    if (pair1.proxyIdA != pair2.proxyIdA) return pair1.proxyIdA < pair2.proxyIdA;
    return pair1.proxyIdB < pair2.proxyIdB;
}

/// The broad-phase: a dynamic tree plus the move and pair buffers.
class LOCKBOX_API b2BroadPhase {
public:
    /// Null proxy id (a destroyed move-buffer entry).
    static constexpr int32 e_nullProxy = -1;

    /// Empty broad-phase with buffer capacity reserved for 16 moves and 16 pairs (as 2.2.1).
    b2BroadPhase();

    /// Creates a proxy with a tight AABB (m) and buffers it as moved; returns its id (>= 0).
    int32 CreateProxy(const b2AABB& aabb, uint64 userData);

    /// Destroys a proxy and removes it from the move buffer. proxyId must be live.
    void DestroyProxy(int32 proxyId);

    /// Moves a proxy (see b2DynamicTree::MoveProxy; displacement in m). Buffers it as moved
    /// only when its fat AABB had to change.
    void MoveProxy(int32 proxyId, const b2AABB& aabb, const b2Vec2& displacement);

    /// Buffers a proxy as moved without moving it, so its pairs are reported again.
    void TouchProxy(int32 proxyId);

    /// The fat AABB of a proxy (m).
    const b2AABB& GetFatAABB(int32 proxyId) const { return m_tree.GetFatAABB(proxyId); }

    /// The user data of a proxy.
    uint64 GetUserData(int32 proxyId) const { return m_tree.GetUserData(proxyId); }

    /// True when the fat AABBs of two proxies overlap (touching counts).
    bool TestOverlap(int32 proxyIdA, int32 proxyIdB) const {
        return b2TestOverlap(m_tree.GetFatAABB(proxyIdA), m_tree.GetFatAABB(proxyIdB));
    }

    /// Number of live proxies.
    int32 GetProxyCount() const noexcept { return m_proxyCount; }

    /// Reports the new pairs through callback->AddPair(uint64 userDataA, uint64 userDataB) in
    /// the order of the contract above, then empties the move buffer.
    template <typename T>
    void UpdatePairs(T* callback);

    /// The pairs UpdatePairs reports, in its order and each once, as proxy ids, without
    /// reporting them; empties the move buffer. For a client that examines the pairs before it
    /// takes them. Valid until the next call of CollectPairs or UpdatePairs.
    const std::vector<b2Pair>& CollectPairs();

    /// CollectPairs with the tree queries of the moved proxies spread over a parallel loop;
    /// the result is the same. parallelFor(count, blockSize, range, context) must call
    /// range(begin, end, context) exactly once for every block [k * blockSize, min((k + 1) *
    /// blockSize, count)), in any order and on any threads, and return when all have run (the
    /// contract of b2TaskSystem::ParallelFor). It is called at most once, with count >= 1.
    template <typename ParallelFor>
    const std::vector<b2Pair>& CollectPairs(ParallelFor&& parallelFor);

    /// Moved proxies per block of the parallel CollectPairs.
    static constexpr int32 kMovesPerBlock = 64;

    /// Forwards to b2DynamicTree::Query.
    template <typename T>
    void Query(T* callback, const b2AABB& aabb) const {
        m_tree.Query(callback, aabb);
    }

    /// Forwards to b2DynamicTree::RayCast.
    template <typename T>
    void RayCast(T* callback, const b2RayCastInput& input) const {
        m_tree.RayCast(callback, input);
    }

    /// Height of the tree.
    int32 GetTreeHeight() const { return m_tree.GetHeight(); }
    /// Largest balance of the tree.
    int32 GetTreeBalance() const { return m_tree.GetMaxBalance(); }
    /// Sum of node perimeters over root perimeter (dimensionless).
    Wide GetTreeQuality() const { return m_tree.GetAreaRatio(); }

    /// Snapshot restore: the tree to fill in (see b2DynamicTree::RestoreState).
    b2DynamicTree& GetTreeForRestore() noexcept { return m_tree; }
    /// Snapshot restore: the proxy count and move buffer of a validated image (the tree is
    /// restored through GetTreeForRestore). The pair buffer is scratch and starts empty.
    void RestoreState(int32 proxyCount, const std::vector<int32>& moveBuffer) {
        m_proxyCount = proxyCount;
        m_moveBuffer = moveBuffer;
        m_pairBuffer.clear();
    }
    /// The tree (read-only), for snapshots and tests.
    const b2DynamicTree& GetTree() const noexcept { return m_tree; }
    /// The pending move buffer (read-only, may contain e_nullProxy), for snapshots and tests.
    const std::vector<int32>& GetMoveBuffer() const noexcept { return m_moveBuffer; }

    /// Equality of the state that carries over between steps (tree, proxy count, move buffer).
    friend bool operator==(const b2BroadPhase& a, const b2BroadPhase& b) noexcept {
        return a.m_proxyCount == b.m_proxyCount && a.m_moveBuffer == b.m_moveBuffer && a.m_tree == b.m_tree;
    }

private:
    /// The tree's query callback while pairs are collected: records the pairs of one moved
    /// proxy into one buffer (a nested type reaches the private state without befriending the
    /// tree).
    struct PairCollector {
        const b2BroadPhase* broadPhase;
        int32 queryProxyId;
        std::vector<b2Pair>* out;
        bool QueryCallback(int32 proxyId);
    };

    void BufferMove(int32 proxyId);
    void UnBufferMove(int32 proxyId);
    /// Sets (or clears) m_moved for every live proxy of the move buffer.
    void MarkMoved(bool moved);
    /// Collection's start: empties the pair buffer and marks the moved proxies.
    void BeginPairs();
    /// The pairs found by the queries of move-buffer entries [begin, end), appended to out in
    /// buffer order. Reads the broad-phase only, so threads may run it on disjoint ranges.
    void QueryMoves(int32 begin, int32 end, std::vector<b2Pair>* out) const;
    /// One block of the parallel CollectPairs (`self` is the broad-phase).
    static void QueryBlock(int32 begin, int32 end, void* self);
    /// Collection's end: clears the marks and the move buffer, sorts the pairs, keeps each once.
    const std::vector<b2Pair>& FinishPairs();

    b2DynamicTree m_tree;
    int32 m_proxyCount = 0;
    std::vector<int32> m_moveBuffer;
    std::vector<b2Pair> m_pairBuffer;
    std::vector<b2Pair> m_pairScratch;  ///< the radix sort's second buffer (scratch)
    std::vector<uint8> m_moved;         ///< per tree node, 1 while pairs are collected for a buffered proxy (scratch)
    std::vector<std::vector<b2Pair>> m_blockPairs;  ///< per block of the parallel collection (scratch)
};

template <typename ParallelFor>
const std::vector<b2Pair>& b2BroadPhase::CollectPairs(ParallelFor&& parallelFor) {
    const auto moves = static_cast<int32>(m_moveBuffer.size());
    if (moves <= kMovesPerBlock) return CollectPairs();
    BeginPairs();
    const int32 blocks = 1 + (moves - 1) / kMovesPerBlock;
    if (m_blockPairs.size() < static_cast<size_t>(blocks)) m_blockPairs.resize(static_cast<size_t>(blocks));
    parallelFor(moves, kMovesPerBlock, &QueryBlock, static_cast<void*>(this));
    // Blocks in buffer order: the very pairs of the one-thread queries, in their order.
    for (int32 k = 0; k < blocks; ++k) {
        const std::vector<b2Pair>& found = m_blockPairs[static_cast<size_t>(k)];
        m_pairBuffer.insert(m_pairBuffer.end(), found.begin(), found.end());
    }
    return FinishPairs();
}

template <typename T>
void b2BroadPhase::UpdatePairs(T* callback) {
    // By index: a callback may buffer moves, never pairs, so the buffer stays as it is.
    const std::vector<b2Pair>& pairs = CollectPairs();
    for (size_t i = 0; i < pairs.size(); ++i) {
        callback->AddPair(m_tree.GetUserData(pairs[i].proxyIdA), m_tree.GetUserData(pairs[i].proxyIdB));
    }
}

}  // namespace lockbox
