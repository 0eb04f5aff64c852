#pragma once
// The leave scenarios of the disconnect agreement (rollback_disconnect_test.cpp and the heavy
// matrix): a peer leaves after its link to peer 0 died, and every survivor must cut it at the
// same frame with identical final hashes. Built on rollback_harness.h.

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "rollback_harness.h"

namespace lockbox::net::rbtest {

/// A leave scenario: `peers` peers, the last one leaves (abruptly, or with RbDisconnect when
/// `graceful`), on links with the given RTT, loss and jitter.
struct Leave {
    uint32_t peers, rtt, loss, jitter;
    bool graceful;
};

// The leaver is the last peer. Its link to peer 0 dies 30 ticks before it leaves, so peer 0
// holds fewer of its inputs than the others: the cut must be peer 0's frozen frame.
inline RbSpec LeaveSpec(const Leave& c, uint64_t seed) {
    RbSpec spec;
    spec.seed = seed;
    spec.peers = c.peers;
    spec.rttMs = c.rtt;
    spec.lossPct = c.loss;
    spec.jitterMs = c.jitter;
    spec.frames = 720;
    const uint32_t leaver = c.peers - 1;
    spec.linkCuts.push_back(RbLinkCut{leaver, 0, 150});
    spec.exits.push_back(RbExit{leaver, 180, c.graceful});
    return spec;
}

// What every survivor must show: one e_disconnected per leaver, at the same frame on all,
// equal to the smallest frozen frame (unless `anyMin`); identical final hashes, at least
// `after` frames past the last cut; no desync; no failed Execute or changed final hash.
// Returns the cut of each leaver.
inline std::map<uint32_t, int32_t> ExpectAgreement(const RbSpec& spec, const RbResult& r, int32_t after,
                                                   bool anyMin = false, std::vector<uint32_t> leavers = {}) {
    SCOPED_TRACE(spec.Describe());
    EXPECT_TRUE(r.finished) << "ticks=" << r.ticks;
    // Leavers: the peers that exit, unless the caller names them (a peer cut out by the
    // others while it still runs).
    std::vector<uint32_t> survivors;
    if (leavers.empty())
        for (uint32_t i = 0; i < spec.peers; ++i)
            if (spec.Gone(i, INT64_MAX)) leavers.push_back(i);
    for (uint32_t i = 0; i < spec.peers; ++i)
        if (std::find(leavers.begin(), leavers.end(), i) == leavers.end()) survivors.push_back(i);
    std::map<uint32_t, int32_t> cuts;
    for (uint32_t l : leavers) {
        int32_t minFrozen = INT32_MAX, maxFrozen = -1;
        for (uint32_t i : survivors) {
            const RbPeer& p = r.peers[i];
            std::vector<int32_t> frames;
            for (const RollbackEvent& e : p.events)
                if (e.kind == RollbackEvent::Kind::e_disconnected && e.player == l) frames.push_back(e.frame);
            EXPECT_EQ(frames.size(), 1u) << "peer " << i << " leaver " << l;
            if (frames.empty()) continue;
            if (cuts.count(l) == 0) cuts[l] = frames[0];
            EXPECT_EQ(frames[0], cuts[l]) << "peer " << i << " leaver " << l;
            EXPECT_EQ(p.session->CutFrame(l), frames[0]) << "peer " << i;
            minFrozen = std::min(minFrozen, p.session->FrozenFrame(l));
            maxFrozen = std::max(maxFrozen, p.session->FrozenFrame(l));
        }
        if (!anyMin && cuts.count(l)) {
            EXPECT_EQ(cuts[l], minFrozen) << "leaver " << l;
        }
        // Figures for docs/rollback.md: the frozen values, the cut, and the ticks from the
        // first survivor's freeze to the last survivor's cut.
        int64_t firstFreeze = INT64_MAX, lastCut = -1;
        for (uint32_t i : survivors) {
            const RbPeer& p = r.peers[i];
            if (auto it = p.frozenTick.find(l); it != p.frozenTick.end())
                firstFreeze = std::min(firstFreeze, it->second);
            if (auto it = p.cutTick.find(l); it != p.cutTick.end()) lastCut = std::max(lastCut, it->second);
        }
        std::printf("RBLEAVE %s | leaver %u frozen %d..%d cut %d, freeze->agreed %lld ticks\n", spec.Describe().c_str(),
                    l, minFrozen, maxFrozen, cuts.count(l) ? cuts[l] : -1,
                    static_cast<long long>(lastCut - firstFreeze));
    }
    int32_t lastCut = 0;
    for (const auto& [l, c] : cuts) lastCut = std::max(lastCut, c);
    for (size_t a = 0; a < survivors.size(); ++a) {
        const RbPeer& p = r.peers[survivors[a]];
        EXPECT_FALSE(p.executeFailed) << "peer " << survivors[a];
        EXPECT_FALSE(p.finalChanged) << "peer " << survivors[a];
        for (const RollbackEvent& e : p.events)
            EXPECT_NE(e.kind, RollbackEvent::Kind::e_desync) << "peer " << survivors[a] << " desync at " << e.frame;
        for (size_t b = a + 1; b < survivors.size(); ++b) {
            const RbPeer& q = r.peers[survivors[b]];
            size_t pastCut = 0;
            for (const auto& [f, h] : p.finals) {
                auto it = q.finals.find(f);
                if (it == q.finals.end()) continue;
                EXPECT_EQ(it->second, h) << "peers " << survivors[a] << "," << survivors[b] << " frame " << f;
                if (f >= lastCut) ++pastCut;
            }
            EXPECT_GE(pastCut, static_cast<size_t>(after / static_cast<int32_t>(spec.desyncInterval)) * 8 / 10)
                << "peers " << survivors[a] << "," << survivors[b];
        }
        EXPECT_GE(p.session->ConfirmedFrame(), lastCut + after) << "peer " << survivors[a];
    }
    if (spec.rttMs * 500u > spec.inputDelay * kTickMicros) {
        EXPECT_GT(r.Rollbacks(), 0u);
    }
    uint32_t deepest = 0;
    for (uint32_t i : survivors) deepest = std::max(deepest, r.peers[i].session->Stats().deepestRollback);
    std::printf("RBLEAVE %s | rollbacks %llu, deepest %u, ticks %lld\n", spec.Describe().c_str(),
                static_cast<unsigned long long>(r.Rollbacks()), deepest, static_cast<long long>(r.ticks));
    return cuts;
}

/// Plays one leave cell and checks it (ExpectAgreement over 300 frames past the cut), and
/// that the scenario is the one meant: peer 0 holds fewer of the leaver's inputs than another
/// survivor, so cutting at each one's own received frame would have diverged.
inline void RunLeaveCell(const Leave& c, uint64_t seed) {
    const RbSpec spec = LeaveSpec(c, seed);
    const RbResult r = RunRbMatch(spec);
    ExpectAgreement(spec, r, 300);
    const uint32_t leaver = c.peers - 1;
    int32_t others = -1;
    for (uint32_t i = 1; i < leaver; ++i) others = std::max(others, r.peers[i].session->FrozenFrame(leaver));
    EXPECT_LT(r.peers[0].session->FrozenFrame(leaver), others) << spec.Describe();
}

}  // namespace lockbox::net::rbtest
