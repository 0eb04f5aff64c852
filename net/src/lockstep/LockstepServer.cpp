// The lockstep server (LockstepServer.h): slots and the handshake, inputs, timeouts and
// confirming frames. Hash comparison and late join are in LockstepServerJoin.cpp, datagrams
// in and out in LockstepServerIo.cpp.

#include <algorithm>

#include "lockbox/dynamics/World.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"
#include "lockstep/LockstepServerImpl.h"

namespace lockbox::net {
namespace {
constexpr int32_t kMaxInputsAhead = 1024;  // inputs accepted beyond the confirmed frame
using State = SlotInfo::State;
}  // namespace

LockstepServer::Impl::Impl(Transport& t, ServerConfig c) : transport(t), config(c) {
    config.playerCount = std::clamp<uint32_t>(config.playerCount, 1, kMaxPlayers);
    if (config.startPlayers == 0 || config.startPlayers > config.playerCount) config.startPlayers = config.playerCount;
    config.inputBytes = std::clamp<uint32_t>(config.inputBytes, 1, kMaxInputBytes);
    config.tickRate = std::clamp<uint32_t>(config.tickRate, 1, 1000);
    config.hashInterval = std::max<uint32_t>(config.hashInterval, 1);
    config.inputDelay = std::min<uint32_t>(config.inputDelay, 255);
    config.maxCatchUpFrames = std::max<uint32_t>(config.maxCatchUpFrames, 1);
    if (config.world == nullptr || config.game == nullptr) config.world = nullptr, config.game = nullptr;
    shape = SessionShape{config.playerCount, config.inputBytes};
    slots.resize(config.playerCount);
    tokenState = config.tokenSeed;
}

int32_t LockstepServer::Impl::SlotOf(PeerId peer) const noexcept {
    for (size_t i = 0; i < slots.size(); ++i)
        if (slots[i].peer == peer && slots[i].state != State::e_free && slots[i].state != State::e_disconnected)
            return static_cast<int32_t>(i);
    return -1;
}

uint32_t LockstepServer::Impl::NewToken() {
    for (;;) {
        // SplitMix64: tokens differ between sessions with different seeds and never repeat soon.
        uint64_t z = (tokenState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        const uint32_t t = static_cast<uint32_t>(z ^ (z >> 31));
        if (t == 0) continue;
        bool used = false;
        for (const Slot& s : slots) used = used || s.token == t;
        if (!used) return t;
    }
}

void LockstepServer::Impl::OnHello(PeerId peer, const Hello& hello, uint64_t now) {
    const int32_t own = SlotOf(peer);
    if (own >= 0) {
        // Our Welcome was lost: send it again, with this Hello's time for the RTT sample.
        Slot& slot = slots[static_cast<size_t>(own)];
        slot.welcome.echoTime = hello.clientTime;
        SendTo(peer, slot.welcome, slot.token, Delivery::e_reliable);
        return;
    }
    auto reject = [&](RejectReason r) {
        ++stats.rejected;
        SendTo(peer, Reject{r}, hello.token, Delivery::e_reliable);
    };
    if (hello.determinismVersion != b2_determinismVersion) return reject(RejectReason::e_determinismVersion);
    int32_t target = -1;
    if (config.admittedSlot) {
        // The admission decided the slot: a reconnect token or a requested slot may not move it.
        const int32_t allowed = config.admittedSlot(peer);
        if (allowed < 0 || static_cast<size_t>(allowed) >= slots.size()) return reject(RejectReason::e_badToken);
        const State st = slots[static_cast<size_t>(allowed)].state;
        if (hello.token != 0) {
            if (slots[static_cast<size_t>(allowed)].token != hello.token || st == State::e_free)
                return reject(RejectReason::e_badToken);
            if (st != State::e_disconnected) Drop(allowed, RejectReason::e_none);
        } else if (st != State::e_free && st != State::e_disconnected) {
            return reject(RejectReason::e_slotTaken);
        }
        target = allowed;
    } else if (hello.token != 0) {
        for (size_t i = 0; i < slots.size(); ++i)
            if (slots[i].token == hello.token && slots[i].state != State::e_free) target = static_cast<int32_t>(i);
        if (target < 0) return reject(RejectReason::e_badToken);
        // The owner came back under a new address: the old connection is dead.
        if (slots[static_cast<size_t>(target)].state != State::e_disconnected) Drop(target, RejectReason::e_none);
    } else if (hello.requestedSlot != kAnySlot) {
        if (hello.requestedSlot >= slots.size()) return reject(RejectReason::e_slotTaken);
        const State st = slots[hello.requestedSlot].state;
        if (st != State::e_free && st != State::e_disconnected) return reject(RejectReason::e_slotTaken);
        target = hello.requestedSlot;
    } else {
        // Free slots first; a dropped player's slot only when none is left.
        for (size_t i = 0; i < slots.size() && target < 0; ++i)
            if (slots[i].state == State::e_free) target = static_cast<int32_t>(i);
        for (size_t i = 0; i < slots.size() && target < 0; ++i)
            if (slots[i].state == State::e_disconnected) target = static_cast<int32_t>(i);
        if (target < 0) return reject(RejectReason::e_full);
    }
    Slot& slot = slots[static_cast<size_t>(target)];
    slot.peer = peer;
    if (hello.token == 0) slot.token = NewToken();
    slot.lastHeard = now;
    slot.lastSent = 0;
    slot.ackDirty = slot.pongPending = false;
    slot.hashNext = 0;
    slot.snapshot.Stop();
    slot.loaded = false;
    slot.admitFrame = -1;
    slot.desyncNotices = 0;
    Welcome& w = slot.welcome;
    w.slot = static_cast<uint8_t>(target);
    w.playerCount = static_cast<uint8_t>(config.playerCount);
    w.inputBytes = static_cast<uint16_t>(config.inputBytes);
    w.tickRate = static_cast<uint16_t>(config.tickRate);
    w.inputDelay = static_cast<uint8_t>(config.inputDelay);
    w.hashInterval = config.hashInterval;
    w.token = slot.token;
    w.echoTime = hello.clientTime;
    w.holdMicros = 0;
    if (!started) {
        slot.state = State::e_live;
        slot.requiredFrom = slot.inputBase = slot.nextInput = 0;
        slot.inputs.clear();
        slot.receivesConfirmed = true;
        slot.acked = slot.sentConfirmedEnd = 0;
        w.startFrame = 0;
        w.lateJoin = false;
    } else {
        // The slot plays empty input until Admit; its old inputs (a dropped player's) stay until then.
        slot.state = State::e_joining;
        slot.receivesConfirmed = false;
        w.startFrame = confirmedNext;
        w.lateJoin = true;
    }
    Event(Ev(ServerEvent::Kind::e_joined, target, peer, started ? -1 : 0));
    SendTo(peer, w, slot.token, Delivery::e_reliable);
}

void LockstepServer::Impl::Drop(int32_t s, RejectReason reason) {
    Slot& slot = slots[static_cast<size_t>(s)];
    if (slot.state == State::e_free || slot.state == State::e_disconnected) return;
    if (reason != RejectReason::e_timeout && reason != RejectReason::e_left && slot.peer != kNoPeer)
        SendTo(slot.peer, Disconnect{reason}, slot.token, Delivery::e_reliable);
    const PeerId peer = slot.peer;
    // From here the slot plays empty input for every frame it has not sent.
    const int32_t from = std::max(slot.nextInput, confirmedNext);
    slot.state = started ? State::e_disconnected : State::e_free;
    if (!started) slot.token = 0;
    slot.peer = kNoPeer;
    slot.snapshot.Stop();
    slot.admitFrame = -1;
    if (pullSource == s) {
        pullSource = -1;
        pull.Reset();
    }
    ServerEvent e = Ev(ServerEvent::Kind::e_disconnected, s, peer, from);
    e.reason = reason;
    Event(std::move(e));
    transport.Disconnect(peer);
}

void LockstepServer::Impl::OnInputs(int32_t s, PeerId peer, const Inputs& in) {
    Slot& slot = slots[static_cast<size_t>(s)];
    if (in.slot != s) {
        ++stats.spoofedInputs;
        ServerEvent e = Ev(ServerEvent::Kind::e_spoofedInput, s, peer, in.firstFrame);
        e.claimedSlot = in.slot;
        Event(std::move(e));
        return;
    }
    if (!slot.admitted()) return;  // a joiner before Admit plays empty input
    const int64_t count = static_cast<int64_t>(in.bytes.size() / shape.inputBytes);
    // Frames may arrive out of order (the client sends only its newest frames eagerly and
    // resends older ones after a timeout): keep each one, missing ones stay empty.
    for (int64_t k = 0; k < count; ++k) {
        const int64_t f = static_cast<int64_t>(in.firstFrame) + k;
        if (f < slot.nextInput) continue;
        if (f >= static_cast<int64_t>(confirmedNext) + kMaxInputsAhead) break;
        const size_t index = static_cast<size_t>(f - slot.inputBase);
        if (slot.inputs.size() <= index) slot.inputs.resize(index + 1);
        if (!slot.inputs[index].empty()) continue;
        const size_t at = static_cast<size_t>(k) * shape.inputBytes;
        slot.inputs[index].assign(in.bytes.begin() + static_cast<std::ptrdiff_t>(at),
                                  in.bytes.begin() + static_cast<std::ptrdiff_t>(at + shape.inputBytes));
    }
    while (static_cast<size_t>(slot.nextInput - slot.inputBase) < slot.inputs.size() &&
           !slot.inputs[static_cast<size_t>(slot.nextInput - slot.inputBase)].empty())
        ++slot.nextInput;
    slot.ackDirty = true;
    if (slot.admitFrame >= 0 && slot.nextInput > slot.admitFrame) slot.admitFrame = -1;
}

void LockstepServer::Impl::Timeouts(uint64_t now) {
    for (size_t i = 0; i < slots.size(); ++i) {
        Slot& slot = slots[i];
        if (slot.state != State::e_live && slot.state != State::e_interrupted && slot.state != State::e_joining)
            continue;
        const uint64_t silent = now - slot.lastHeard;
        if (silent >= config.disconnectMicros) {
            Drop(static_cast<int32_t>(i), RejectReason::e_timeout);
        } else if (silent >= config.interruptMicros && slot.state == State::e_live) {
            slot.state = State::e_interrupted;
            Event(Ev(ServerEvent::Kind::e_interrupted, static_cast<int32_t>(i), slot.peer, confirmedNext));
        }
    }
}

void LockstepServer::Impl::Confirm() {
    if (!started) {
        uint32_t filled = 0;
        for (const Slot& s : slots) filled += s.admitted() ? 1u : 0u;
        if (filled < config.startPlayers) return;
        started = true;
        Event(Ev(ServerEvent::Kind::e_started, -1, kNoPeer, 0));
    }
    const size_t width = shape.inputBytes;
    // Bounded: inputs are accepted at most kMaxInputsAhead frames past confirmedNext.
    for (int32_t n = 0; n < kMaxInputsAhead; ++n) {
        const int32_t f = confirmedNext;
        bool anyLive = false;
        for (const Slot& s : slots) {
            if (!s.admitted() || f < s.requiredFrom) continue;
            if (s.nextInput <= f) return;  // still waiting
            anyLive = true;
        }
        // With no live player nothing paces the match: it pauses until someone (re)joins.
        if (!anyLive) return;
        // Every live slot has its input: the row is final. Others play empty input.
        const size_t at = history.size();
        history.resize(at + RowBytes(), 0);
        for (size_t i = 0; i < slots.size(); ++i) {
            Slot& s = slots[i];
            if (f >= s.inputBase && f < s.nextInput && !s.inputs.empty())
                std::copy(s.inputs.front().begin(), s.inputs.front().end(),
                          history.begin() + static_cast<std::ptrdiff_t>(at + i * width));
            while (!s.inputs.empty() && s.inputBase <= f) {
                s.inputs.pop_front();
                ++s.inputBase;
            }
            if (s.inputBase <= f) s.inputBase = f + 1;
            if (s.nextInput <= f) {
                // A slot that did not send f (not required): nothing late is taken, and frames
                // that arrived ahead of the gap count from here.
                s.nextInput = f + 1;
                while (static_cast<size_t>(s.nextInput - s.inputBase) < s.inputs.size() &&
                       !s.inputs[static_cast<size_t>(s.nextInput - s.inputBase)].empty())
                    ++s.nextInput;
            }
        }
        ++confirmedNext;
        stats.confirmedFrames = confirmedNext;
    }
}

void LockstepServer::Impl::Simulate() {
    if (config.world == nullptr) return;
    for (uint32_t n = 0; n < config.maxCatchUpFrames && simulated < confirmedNext; ++n) {
        const std::span<const uint8_t> row(Row(simulated), RowBytes());
        AdvanceWorldFrame(*config.world, *config.game, static_cast<int32_t>(simulated), row,
                          {config.tickRate, config.velocityIterations, config.positionIterations});
        if (simulated % static_cast<int64_t>(config.hashInterval) == 0)
            OnHash(-1, simulated, FoldedStateHash(*config.world, *config.game));
        ++simulated;
    }
}

// ---- public ----

LockstepServer::LockstepServer(Transport& transport, ServerConfig config)
    : m_impl(std::make_unique<Impl>(transport, config)) {}
LockstepServer::~LockstepServer() = default;

void LockstepServer::Update() {
    Impl& s = *m_impl;
    if (s.closed) return;
    const uint64_t now = s.transport.NowMicros();
    s.Receive(now);
    s.Timeouts(now);
    s.Confirm();
    s.Simulate();
    s.Snapshots(now);
    s.SendAll(now);
    s.TrimHistory();
}

void LockstepServer::Close() {
    Impl& s = *m_impl;
    if (s.closed) return;
    for (Impl::Slot& slot : s.slots)
        if (slot.peer != kNoPeer && slot.state != State::e_free && slot.state != State::e_disconnected)
            s.SendTo(slot.peer, Disconnect{RejectReason::e_serverClosing}, slot.token, Delivery::e_reliable);
    s.closed = true;
}

std::vector<ServerEvent> LockstepServer::TakeEvents() {
    std::vector<ServerEvent> out;
    out.swap(m_impl->events);
    return out;
}
const ServerStats& LockstepServer::Stats() const noexcept { return m_impl->stats; }
const ServerConfig& LockstepServer::Config() const noexcept { return m_impl->config; }
int32_t LockstepServer::ConfirmedFrames() const noexcept { return m_impl->confirmedNext; }
bool LockstepServer::Started() const noexcept { return m_impl->started; }
int32_t LockstepServer::SimulatedFrames() const noexcept { return m_impl->simulated; }

SlotInfo LockstepServer::Slot(uint32_t slot) const {
    SlotInfo info;
    if (slot >= m_impl->slots.size()) return info;
    const Impl::Slot& s = m_impl->slots[slot];
    info.state = s.state;
    info.peer = s.peer;
    info.nextInputFrame = s.nextInput;
    info.ackedConfirmed = s.acked;
    return info;
}

std::span<const uint8_t> LockstepServer::ConfirmedInputs(int32_t frame) const {
    const Impl& s = *m_impl;
    if (frame < 0 || frame >= s.confirmedNext) return {};
    if (frame < s.historyBase) return {};
    return std::span<const uint8_t>(s.Row(frame), s.RowBytes());
}

}  // namespace lockbox::net
