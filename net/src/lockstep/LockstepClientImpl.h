#pragma once
// The lockstep client's state (LockstepClient.h), shared by LockstepClient.cpp (session,
// inputs, stepping) and LockstepClientIo.cpp (receiving and sending datagrams).

#include <deque>
#include <vector>

#include "lockbox/net/LockstepClient.h"
#include "session/SessionCommon.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {

struct LockstepClient::Impl {
    Impl(Transport& t, PeerId s, ClientConfig c, b2World& w, WorldGame& g)
        : transport(t), server(s), config(c), world(w), game(g) {}

    Transport& transport;
    PeerId server;
    ClientConfig config;
    b2World& world;
    WorldGame& game;

    ClientState state = ClientState::e_connecting;
    SessionShape shape;
    int32_t slot = -1;
    uint32_t token = 0;
    uint32_t tickRate = 60;
    uint32_t hashInterval = 1;
    uint32_t serverDelay = 0;  ///< Welcome.inputDelay
    uint32_t delay = 0;        ///< the input delay in use (0 before it is known)
    int32_t startFrame = 0;

    // Time (microseconds on the transport's clock).
    uint64_t connectStart = 0, lastHello = 0, lastHeard = 0, lastSent = 0, lastPing = 0;
    bool interrupted = false, anySent = false;
    RttEstimator rtt;
    uint64_t rttMin = 0, rttMax = 0;

    // Simulation: frame = next frame to step; confirmed rows for [frame, confirmedEnd).
    int32_t frame = 0;
    int32_t confirmedEnd = 0;
    std::deque<std::vector<uint8_t>> confirmed;
    uint64_t lastHash = 0;
    ConfirmedFrameHook hook;

    // Local inputs not acknowledged yet: frames [unackedBase, nextInputFrame).
    int32_t unackedBase = 0, nextInputFrame = 0;
    std::deque<std::vector<uint8_t>> unacked;
    std::deque<uint64_t> unackedSentAt;  ///< first send time of each unacked input (0: not yet)
    uint64_t lastFullResend = 0;
    uint64_t inputEpoch = 0;
    uint64_t inputCount = 0;
    bool urgent = false;  ///< something worth a datagram right away (a new input, snapshot acks)

    // Hash reports not acknowledged yet (oldest first).
    struct PendingHash {
        HashReport report;
        uint32_t sends = 0;
        uint64_t lastSent = 0;
    };
    std::deque<PendingHash> hashes;
    int32_t confirmedAckSent = -1;
    int32_t desyncFrame = -1;

    // Late join: snapshot we receive; snapshot we serve when the server asks.
    SnapshotReceiver snapshotIn;
    std::vector<SnapshotAck> snapshotAcks;
    SnapshotSender snapshotOut;

    std::vector<ClientEvent> events;
    DecodeErrorCounts malformed{};
    uint16_t sequence = 0;
    DatagramWriter writer;
    std::vector<Datagram> inbox;
    std::vector<Message> messages;

    uint64_t Tick() const noexcept { return TickMicros(tickRate); }
    void Event(ClientEvent::Kind kind, int32_t f = -1, RejectReason reason = RejectReason::e_none) {
        events.push_back(ClientEvent{kind, f, reason});
    }
    void Close(ClientEvent::Kind kind, RejectReason reason) {
        if (state == ClientState::e_closed) return;
        state = ClientState::e_closed;
        Event(kind, frame, reason);
    }

    // LockstepClient.cpp
    void StartRunning(int32_t firstFrame, bool fillDelay);
    void UpdateDelay();
    void StepFrames();
    void Timeouts(uint64_t now);
    // LockstepClientIo.cpp
    void Receive(uint64_t now);
    void Handle(const Message& m, uint64_t now);
    void Send(uint64_t now);
    void SendHello(uint64_t now);
    void SendSnapshot(uint64_t now);
    void Begin(DatagramWriter& w);
};

}  // namespace lockbox::net
