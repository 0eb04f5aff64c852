#include "lockbox/collision/DynamicTree.h"

#include <cstdlib>

#include "lockbox/fixed/Assert.h"

namespace lockbox {

namespace {

/// Initial pool size, as 2.2.1; the pool doubles when the free list runs dry.
constexpr int32 kInitialCapacity = 16;

/// a.raw + delta clamped to the symmetric Fixed range. Fat boxes are a heuristic, so clamping
/// an extension or a predicted displacement at the edge of the number range is harmless: the
/// fat box still contains the tight one, and nothing traps or wraps.
Fixed AddClamped(Fixed a, int64_t delta) noexcept {
    const int64_t r = int64_t{a.Raw()} + delta;
    if (r > Fixed::kMaxRaw) return Fixed::FromRaw(Fixed::kMaxRaw);
    if (r < -int64_t{Fixed::kMaxRaw}) return Fixed::FromRaw(-Fixed::kMaxRaw);
    return Fixed::FromRaw(static_cast<int32_t>(r));
}

/// The tight box extended by b2_aabbExtension on every side.
b2AABB Fatten(const b2AABB& aabb) noexcept {
    const int64_t r = b2_aabbExtension.Raw();
    b2AABB b;
    b.lowerBound = {AddClamped(aabb.lowerBound.x, -r), AddClamped(aabb.lowerBound.y, -r)};
    b.upperBound = {AddClamped(aabb.upperBound.x, r), AddClamped(aabb.upperBound.y, r)};
    return b;
}

/// round(multiplier * v) in raw, exact in int64 (|raw product| < 2^62).
int64_t PredictRaw(Fixed v) noexcept {
    return detail::ShiftRound(int64_t{b2_aabbMultiplier.Raw()} * v.Raw(), Fixed::kFractionBits);
}

b2AABB Union(const b2AABB& a, const b2AABB& b) noexcept {
    b2AABB c;
    c.Combine(a, b);
    return c;
}

bool SameBox(const b2AABB& a, const b2AABB& b) noexcept {
    return a.lowerBound == b.lowerBound && a.upperBound == b.upperBound;
}

}  // namespace

b2DynamicTree::b2DynamicTree() {
    m_nodes.resize(kInitialCapacity);
    // Chain every slot into the free list in index order, as 2.2.1's constructor does.
    for (int32 i = 0; i < kInitialCapacity - 1; ++i) m_nodes[static_cast<size_t>(i)].next = i + 1;
    m_freeList = 0;
}

int32 b2DynamicTree::AllocateNode() {
    if (m_freeList == b2_nullNode) {
        // Pool full: double it and chain the new slots in index order.
        const int32 capacity = static_cast<int32>(m_nodes.size());
        LOCKBOX_ASSERT(m_nodeCount == capacity, "b2DynamicTree: the free list lost nodes");
        m_nodes.resize(static_cast<size_t>(capacity) * 2);
        for (int32 i = capacity; i < capacity * 2 - 1; ++i) m_nodes[static_cast<size_t>(i)].next = i + 1;
        m_freeList = capacity;
    }
    const int32 nodeId = m_freeList;
    b2TreeNode& node = m_nodes[static_cast<size_t>(nodeId)];
    m_freeList = node.next;
    node.next = b2_nullNode;
    node.parent = b2_nullNode;
    node.child1 = b2_nullNode;
    node.child2 = b2_nullNode;
    node.height = 0;
    node.userData = 0;
    ++m_nodeCount;
    return nodeId;
}

void b2DynamicTree::FreeNode(int32 nodeId) {
    LOCKBOX_ASSERT(0 <= nodeId && nodeId < static_cast<int32>(m_nodes.size()) && m_nodeCount > 0,
                   "b2DynamicTree: freeing a node the tree does not have");
    // Reset the slot to the one canonical free state, so that equal histories give equal pools
    // and a snapshot of free slots carries no stale data.
    b2TreeNode& node = m_nodes[static_cast<size_t>(nodeId)];
    node = b2TreeNode{};
    node.next = m_freeList;
    m_freeList = nodeId;
    --m_nodeCount;
}

int32 b2DynamicTree::CreateProxy(const b2AABB& aabb, uint64 userData) {
    const int32 proxyId = AllocateNode();
    b2TreeNode& node = m_nodes[static_cast<size_t>(proxyId)];
    node.aabb = Fatten(aabb);
    node.userData = userData;
    node.height = 0;
    InsertLeaf(proxyId);
    return proxyId;
}

void b2DynamicTree::DestroyProxy(int32 proxyId) {
    LOCKBOX_ASSERT(0 <= proxyId && proxyId < static_cast<int32>(m_nodes.size()),
                   "b2DynamicTree: a proxy id the tree never gave out");
    LOCKBOX_ASSERT(m_nodes[static_cast<size_t>(proxyId)].height == 0, "b2DynamicTree: not a live proxy");
    RemoveLeaf(proxyId);
    FreeNode(proxyId);
}

bool b2DynamicTree::MoveProxy(int32 proxyId, const b2AABB& aabb, const b2Vec2& displacement) {
    LOCKBOX_ASSERT(0 <= proxyId && proxyId < static_cast<int32>(m_nodes.size()),
                   "b2DynamicTree: a proxy id the tree never gave out");
    LOCKBOX_ASSERT(m_nodes[static_cast<size_t>(proxyId)].height == 0, "b2DynamicTree: not a live proxy");
    if (m_nodes[static_cast<size_t>(proxyId)].aabb.Contains(aabb)) return false;

    RemoveLeaf(proxyId);

    b2AABB b = Fatten(aabb);
    // Predict the motion: stretch the box on the side it moves towards (a zero component
    // stretches the upper side by zero, as 2.2.1's `d < 0 ? lower : upper`).
    const int64_t dx = PredictRaw(displacement.x);
    const int64_t dy = PredictRaw(displacement.y);
    if (dx < 0)
        b.lowerBound.x = AddClamped(b.lowerBound.x, dx);
    else
        b.upperBound.x = AddClamped(b.upperBound.x, dx);
    if (dy < 0)
        b.lowerBound.y = AddClamped(b.lowerBound.y, dy);
    else
        b.upperBound.y = AddClamped(b.upperBound.y, dy);
    m_nodes[static_cast<size_t>(proxyId)].aabb = b;

    InsertLeaf(proxyId);
    return true;
}

void b2DynamicTree::InsertLeaf(int32 leaf) {
    ++m_insertionCount;
    if (m_root == b2_nullNode) {
        m_root = leaf;
        m_nodes[static_cast<size_t>(leaf)].parent = b2_nullNode;
        return;
    }

    // Find the best sibling by the perimeter heuristic. Costs are exact Wide values, so equal
    // costs are real ties and are broken by the comparisons below, as in 2.2.1: stopping here
    // needs a cost strictly below both children's (a tie descends), and a tie between the
    // children descends into child2.
    const b2AABB leafAABB = m_nodes[static_cast<size_t>(leaf)].aabb;
    int32 index = m_root;
    while (!m_nodes[static_cast<size_t>(index)].IsLeaf()) {
        const b2TreeNode& node = m_nodes[static_cast<size_t>(index)];
        const int32 child1 = node.child1;
        const int32 child2 = node.child2;

        const Wide area = node.aabb.GetPerimeterWide();
        const Wide combinedArea = Union(node.aabb, leafAABB).GetPerimeterWide();

        // Cost of creating a new parent for this node and the new leaf.
        const Wide cost = combinedArea + combinedArea;
        // Minimum cost of pushing the leaf further down the tree.
        const Wide inheritanceCost = (combinedArea - area) + (combinedArea - area);

        // Cost of descending into a child: a leaf sibling pays the new parent's whole
        // perimeter, an internal child only its growth.
        auto descendCost = [&](int32 child) {
            const b2TreeNode& c = m_nodes[static_cast<size_t>(child)];
            const Wide newArea = Union(leafAABB, c.aabb).GetPerimeterWide();
            if (c.IsLeaf()) return newArea + inheritanceCost;
            return (newArea - c.aabb.GetPerimeterWide()) + inheritanceCost;
        };
        const Wide cost1 = descendCost(child1);
        const Wide cost2 = descendCost(child2);

        if (cost < cost1 && cost < cost2) break;
        index = cost1 < cost2 ? child1 : child2;
    }

    const int32 sibling = index;

    // Create a new parent above the sibling.
    const int32 oldParent = m_nodes[static_cast<size_t>(sibling)].parent;
    const int32 newParent = AllocateNode();
    {
        b2TreeNode& p = m_nodes[static_cast<size_t>(newParent)];
        p.parent = oldParent;
        p.userData = 0;
        p.aabb = Union(leafAABB, m_nodes[static_cast<size_t>(sibling)].aabb);
        p.height = m_nodes[static_cast<size_t>(sibling)].height + 1;
        p.child1 = sibling;
        p.child2 = leaf;
    }
    if (oldParent != b2_nullNode) {
        b2TreeNode& op = m_nodes[static_cast<size_t>(oldParent)];
        if (op.child1 == sibling)
            op.child1 = newParent;
        else
            op.child2 = newParent;
    } else {
        m_root = newParent;
    }
    m_nodes[static_cast<size_t>(sibling)].parent = newParent;
    m_nodes[static_cast<size_t>(leaf)].parent = newParent;

    Refit(m_nodes[static_cast<size_t>(leaf)].parent);
}

void b2DynamicTree::RemoveLeaf(int32 leaf) {
    if (leaf == m_root) {
        m_root = b2_nullNode;
        return;
    }

    const int32 parent = m_nodes[static_cast<size_t>(leaf)].parent;
    const int32 grandParent = m_nodes[static_cast<size_t>(parent)].parent;
    const b2TreeNode& p = m_nodes[static_cast<size_t>(parent)];
    const int32 sibling = p.child1 == leaf ? p.child2 : p.child1;

    if (grandParent != b2_nullNode) {
        // Destroy the parent and connect the sibling to the grandparent.
        b2TreeNode& g = m_nodes[static_cast<size_t>(grandParent)];
        if (g.child1 == parent)
            g.child1 = sibling;
        else
            g.child2 = sibling;
        m_nodes[static_cast<size_t>(sibling)].parent = grandParent;
        FreeNode(parent);
        Refit(grandParent);
    } else {
        m_root = sibling;
        m_nodes[static_cast<size_t>(sibling)].parent = b2_nullNode;
        FreeNode(parent);
    }
    // The leaf is detached; its parent link is meaningless until it is re-inserted.
    m_nodes[static_cast<size_t>(leaf)].parent = b2_nullNode;
}

void b2DynamicTree::Refit(int32 index) {
    // Walk back up, balancing and fixing heights and boxes (2.2.1 does this inline in both
    // InsertLeaf and RemoveLeaf; the order there differs only in height-before-box, which
    // touches disjoint fields).
    while (index != b2_nullNode) {
        index = Balance(index);
        b2TreeNode& node = m_nodes[static_cast<size_t>(index)];
        const b2TreeNode& c1 = m_nodes[static_cast<size_t>(node.child1)];
        const b2TreeNode& c2 = m_nodes[static_cast<size_t>(node.child2)];
        node.height = 1 + (c1.height > c2.height ? c1.height : c2.height);
        node.aabb.Combine(c1.aabb, c2.aabb);
        index = node.parent;
    }
}

int32 b2DynamicTree::Balance(int32 iA) {
    b2TreeNode* const nodes = m_nodes.data();  // no allocation below: pointers stay valid
    b2TreeNode* A = nodes + iA;
    if (A->IsLeaf() || A->height < 2) return iA;

    const int32 iB = A->child1;
    const int32 iC = A->child2;
    b2TreeNode* B = nodes + iB;
    b2TreeNode* C = nodes + iC;
    const int32 balance = C->height - B->height;

    // Rotate C up.
    if (balance > 1) {
        const int32 iF = C->child1;
        const int32 iG = C->child2;
        b2TreeNode* F = nodes + iF;
        b2TreeNode* G = nodes + iG;

        // Swap A and C.
        C->child1 = iA;
        C->parent = A->parent;
        A->parent = iC;

        // A's old parent points to C.
        if (C->parent != b2_nullNode) {
            b2TreeNode* P = nodes + C->parent;
            if (P->child1 == iA)
                P->child1 = iC;
            else
                P->child2 = iC;
        } else {
            m_root = iC;
        }

        // Keep the taller grandchild under C (a height tie keeps G, as 2.2.1).
        if (F->height > G->height) {
            C->child2 = iF;
            A->child2 = iG;
            G->parent = iA;
            A->aabb.Combine(B->aabb, G->aabb);
            C->aabb.Combine(A->aabb, F->aabb);
            A->height = 1 + (B->height > G->height ? B->height : G->height);
            C->height = 1 + (A->height > F->height ? A->height : F->height);
        } else {
            C->child2 = iG;
            A->child2 = iF;
            F->parent = iA;
            A->aabb.Combine(B->aabb, F->aabb);
            C->aabb.Combine(A->aabb, G->aabb);
            A->height = 1 + (B->height > F->height ? B->height : F->height);
            C->height = 1 + (A->height > G->height ? A->height : G->height);
        }
        return iC;
    }

    // Rotate B up.
    if (balance < -1) {
        const int32 iD = B->child1;
        const int32 iE = B->child2;
        b2TreeNode* D = nodes + iD;
        b2TreeNode* E = nodes + iE;

        // Swap A and B.
        B->child1 = iA;
        B->parent = A->parent;
        A->parent = iB;

        // A's old parent points to B.
        if (B->parent != b2_nullNode) {
            b2TreeNode* P = nodes + B->parent;
            if (P->child1 == iA)
                P->child1 = iB;
            else
                P->child2 = iB;
        } else {
            m_root = iB;
        }

        if (D->height > E->height) {
            B->child2 = iD;
            A->child1 = iE;
            E->parent = iA;
            A->aabb.Combine(C->aabb, E->aabb);
            B->aabb.Combine(A->aabb, D->aabb);
            A->height = 1 + (C->height > E->height ? C->height : E->height);
            B->height = 1 + (A->height > D->height ? A->height : D->height);
        } else {
            B->child2 = iE;
            A->child1 = iD;
            D->parent = iA;
            A->aabb.Combine(C->aabb, D->aabb);
            B->aabb.Combine(A->aabb, E->aabb);
            A->height = 1 + (C->height > D->height ? C->height : D->height);
            B->height = 1 + (A->height > E->height ? A->height : E->height);
        }
        return iB;
    }

    return iA;
}

int32 b2DynamicTree::GetHeight() const {
    if (m_root == b2_nullNode) return 0;
    return m_nodes[static_cast<size_t>(m_root)].height;
}

int32 b2DynamicTree::GetMaxBalance() const {
    int32 maxBalance = 0;
    for (const b2TreeNode& node : m_nodes) {
        if (node.height <= 1) continue;
        const int32 balance = std::abs(m_nodes[static_cast<size_t>(node.child2)].height -
                                       m_nodes[static_cast<size_t>(node.child1)].height);
        if (balance > maxBalance) maxBalance = balance;
    }
    return maxBalance;
}

Wide b2DynamicTree::GetAreaRatio() const {
    if (m_root == b2_nullNode) return Wide();
    const int64_t rootArea = m_nodes[static_cast<size_t>(m_root)].aabb.GetPerimeterWide().Raw();
    // A fat box always has a positive perimeter; the guard only protects hand-made states.
    if (rootArea <= 0) return Wide();
    // Each perimeter is below 2^50 raw, so the sum of up to 2^31 of them needs 128 bits.
    detail::U128 totalArea{0, 0};
    for (const b2TreeNode& node : m_nodes) {
        if (node.height < 0) continue;  // free slot
        totalArea = detail::AddU128(totalArea, static_cast<uint64_t>(node.aabb.GetPerimeterWide().Raw()));
    }
    // Q32.32 quotient total / root, truncated (a diagnostic; the ratio is below 2^31).
    const detail::U128 q = detail::DivModU128(detail::ShlU128(totalArea, Wide::kFractionBits),
                                              detail::U128{0, static_cast<uint64_t>(rootArea)})
                               .quot;
    if (q.hi != 0 || q.lo > static_cast<uint64_t>(Wide::kMaxRaw)) return Wide::FromRaw(Wide::kMaxRaw);
    return Wide::FromRaw(static_cast<int64_t>(q.lo));
}

void b2DynamicTree::RebuildBottomUp() {
    std::vector<int32> nodes;
    nodes.reserve(static_cast<size_t>(m_nodeCount));

    // Collect the leaves in index order and free the internal nodes.
    const int32 capacity = static_cast<int32>(m_nodes.size());
    for (int32 i = 0; i < capacity; ++i) {
        b2TreeNode& node = m_nodes[static_cast<size_t>(i)];
        if (node.height < 0) continue;
        if (node.IsLeaf()) {
            node.parent = b2_nullNode;
            nodes.push_back(i);
        } else {
            FreeNode(i);
        }
    }

    size_t count = nodes.size();
    while (count > 1) {
        // Greedy: join the pair with the smallest combined perimeter (strict <: the first
        // pair in (i, j) order wins a tie).
        Wide minCost = Wide::FromRaw(Wide::kMaxRaw);
        size_t iMin = 0;
        size_t jMin = 1;
        for (size_t i = 0; i < count; ++i) {
            const b2AABB& aabbi = m_nodes[static_cast<size_t>(nodes[i])].aabb;
            for (size_t j = i + 1; j < count; ++j) {
                const Wide cost = Union(aabbi, m_nodes[static_cast<size_t>(nodes[j])].aabb).GetPerimeterWide();
                if (cost < minCost) {
                    iMin = i;
                    jMin = j;
                    minCost = cost;
                }
            }
        }

        const int32 index1 = nodes[iMin];
        const int32 index2 = nodes[jMin];
        const int32 parentIndex = AllocateNode();
        b2TreeNode& parent = m_nodes[static_cast<size_t>(parentIndex)];
        b2TreeNode& child1 = m_nodes[static_cast<size_t>(index1)];
        b2TreeNode& child2 = m_nodes[static_cast<size_t>(index2)];
        parent.child1 = index1;
        parent.child2 = index2;
        parent.height = 1 + (child1.height > child2.height ? child1.height : child2.height);
        parent.aabb.Combine(child1.aabb, child2.aabb);
        parent.parent = b2_nullNode;
        child1.parent = parentIndex;
        child2.parent = parentIndex;

        nodes[jMin] = nodes[count - 1];
        nodes[iMin] = parentIndex;
        --count;
    }

    m_root = count == 0 ? b2_nullNode : nodes[0];
}

bool b2DynamicTree::Validate() const {
    const int32 capacity = static_cast<int32>(m_nodes.size());
    auto valid = [capacity](int32 i) { return 0 <= i && i < capacity; };

    // Free list: every entry free, no cycle (bounded by the capacity).
    int32 freeCount = 0;
    for (int32 i = m_freeList; i != b2_nullNode; i = m_nodes[static_cast<size_t>(i)].next) {
        if (!valid(i) || m_nodes[static_cast<size_t>(i)].height != -1 || ++freeCount > capacity) return false;
    }
    if (m_nodeCount + freeCount != capacity) return false;

    // Structure and metrics, depth first with an explicit stack; counting the visits bounds it
    // even on a corrupted (cyclic) tree.
    if (m_root == b2_nullNode) return m_nodeCount == 0;
    if (!valid(m_root) || m_nodes[static_cast<size_t>(m_root)].parent != b2_nullNode) return false;
    std::vector<int32> stack{m_root};
    int32 visited = 0;
    while (!stack.empty()) {
        const int32 index = stack.back();
        stack.pop_back();
        if (++visited > m_nodeCount) return false;
        const b2TreeNode& node = m_nodes[static_cast<size_t>(index)];
        if (node.next != b2_nullNode) return false;
        if (node.IsLeaf()) {
            if (node.child2 != b2_nullNode || node.height != 0) return false;
            if (!node.aabb.IsValid()) return false;
            continue;
        }
        if (!valid(node.child1) || !valid(node.child2)) return false;
        const b2TreeNode& c1 = m_nodes[static_cast<size_t>(node.child1)];
        const b2TreeNode& c2 = m_nodes[static_cast<size_t>(node.child2)];
        if (c1.parent != index || c2.parent != index) return false;
        if (c1.height < 0 || c2.height < 0) return false;
        if (node.height != 1 + (c1.height > c2.height ? c1.height : c2.height)) return false;
        if (!SameBox(node.aabb, Union(c1.aabb, c2.aabb))) return false;
        if (node.userData != 0) return false;
        stack.push_back(node.child1);
        stack.push_back(node.child2);
    }
    return visited == m_nodeCount;
}

// ---- Traversal stack ----------------------------------------------------------------------

void detail::b2TreeStack::PushSpill(int32 v) {
    const size_t slot = static_cast<size_t>(m_count - kInline);
    if (m_spill.size() <= slot)
        m_spill.push_back(v);
    else
        m_spill[slot] = v;
    ++m_count;
}

// ---- Ray helper -------------------------------------------------------------------------

namespace detail {

b2TreeRay::b2TreeRay(const b2Vec2& p1, const b2Vec2& p2, Fixed maxFraction) noexcept
    : m_p1(p1), m_dx(int64_t{p2.x.Raw()} - p1.x.Raw()), m_dy(int64_t{p2.y.Raw()} - p1.y.Raw()) {
    Clip(maxFraction);
}

namespace {
/// p + round(f * d) in raw, clamped to the Fixed range. |f.raw * d| < 2^63 needs 128 bits.
int64_t ClippedEnd(int32_t p, Fixed f, int64_t d) noexcept {
    const S128 q = ShrRoundS128(MulS64(f.Raw(), d), Fixed::kFractionBits);
    constexpr int64_t kMax = Fixed::kMaxRaw;
    if (!FitsS64(q)) return q.negative ? -kMax : kMax;
    const int64_t qs = ToS64(q);
    // |qs| can reach 2^62 with a huge fraction; clamp before adding so nothing overflows.
    if (qs > 2 * kMax) return kMax;
    if (qs < -2 * kMax) return -kMax;
    return p + qs;
}

Fixed ClampRaw(int64_t r) noexcept {
    constexpr int64_t kMax = Fixed::kMaxRaw;
    return Fixed::FromRaw(static_cast<int32_t>(r > kMax ? kMax : r < -kMax ? -kMax : r));
}
}  // namespace

void b2TreeRay::Clip(Fixed maxFraction) noexcept {
    // The true end p1 + f * d lies within half a raw of the rounded one, so one raw of slack
    // on each side of it keeps the box a superset of the exact segment.
    const int64_t tx = ClippedEnd(m_p1.x.Raw(), maxFraction, m_dx);
    const int64_t ty = ClippedEnd(m_p1.y.Raw(), maxFraction, m_dy);
    const int64_t px = m_p1.x.Raw();
    const int64_t py = m_p1.y.Raw();
    m_segmentAABB.lowerBound = {ClampRaw(px < tx - 1 ? px : tx - 1), ClampRaw(py < ty - 1 ? py : ty - 1)};
    m_segmentAABB.upperBound = {ClampRaw(px > tx + 1 ? px : tx + 1), ClampRaw(py > ty + 1 ? py : ty + 1)};
}

bool b2TreeRay::LineMisses(const b2AABB& box) const noexcept {
    // Doubled centre and extents are exact integers: c2 = lower + upper, h2 = upper - lower.
    const int64_t wx = 2 * int64_t{m_p1.x.Raw()} - box.lowerBound.x.Raw() - box.upperBound.x.Raw();
    const int64_t wy = 2 * int64_t{m_p1.y.Raw()} - box.lowerBound.y.Raw() - box.upperBound.y.Raw();
    const int64_t hx = int64_t{box.upperBound.x.Raw()} - box.lowerBound.x.Raw();
    const int64_t hy = int64_t{box.upperBound.y.Raw()} - box.lowerBound.y.Raw();
    const int64_t adx = m_dx < 0 ? -m_dx : m_dx;
    const int64_t ady = m_dy < 0 ? -m_dy : m_dy;
    // v = (-dy, dx): |dot(v, w)| against dot(|v|, h). With every factor below 2^31 (the ray
    // shorter than 32768 m and the box centre within 16384 m of p1, the usual case) each
    // product is below 2^62 and the sums fit int64; otherwise the terms reach 2^66 and the
    // same comparison runs in 128 bits. Both paths are exact, so they always agree.
    constexpr int64_t kSmall = int64_t{1} << 31;
    const int64_t awx = wx < 0 ? -wx : wx;
    const int64_t awy = wy < 0 ? -wy : wy;
    if (adx < kSmall && ady < kSmall && awx < kSmall && awy < kSmall && 0 <= hx && hx < kSmall && 0 <= hy &&
        hy < kSmall) {
        const int64_t sep = m_dx * wy - m_dy * wx;
        const int64_t reach = ady * hx + adx * hy;
        return (sep < 0 ? -sep : sep) > reach;
    }
    const S128 sep = SubS128(MulS64(m_dx, wy), MulS64(m_dy, wx));
    const S128 reach = AddS128(MulS64(ady, hx), MulS64(adx, hy));
    return LessU128(reach.mag, sep.mag);
}

}  // namespace detail

}  // namespace lockbox
