#pragma once
/// @file
/// b2DynamicTree: the broad-phase bounding volume hierarchy of Box2D v2.2.1 on Q16.16.
///
/// Leaves hold "fat" AABBs (the client box extended by b2_aabbExtension, plus a prediction of
/// b2_aabbMultiplier times the displacement in MoveProxy), so a proxy that moves a little does
/// not touch the tree. Internal nodes are unions of their two children. Insertion descends by
/// Box2D's surface-area heuristic and the tree is kept balanced by AVL-style rotations.
///
/// Determinism and state (docs/determinism.md): nodes live in a std::vector addressed by index
/// and every link is an int32 index (b2_nullNode = -1). The tree's whole future behaviour is a
/// function of GetNodes() (every slot, free ones included, which are kept in one canonical
/// cleared state), GetRoot(), GetFreeList(), GetNodeCount() and GetInsertionCount(); restoring
/// those fields restores the tree bit for bit. The capacity is GetNodes().size().
///
/// Numerics: the insertion heuristic compares perimeters as Wide (Q32.32, exact: a perimeter is
/// a sum of raw differences), so costs never overflow for boxes anywhere in the Fixed range
/// (Q16.16 costs would overflow once wx + wy > 8192 m). Because the costs are exact
/// integers the descent is a pure function of the boxes. Ties are resolved as in 2.2.1: a tie
/// between stopping (new parent here) and descending descends, and a tie between the two
/// children descends into child2. Balance keeps the taller grandchild up and, on a height tie,
/// the second one (G or E).

#include <cstdint>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

/// Null node index (a free-list end, a leaf's missing children, the empty tree's root).
inline constexpr int32 b2_nullNode = -1;

/// A node of the dynamic tree. Plain data: a snapshot writes the fields, never the struct.
struct b2TreeNode {
    /// True for leaves (proxies). A free node also reports true; check height >= 0 first.
    constexpr bool IsLeaf() const noexcept { return child1 == b2_nullNode; }

    b2AABB aabb;                 ///< fat AABB (leaf) or union of the children (internal), m
    uint64 userData = 0;         ///< client data of a leaf; 0 for internal and free nodes
    int32 parent = b2_nullNode;  ///< parent index; b2_nullNode for the root and free nodes
    int32 next = b2_nullNode;    ///< free-list link of a free node; b2_nullNode when allocated
    int32 child1 = b2_nullNode;  ///< first child; b2_nullNode for leaves and free nodes
    int32 child2 = b2_nullNode;  ///< second child; b2_nullNode for leaves and free nodes
    int32 height = -1;           ///< 0 for a leaf, 1 + max child height inside, -1 when free

    /// Field-wise equality (every field, free nodes included).
    friend constexpr bool operator==(const b2TreeNode& a, const b2TreeNode& b) noexcept {
        return a.aabb.lowerBound == b.aabb.lowerBound && a.aabb.upperBound == b.aabb.upperBound &&
               a.userData == b.userData && a.parent == b.parent && a.next == b.next && a.child1 == b.child1 &&
               a.child2 == b.child2 && a.height == b.height;
    }
};

namespace detail {

/// b2TestOverlap without short-circuits: the same answer, but one branch instead of four,
/// which is what a tree walk over mostly-disjoint boxes wants.
constexpr bool b2TreeOverlap(const b2AABB& a, const b2AABB& b) noexcept {
    const int separated = int{b.lowerBound.x > a.upperBound.x} | int{b.lowerBound.y > a.upperBound.y} |
                          int{a.lowerBound.x > b.upperBound.x} | int{a.lowerBound.y > b.upperBound.y};
    return separated == 0;
}

/// Traversal stack of Query and RayCast: 256 entries inline (a balanced tree of 2^100 leaves
/// would fit), spilling to the heap only beyond that, so a warm query never allocates.
class LOCKBOX_API b2TreeStack {
public:
    /// Pushes a node index.
    void Push(int32 v) {
        if (m_count < kInline) [[likely]] {
            m_inline[m_count++] = v;
            return;
        }
        PushSpill(v);
    }
    /// Pops the last index pushed; the stack must not be empty.
    int32 Pop() {
        --m_count;
        if (m_count < kInline) [[likely]]
            return m_inline[m_count];
        return m_spill[static_cast<size_t>(m_count - kInline)];
    }
    /// Number of entries.
    int32 GetCount() const noexcept { return m_count; }

private:
    void PushSpill(int32 v);  // out of line: keeps Push small enough to inline

    static constexpr int32 kInline = 256;
    int32 m_inline[kInline];
    std::vector<int32> m_spill;
    int32 m_count = 0;
};

/// The ray of b2DynamicTree::RayCast in exact integer form: the segment's bounding box for the
/// current max fraction and the separating-axis test of the segment's line against a box.
/// Both are conservative (never reject a box the true segment touches) and exact up to the
/// half-raw rounding of the segment end, which the box absorbs by one raw.
class LOCKBOX_API b2TreeRay {
public:
    /// Ray from p1 towards p2, clipped at maxFraction (any Fixed; [0, 1] in practice).
    b2TreeRay(const b2Vec2& p1, const b2Vec2& p2, Fixed maxFraction) noexcept;
    /// Re-clips the segment at a new max fraction.
    void Clip(Fixed maxFraction) noexcept;
    /// The segment's bounding box, widened by one raw at the clipped end.
    const b2AABB& GetSegmentAABB() const noexcept { return m_segmentAABB; }
    /// True when the infinite line through the ray separates from the box (Gino, p80:
    /// |dot(v, p1 - c)| > dot(|v|, h) with v perpendicular to the ray), decided exactly in
    /// 128-bit integers on the doubled centre and extents, so no rounded normal is involved.
    bool LineMisses(const b2AABB& box) const noexcept;

private:
    b2Vec2 m_p1;
    int64_t m_dx = 0;  // p2 - p1, raw, exact (up to 2^32 in magnitude)
    int64_t m_dy = 0;
    b2AABB m_segmentAABB;
};

}  // namespace detail

/// A dynamic AABB tree (Box2D v2.2.1's b2DynamicTree). Proxy ids are node indices and stay
/// valid until DestroyProxy. Not thread-safe for writes; const methods may run concurrently.
class LOCKBOX_API b2DynamicTree {
public:
    /// An empty tree with 16 free node slots (as 2.2.1).
    b2DynamicTree();

    /// Creates a proxy for a tight AABB (m, sorted bounds inside the Fixed range); the stored
    /// fat box is the AABB extended by b2_aabbExtension (clamped to the Fixed range). Returns
    /// the proxy id (a node index, >= 0).
    int32 CreateProxy(const b2AABB& aabb, uint64 userData);

    /// Destroys a proxy; proxyId must be a live leaf.
    void DestroyProxy(int32 proxyId);

    /// Moves a proxy to a new tight AABB with a swept displacement (m, the motion this step).
    /// Does nothing and returns false while the fat AABB still contains aabb; otherwise
    /// re-inserts the leaf with a new fat AABB (extension plus b2_aabbMultiplier * displacement
    /// on the side of motion, clamped to the Fixed range) and returns true.
    bool MoveProxy(int32 proxyId, const b2AABB& aabb, const b2Vec2& displacement);

    /// The user data of a proxy.
    uint64 GetUserData(int32 proxyId) const;

    /// The fat AABB of a proxy (m).
    const b2AABB& GetFatAABB(int32 proxyId) const;

    /// Calls callback->QueryCallback(int32 proxyId) -> bool for every proxy whose fat AABB
    /// overlaps aabb (touching counts); returning false stops the query. The order is a
    /// depth-first walk visiting child2 before child1: a function of the tree state only.
    template <typename T>
    void Query(T* callback, const b2AABB& aabb) const;

    /// Ray cast against the proxies (the manual's protocol). For every proxy whose fat AABB the
    /// segment p1 -> p1 + maxFraction * (p2 - p1) may touch, calls
    /// callback->RayCastCallback(const b2RayCastInput&, int32 proxyId) -> Fixed with the input
    /// clipped to the current max fraction. The callback returns 0 to terminate, a positive
    /// fraction to clip the ray to it, or a negative value to ignore the proxy. No proxy whose
    /// fat AABB the clipped segment touches is ever skipped (the culling is exact, see
    /// detail::b2TreeRay); a few that it does not touch may be passed to the callback.
    template <typename T>
    void RayCast(T* callback, const b2RayCastInput& input) const;

    /// Checks structure (links, leaf/internal shape, free list, node count) and metrics
    /// (heights, boxes equal to the union of their children). Returns false on the first
    /// violation; never asserts, so tests can use it in any build. O(capacity).
    bool Validate() const;

    /// Height of the root (0 for a single leaf or an empty tree). O(1).
    int32 GetHeight() const;

    /// Largest |height(child2) - height(child1)| over the internal nodes. O(capacity).
    int32 GetMaxBalance() const;

    /// Sum of all node perimeters divided by the root perimeter (dimensionless, >= 1 when not
    /// empty; 0 for an empty tree). O(capacity).
    Wide GetAreaRatio() const;

    /// Rebuilds an optimal-ish tree bottom-up (greedy pairing by smallest combined perimeter,
    /// ties to the lowest (i, j) position pair). O(n^3): for tests and tools, not per step.
    void RebuildBottomUp();

    /// Snapshot restore: replaces the whole tree (nodes with their free-slot chain, root and
    /// counters) with a validated image of another tree's state.
    void RestoreState(const std::vector<b2TreeNode>& nodes, int32 root, int32 freeList, int32 nodeCount,
                      int32 insertionCount) {
        m_nodes = nodes;
        m_root = root;
        m_freeList = freeList;
        m_nodeCount = nodeCount;
        m_insertionCount = insertionCount;
    }
    /// Read-only view of the node pool (size = capacity). With the four fields below this is
    /// the tree's complete state.
    const std::vector<b2TreeNode>& GetNodes() const noexcept { return m_nodes; }
    /// Root index, or b2_nullNode when empty.
    int32 GetRoot() const noexcept { return m_root; }
    /// Head of the free list, or b2_nullNode when the pool is full.
    int32 GetFreeList() const noexcept { return m_freeList; }
    /// Number of allocated nodes (leaves + internal).
    int32 GetNodeCount() const noexcept { return m_nodeCount; }
    /// Number of leaf insertions so far (CreateProxy and every re-insertion by MoveProxy).
    int32 GetInsertionCount() const noexcept { return m_insertionCount; }

    /// Equality of the complete state (every node slot, root, free list, counters).
    friend bool operator==(const b2DynamicTree& a, const b2DynamicTree& b) noexcept {
        return a.m_root == b.m_root && a.m_freeList == b.m_freeList && a.m_nodeCount == b.m_nodeCount &&
               a.m_insertionCount == b.m_insertionCount && a.m_nodes == b.m_nodes;
    }

private:
    int32 AllocateNode();
    void FreeNode(int32 nodeId);
    void InsertLeaf(int32 leaf);
    void RemoveLeaf(int32 leaf);
    int32 Balance(int32 iA);
    void Refit(int32 index);

    std::vector<b2TreeNode> m_nodes;
    int32 m_root = b2_nullNode;
    int32 m_nodeCount = 0;
    int32 m_freeList = b2_nullNode;
    int32 m_insertionCount = 0;
};

inline uint64 b2DynamicTree::GetUserData(int32 proxyId) const { return m_nodes[static_cast<size_t>(proxyId)].userData; }

inline const b2AABB& b2DynamicTree::GetFatAABB(int32 proxyId) const {
    return m_nodes[static_cast<size_t>(proxyId)].aabb;
}

template <typename T>
void b2DynamicTree::Query(T* callback, const b2AABB& aabb) const {
    detail::b2TreeStack stack;
    stack.Push(m_root);
    while (stack.GetCount() > 0) {
        const int32 nodeId = stack.Pop();
        if (nodeId == b2_nullNode) continue;
        const b2TreeNode& node = m_nodes[static_cast<size_t>(nodeId)];
        if (!detail::b2TreeOverlap(node.aabb, aabb)) continue;
        if (node.IsLeaf()) {
            if (!callback->QueryCallback(nodeId)) return;
        } else {
            stack.Push(node.child1);
            stack.Push(node.child2);
        }
    }
}

template <typename T>
void b2DynamicTree::RayCast(T* callback, const b2RayCastInput& input) const {
    Fixed maxFraction = input.maxFraction;
    detail::b2TreeRay ray(input.p1, input.p2, maxFraction);
    detail::b2TreeStack stack;
    stack.Push(m_root);
    while (stack.GetCount() > 0) {
        const int32 nodeId = stack.Pop();
        if (nodeId == b2_nullNode) continue;
        const b2TreeNode& node = m_nodes[static_cast<size_t>(nodeId)];
        if (!detail::b2TreeOverlap(node.aabb, ray.GetSegmentAABB())) continue;
        if (ray.LineMisses(node.aabb)) continue;
        if (node.IsLeaf()) {
            b2RayCastInput subInput;
            subInput.p1 = input.p1;
            subInput.p2 = input.p2;
            subInput.maxFraction = maxFraction;
            const Fixed value = callback->RayCastCallback(subInput, nodeId);
            // Exactly zero is the client's "stop" (a Q16.16 fraction has no signed zero).
            if (value == Fixed()) return;
            if (value > Fixed()) {
                maxFraction = value;
                ray.Clip(maxFraction);
            }
        } else {
            stack.Push(node.child1);
            stack.Push(node.child2);
        }
    }
}

}  // namespace lockbox
