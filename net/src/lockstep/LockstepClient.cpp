// The lockstep client (LockstepClient.h): session state, local inputs, the input delay and
// stepping confirmed frames. Datagrams in and out are in LockstepClientIo.cpp.

#include <algorithm>

#include "lockbox/dynamics/World.h"
#include "lockbox/state/WorldGame.h"
#include "lockstep/LockstepClientImpl.h"

namespace lockbox::net {

LockstepClient::LockstepClient(Transport& transport, PeerId server, ClientConfig config, b2World& world,
                               WorldGame& game)
    : m_impl(std::make_unique<Impl>(transport, server, config, world, game)) {
    Impl& s = *m_impl;
    s.config.maxCatchUpFrames = std::max<uint32_t>(s.config.maxCatchUpFrames, 1);
    s.config.maxAutoDelay = std::clamp<uint32_t>(s.config.maxAutoDelay, 1, 255);
    s.connectStart = transport.NowMicros();
    s.lastHeard = s.connectStart;
}

LockstepClient::~LockstepClient() = default;

void LockstepClient::Update() {
    Impl& s = *m_impl;
    const uint64_t now = s.transport.NowMicros();
    s.Receive(now);
    if (s.state == ClientState::e_closed) return;
    s.Timeouts(now);
    if (s.state == ClientState::e_closed) return;
    if (s.state == ClientState::e_syncing && s.rtt.Samples() >= kHandshakePings) {
        s.UpdateDelay();
        s.StartRunning(s.startFrame, true);
    }
    s.StepFrames();
    s.Send(now);
}

void LockstepClient::Impl::Timeouts(uint64_t now) {
    if (state == ClientState::e_connecting) {
        // Nobody answers the Hellos: give up after several disconnect timeouts.
        if (now - connectStart >= 5 * config.disconnectMicros)
            Close(ClientEvent::Kind::e_disconnected, RejectReason::e_timeout);
        return;
    }
    const uint64_t silent = now - lastHeard;
    if (silent >= config.disconnectMicros) {
        Close(ClientEvent::Kind::e_disconnected, RejectReason::e_timeout);
    } else if (silent >= config.interruptMicros && !interrupted) {
        interrupted = true;
        Event(ClientEvent::Kind::e_interrupted, frame);
    }
}

void LockstepClient::Impl::UpdateDelay() {
    const bool automatic = config.inputDelay == 0 || (config.inputDelay < 0 && serverDelay == 0);
    if (!automatic) {
        delay = config.inputDelay > 0 ? static_cast<uint32_t>(std::min(config.inputDelay, 255)) : serverDelay;
        return;
    }
    // Relay path: our input reaches the server, the confirmed frame comes back: one full RTT.
    // The samples' spread is added once more as the jitter margin, plus one frame of phase.
    const uint64_t tick = std::max<uint64_t>(Tick(), 1);
    const uint64_t budget = rttMax + (rttMax - rttMin);
    const uint64_t frames = (budget + tick - 1) / tick + 1;
    delay = static_cast<uint32_t>(std::clamp<uint64_t>(frames, 1, config.maxAutoDelay));
}

void LockstepClient::Impl::StartRunning(int32_t firstFrame, bool fillDelay) {
    if (delay == 0) UpdateDelay();
    unacked.clear();
    unackedSentAt.clear();
    unackedBase = firstFrame;
    nextInputFrame = firstFrame;
    if (fillDelay) {
        // The first `delay` frames have no local input yet: they are sent as empty inputs.
        for (uint32_t i = 0; i < delay; ++i) {
            unacked.emplace_back(shape.inputBytes, uint8_t{0});
            unackedSentAt.push_back(0);
            ++nextInputFrame;
        }
        urgent = true;
    }
    inputEpoch = transport.NowMicros();
    inputCount = 0;
    state = ClientState::e_running;
    Event(ClientEvent::Kind::e_running, nextInputFrame);
}

void LockstepClient::Impl::StepFrames() {
    if (state != ClientState::e_syncing && state != ClientState::e_running && state != ClientState::e_catchingUp)
        return;
    for (uint32_t n = 0; n < config.maxCatchUpFrames && !confirmed.empty(); ++n) {
        const std::vector<uint8_t>& row = confirmed.front();
        AdvanceWorldFrame(world, game, frame, row, {tickRate, config.velocityIterations, config.positionIterations});
        const uint64_t worldHash = world.Hash();
        lastHash = FoldUserState(worldHash, game);
        if (config.reportHashes && frame % static_cast<int64_t>(hashInterval) == 0) {
            hashes.push_back(Impl::PendingHash{HashReport{frame, lastHash}, 0, 0});
            // A server that never acks must not make us grow without bound.
            if (hashes.size() > 64) hashes.pop_front();
        }
        if (hook) hook(frame, row, worldHash, world);
        confirmed.pop_front();
        ++frame;
    }
}

bool LockstepClient::WantsInput() const {
    const Impl& s = *m_impl;
    if (s.state != ClientState::e_running) return false;
    const int64_t window = static_cast<int64_t>(s.frame) + s.delay;
    if (s.nextInputFrame > window) return false;
    // The clock sets the pace: one input per tick. (Hurrying when the window allows more would
    // let the match run faster than the tick rate whenever confirmations arrive in pairs.)
    const uint64_t due = s.inputEpoch + s.inputCount * 1'000'000u / s.tickRate;
    return s.transport.NowMicros() >= due;
}

bool LockstepClient::SubmitLocalInput(std::span<const uint8_t> input) {
    Impl& s = *m_impl;
    if (s.state != ClientState::e_running) return false;
    if (static_cast<int64_t>(s.nextInputFrame) > static_cast<int64_t>(s.frame) + s.delay) return false;
    std::vector<uint8_t> bytes(s.shape.inputBytes, 0);
    std::copy_n(input.begin(), std::min<size_t>(input.size(), bytes.size()), bytes.begin());
    s.unacked.push_back(std::move(bytes));
    s.unackedSentAt.push_back(0);
    ++s.nextInputFrame;
    ++s.inputCount;
    const uint64_t now = s.transport.NowMicros();
    const uint64_t tick = s.Tick();
    // Far behind the clock (a stall): restart the pacing instead of bursting to catch up.
    if (now > s.inputEpoch + s.inputCount * 1'000'000u / s.tickRate + 4 * tick) {
        s.inputEpoch = now;
        s.inputCount = 1;
    }
    s.urgent = true;
    // Out at once when the pacing allows: one Update period less of input latency.
    s.Send(now);
    return true;
}

int32_t LockstepClient::NextInputFrame() const noexcept { return m_impl->nextInputFrame; }

void LockstepClient::Leave() {
    Impl& s = *m_impl;
    if (s.state == ClientState::e_closed) return;
    if (s.token != 0) {
        // Three copies: the server also times us out if all of them are lost.
        for (int i = 0; i < 3; ++i) {
            s.Begin(s.writer);
            s.writer.Add(Disconnect{RejectReason::e_left}, s.shape);
            s.transport.Send(s.server, s.writer.Bytes(), Delivery::e_reliable);
        }
    }
    s.Close(ClientEvent::Kind::e_disconnected, RejectReason::e_left);
}

void LockstepClient::SetConfirmedFrameHook(ConfirmedFrameHook hook) { m_impl->hook = std::move(hook); }

std::vector<ClientEvent> LockstepClient::TakeEvents() {
    std::vector<ClientEvent> out;
    out.swap(m_impl->events);
    return out;
}

ClientState LockstepClient::State() const noexcept { return m_impl->state; }
int32_t LockstepClient::Frame() const noexcept { return m_impl->frame; }
int32_t LockstepClient::Slot() const noexcept { return m_impl->slot; }
uint32_t LockstepClient::Token() const noexcept { return m_impl->token; }
uint32_t LockstepClient::InputDelay() const noexcept { return m_impl->delay; }
uint64_t LockstepClient::RttMicros() const noexcept { return m_impl->rtt.Srtt(); }
uint64_t LockstepClient::JitterMicros() const noexcept { return m_impl->rtt.Var(); }
uint64_t LockstepClient::LastHash() const noexcept { return m_impl->lastHash; }
SessionShape LockstepClient::Shape() const noexcept { return m_impl->shape; }
const DecodeErrorCounts& LockstepClient::Malformed() const noexcept { return m_impl->malformed; }

uint64_t LockstepClient::StateHash(const b2World& world, const WorldGame& game) { return FoldedStateHash(world, game); }

std::vector<uint8_t> LockstepClient::SnapshotBlob(const b2World& world, const WorldGame& game) {
    std::vector<uint8> image;
    world.Save(image);
    std::vector<uint8> user;
    game.SaveUserState(user);
    std::vector<uint8_t> blob;
    PackStateBlob(image, user, blob);
    return blob;
}

bool LockstepClient::LoadSnapshotBlob(std::span<const uint8_t> blob, b2World& world, WorldGame& game) {
    return LoadStateBlob(blob, world, game);
}

}  // namespace lockbox::net
