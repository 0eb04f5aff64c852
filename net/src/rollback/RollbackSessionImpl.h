#pragma once
// The state behind RollbackSession (RollbackSession.h), shared by RollbackSession.cpp (inputs,
// requests, final hashes) and RollbackSessionFinality.cpp (remote views, the final frame,
// freezing and cutting a leaving player).

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <deque>
#include <map>
#include <utility>
#include <vector>

#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

namespace rbsession {

// Frames of inputs kept per player. The worst case a peer can lag behind our newest local
// input is about 2 * (window + delay) frames (docs/rollback.md), far below this.
inline constexpr int32_t kInputRing = 512;
// Final local hashes kept for comparison with late remote reports.
inline constexpr size_t kFinalKept = 64;
// Final local hashes offered to the network (FinalHashes()).
inline constexpr size_t kFinalOffered = 8;
// Remote hashes waiting for our own final hash of the same frame.
inline constexpr size_t kRemotePendingMax = 256;
// Hash slots: the final frame may trail the current one by up to kRollbackMaxFinalLag frames,
// and every hash between them must still be at hand when it becomes final.
inline constexpr int32_t kSaveSlots = static_cast<int32_t>(kRollbackMaxFinalLag) + 2;

inline int32_t Slot(int32_t frame, int32_t size) noexcept { return frame % size; }

}  // namespace rbsession

struct RollbackSession::Impl {
    struct Player {
        bool local = false;
        // Leaving: no input is taken any more; `received` stays where it was (frozenFrame)
        // until the cut is agreed. Inputs past it are predicted meanwhile.
        bool frozen = false;
        int32_t frozenFrame = -1;
        // Smallest frozen value known for this player (ours and every peer's report).
        int32_t pendingCut = INT32_MAX;
        bool disconnected = false;  // the cut is set: zeros from disconnectFrame on
        int32_t received = 0;       // frames before this are known
        int32_t disconnectFrame = INT32_MAX;
        // Frames a lowered input delay still owes: the local queue runs this much deeper than
        // the delay until as many repeated inputs have been absorbed (SetInputDelay).
        int32_t surplus = 0;
        uint64_t mispredicted = 0;  // remote inputs that differed from what a past Advance used
        std::vector<uint8_t> ring;  // kInputRing * inputBytes
        std::vector<int32_t> ringFrame;
    };
    struct SaveSlot {
        int32_t frame = -1;
        bool hasHash = false;
        uint64_t hash = 0;
    };
    using View = std::array<int32_t, kRollbackMaxPlayers>;

    RollbackConfig config;
    std::vector<Player> players;
    int32_t current = 0;
    bool started = false;
    bool synchronizing = false;  // the start phase holds every Advance (SetSynchronizing)
    bool stalled = false;
    int32_t firstIncorrect = INT32_MAX;
    // What the last Advance of each frame used: one row of players * inputBytes per frame.
    std::vector<uint8_t> used;
    std::vector<int32_t> usedFrame;
    std::vector<SaveSlot> saves;
    int32_t nextFinal = 0;  // frames before this had their final hash decided
    std::deque<std::pair<int32_t, uint64_t>> offered;
    std::map<int32_t, uint64_t> finals;  // frame -> final local hash (ordered: trimmed oldest first)
    std::map<std::pair<int32_t, uint32_t>, uint64_t> remotePending;  // (frame, peer) -> hash
    // Live remote peers' views (peer tag -> first frame it lacks, per player). Only the min
    // over them is ever read, so the map's order does not matter.
    std::map<uint32_t, View> views;
    std::vector<uint32_t> desyncedPeers;
    std::vector<RollbackEvent> events;
    RollbackStats stats;
    std::vector<uint8_t> scratch;

    size_t Bytes() const noexcept { return config.inputBytes; }
    size_t RowBytes() const noexcept { return config.inputBytes * config.players; }

    uint8_t* InputAt(Player& p, int32_t frame) {
        return p.ring.data() + rbsession::Slot(frame, rbsession::kInputRing) * Bytes();
    }

    void Store(Player& p, int32_t frame, std::span<const uint8_t> bytes) {
        std::memcpy(InputAt(p, frame), bytes.data(), Bytes());
        p.ringFrame[static_cast<size_t>(rbsession::Slot(frame, rbsession::kInputRing))] = frame;
        p.received = frame + 1;
    }

    // Whether local `next` may stand for a repeat of the player's latest queued input (while
    // a lowered input delay catches up): equal bytes, or what the game's RepeatTest accepts.
    bool IsRepeat(uint32_t player, Player& p, std::span<const uint8_t> next) {
        const std::span<const uint8_t> previous(InputAt(p, p.received - 1), Bytes());
        if (std::memcmp(previous.data(), next.data(), Bytes()) == 0) return true;
        return config.repeatTest && config.repeatTest(player, previous, next);
    }

    // First frame whose inputs this session does not all hold (a frozen player counts with
    // its frozen frame). The prediction window is measured from here.
    int32_t Held() const noexcept;
    // First frame that is not final: held here, held by every live remote peer as far as its
    // last view says, and below every frozen value known for a player still being cut.
    int32_t Final() const noexcept;
    // Fills one player's input for `frame` into `out`; returns its status.
    InputStatus InputFor(uint32_t index, int32_t frame, uint8_t* out);
    void EmitAdvance(std::vector<RollbackRequest>& out, int32_t frame, bool fresh);
    void EmitSave(std::vector<RollbackRequest>& out, int32_t frame);
    // Marks `frame` for re-simulation when the input a past Advance used for `player`
    // differs from `actual`; true when it did.
    bool CheckPast(uint32_t player, int32_t frame, const uint8_t* actual);
    void Compare(uint32_t peer, int32_t frame, uint64_t local, uint64_t remote);
    // Hashes of final frames that no pending rollback will re-simulate become final; compares
    // them with what the peers reported.
    void FinalizeHashes();
    // Sets the cut of a frozen player: zeros from `cut` on, rollback of frames simulated
    // otherwise, the e_disconnected event.
    void Cut(uint32_t index, int32_t cut);
};

}  // namespace lockbox::net
