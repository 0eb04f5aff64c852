#pragma once
// The lockstep server's state (LockstepServer.h), shared by LockstepServer.cpp (slots,
// confirmation, hashes, late join) and LockstepServerIo.cpp (receiving and sending).

#include <deque>
#include <map>
#include <vector>

#include "lockbox/net/LockstepServer.h"
#include "session/SessionCommon.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {

struct LockstepServer::Impl {
    /// One slot and the client holding it.
    struct Slot {
        SlotInfo::State state = SlotInfo::State::e_free;
        PeerId peer = kNoPeer;
        uint32_t token = 0;
        uint64_t lastHeard = 0, lastSent = 0;
        uint16_t sequence = 0;
        Welcome welcome;  ///< resent when a Hello is repeated
        // Inputs of frames [inputBase, inputBase + inputs.size()), an empty entry where a frame
        // is missing; every frame before nextInput is present. Required from requiredFrom on.
        int32_t requiredFrom = 0;
        int32_t inputBase = 0, nextInput = 0;
        std::deque<std::vector<uint8_t>> inputs;
        bool ackDirty = false;
        int32_t acked = 0;  ///< the client holds every confirmed frame before this
        int32_t sentConfirmedEnd = 0;
        int32_t hashNext = 0;  ///< InputAck.hashFrame
        bool pongPending = false;
        uint64_t pongEcho = 0, pongAt = 0;
        // Late join.
        bool receivesConfirmed = false;  ///< false while a joiner waits for its snapshot
        SnapshotSender snapshot;
        bool loaded = false;      ///< joiner acked the whole snapshot
        int32_t admitFrame = -1;  ///< Admit sent until inputs of this frame arrive
        uint32_t desyncNotices = 0;
        bool admitted() const noexcept {
            return state == SlotInfo::State::e_live || state == SlotInfo::State::e_interrupted;
        }
    };
    /// Hash reports of one frame.
    struct HashRecord {
        std::vector<uint64_t> hash;
        std::vector<uint8_t> have;
        bool haveServer = false, mismatch = false;
        uint64_t server = 0;
    };

    Impl(Transport& t, ServerConfig c);

    Transport& transport;
    ServerConfig config;
    SessionShape shape;
    std::vector<Slot> slots;
    bool started = false, closed = false;
    uint64_t tokenState = 0;

    std::vector<uint8_t> history;  ///< confirmed rows of frames [historyBase, confirmedNext)
    int32_t historyBase = 0;
    /// Row of a confirmed frame still kept (historyBase <= f < confirmedNext).
    const uint8_t* Row(int32_t f) const noexcept {
        return history.data() + static_cast<size_t>(f - historyBase) * RowBytes();
    }
    int32_t confirmedNext = 0;
    int32_t simulated = 0;  ///< authoritative mode: next frame to step

    std::map<int32_t, HashRecord> hashes;
    bool desyncRaised = false;
    int32_t desyncFrame = -1;

    // Relay-mode snapshot pulled from a live client.
    SnapshotReceiver pull;
    int32_t pullSource = -1;
    uint64_t pullRequestedAt = 0;
    int32_t cacheFrame = 0;
    CompressedSnapshot cache;  ///< null: none

    std::vector<ServerEvent> events;
    ServerStats stats;
    DatagramWriter writer;
    std::vector<Datagram> inbox;
    std::vector<Message> messages;

    uint64_t Tick() const noexcept { return TickMicros(config.tickRate); }
    size_t RowBytes() const noexcept { return size_t{shape.playerCount} * shape.inputBytes; }
    int32_t SlotOf(PeerId peer) const noexcept;
    void Event(ServerEvent e) { events.push_back(std::move(e)); }
    static ServerEvent Ev(ServerEvent::Kind kind, int32_t slot, PeerId peer, int32_t frame) {
        ServerEvent e;
        e.kind = kind;
        e.slot = slot;
        e.peer = peer;
        e.frame = frame;
        return e;
    }
    uint32_t NewToken();

    // LockstepServer.cpp
    void OnHello(PeerId peer, const Hello& hello, uint64_t now);
    void OnInputs(int32_t s, PeerId peer, const Inputs& in);
    void OnHash(int32_t s, int32_t frame, uint64_t hash);
    void Drop(int32_t s, RejectReason reason);
    void Timeouts(uint64_t now);
    void Confirm();
    void Simulate();
    // LockstepServerJoin.cpp
    void Admit(int32_t s);
    void Snapshots(uint64_t now);
    void TrimHistory();
    // LockstepServerIo.cpp
    void Receive(uint64_t now);
    void Handle(int32_t s, PeerId peer, const Message& m, uint64_t now);
    void Begin(Slot& slot);
    void SendTo(PeerId peer, const Message& m, uint32_t token, Delivery d);
    void SendAll(uint64_t now);
    void SendSlot(int32_t s, uint64_t now);
};

}  // namespace lockbox::net
