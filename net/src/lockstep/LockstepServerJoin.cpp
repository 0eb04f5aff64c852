// The lockstep server's hash comparison and late join (LockstepServer.h): desync detection,
// admitting joiners whose hash matches, serving snapshots, and trimming the confirmed history.

#include <algorithm>

#include "lockbox/net/LockstepClient.h"
#include "lockstep/LockstepServerImpl.h"

namespace lockbox::net {
namespace {
constexpr int32_t kHashWindow = 1200;  // frames of hash reports kept for comparison
constexpr uint64_t kPullRetryMicros = 200'000;
constexpr uint32_t kDesyncNotices = 5;  // datagrams that carry the DesyncNotice
constexpr int64_t kTrimBlock = 1024;    // confirmed rows dropped at a time
using State = SlotInfo::State;
}  // namespace

void LockstepServer::Impl::Admit(int32_t s) {
    Slot& slot = slots[static_cast<size_t>(s)];
    // Two frames of margin: the frame being confirmed now may already be on its way.
    const int32_t join = confirmedNext + 2;
    slot.state = State::e_live;
    slot.requiredFrom = slot.inputBase = slot.nextInput = join;
    slot.inputs.clear();
    slot.admitFrame = join;
    slot.ackDirty = true;
    Event(Ev(ServerEvent::Kind::e_admitted, s, slot.peer, join));
}

void LockstepServer::Impl::OnHash(int32_t s, int32_t frame, uint64_t hash) {
    if (frame >= confirmedNext || frame < confirmedNext - kHashWindow) return;  // only confirmed, recent frames
    HashRecord& rec = hashes[frame];
    if (rec.hash.empty()) {
        rec.hash.assign(slots.size(), 0);
        rec.have.assign(slots.size(), 0);
    }
    if (s < 0) {
        rec.haveServer = true;
        rec.server = hash;
    } else {
        if (rec.have[static_cast<size_t>(s)]) return;  // a resent report
        rec.have[static_cast<size_t>(s)] = 1;
        rec.hash[static_cast<size_t>(s)] = hash;
    }
    // The reference: the server's own hash, else the lowest admitted slot's report.
    bool haveRef = rec.haveServer;
    uint64_t ref = rec.server;
    bool mismatch = false;
    for (size_t i = 0; i < slots.size(); ++i) {
        if (!rec.have[i] || slots[i].state == State::e_joining) continue;
        if (!haveRef) {
            haveRef = true;
            ref = rec.hash[i];
        } else if (rec.hash[i] != ref) {
            mismatch = true;
        }
    }
    if (mismatch && !rec.mismatch) {
        rec.mismatch = true;
        ++stats.desyncFrames;
        if (!desyncRaised) {
            // One event for the first diverging frame: every later frame differs too.
            desyncRaised = true;
            desyncFrame = frame;
            ServerEvent e = Ev(ServerEvent::Kind::e_desync, -1, kNoPeer, frame);
            if (rec.haveServer) e.hashes.push_back(SlotHash{-1, rec.server});
            for (size_t i = 0; i < slots.size(); ++i)
                if (rec.have[i]) e.hashes.push_back(SlotHash{static_cast<int32_t>(i), rec.hash[i]});
            Event(std::move(e));
            for (Slot& slot : slots) slot.desyncNotices = kDesyncNotices;
        }
    }
    // Joiners waiting on this frame: admit on a match, drop on a mismatch.
    if (haveRef) {
        for (size_t i = 0; i < slots.size(); ++i) {
            if (!rec.have[i] || slots[i].state != State::e_joining) continue;
            if (rec.hash[i] == ref) {
                Admit(static_cast<int32_t>(i));
            } else {
                ServerEvent e = Ev(ServerEvent::Kind::e_joinFailed, static_cast<int32_t>(i), slots[i].peer, frame);
                e.reason = RejectReason::e_hashMismatch;
                Event(std::move(e));
                Drop(static_cast<int32_t>(i), RejectReason::e_hashMismatch);
            }
        }
    }
    while (!hashes.empty() && hashes.begin()->first < confirmedNext - kHashWindow) hashes.erase(hashes.begin());
}

void LockstepServer::Impl::Snapshots(uint64_t now) {
    // Joiners served in the same tick share one saved and compressed state.
    CompressedSnapshot current;
    for (size_t i = 0; i < slots.size(); ++i) {
        Slot& slot = slots[i];
        if (slot.state != State::e_joining || slot.snapshot.Active() || slot.loaded) continue;
        if (config.world != nullptr) {
            if (simulated != confirmedNext) continue;  // serve a state every confirmed input is known for
            if (current == nullptr)
                current = SnapshotSender::Compress(LockstepClient::SnapshotBlob(*config.world, *config.game));
            slot.snapshot.Start(simulated, current);
            continue;
        }
        // Relay mode: a recent snapshot from a live client (10 s of fast-forward at most).
        if (cache != nullptr &&
            static_cast<int64_t>(cacheFrame) + 10 * static_cast<int64_t>(config.tickRate) >= confirmedNext) {
            slot.snapshot.Start(cacheFrame, cache);
            continue;
        }
        if (pullSource < 0) {
            for (size_t j = 0; j < slots.size() && pullSource < 0; ++j)
                if (slots[j].state == State::e_live && slots[j].receivesConfirmed && slots[j].peer != kNoPeer)
                    pullSource = static_cast<int32_t>(j);
            pull.Reset();
            pullRequestedAt = 0;
        }
        if (pullSource >= 0 && !pull.Active() && (pullRequestedAt == 0 || now - pullRequestedAt >= kPullRetryMicros)) {
            const Slot& src = slots[static_cast<size_t>(pullSource)];
            SendTo(src.peer, SnapshotRequest{std::max(0, confirmedNext - 2 * static_cast<int32_t>(config.tickRate))},
                   src.token, Delivery::e_reliable);
            pullRequestedAt = now == 0 ? 1 : now;
        }
    }
}

void LockstepServer::Impl::TrimHistory() {
    // Keep what a client may still need resent, what a late joiner fast-forwards through (a
    // cached snapshot's frame, or a fresh snapshot of a client up to 10 s behind), and what the
    // authoritative world has not stepped; trim in blocks so the erase cost is amortized.
    int64_t keep = static_cast<int64_t>(confirmedNext) - 10 * static_cast<int64_t>(config.tickRate);
    for (const Slot& s : slots)
        if (s.receivesConfirmed && s.state != State::e_free && s.state != State::e_disconnected)
            keep = std::min<int64_t>(keep, s.acked);
    if (cache != nullptr) keep = std::min<int64_t>(keep, cacheFrame);
    for (const Slot& s : slots)
        if (s.snapshot.Active()) keep = std::min<int64_t>(keep, s.snapshot.Frame());
    if (config.world != nullptr) keep = std::min<int64_t>(keep, simulated);
    if (keep - historyBase < kTrimBlock) return;
    const size_t rows = static_cast<size_t>(keep - historyBase);
    history.erase(history.begin(), history.begin() + static_cast<std::ptrdiff_t>(rows * RowBytes()));
    historyBase = static_cast<int32_t>(keep);
}

}  // namespace lockbox::net
