// RollbackPeer: a rollback session's datagrams over a Transport (RollbackPeer.h).

#include "lockbox/net/RollbackPeer.h"

#include <algorithm>
#include <array>
#include <deque>
#include <map>

#include "rollback/RollbackPeerRemote.h"
#include "rollback/RollbackSnapshotHost.h"

namespace lockbox::net {

namespace {

// Advantage samples averaged for time sync: enough to smooth jitter, few enough to follow a
// change within a fraction of a second at 60 Hz.
constexpr size_t kAdvantageSamples = 16;
// Each final hash goes out in this many datagrams to each remote: at 20 % loss all copies
// are lost 0.8 % of the time, which only skips that comparison, and no acks are needed.
constexpr uint8_t kHashCopies = 3;
// Bit rates (RemoteStats) are measured over windows of this length.
constexpr uint64_t kRateWindowMicros = 1000000;
// IPv4 + UDP header bytes counted per datagram in the bit rates.
constexpr uint64_t kDatagramHeaderBytes = 28;

int32_t ClampMilli(int64_t v) noexcept { return static_cast<int32_t>(std::clamp<int64_t>(v, -1000000000, 1000000000)); }

int32_t Average(const std::deque<int32_t>& v) noexcept {
    if (v.empty()) return 0;
    int64_t sum = 0;
    for (int32_t x : v) sum += x;
    return static_cast<int32_t>(sum / static_cast<int64_t>(v.size()));
}

void Push(std::deque<int32_t>& v, int32_t x) {
    v.push_back(x);
    while (v.size() > kAdvantageSamples) v.pop_front();
}

}  // namespace

RollbackPeer::RollbackPeer(RollbackSession& session, Transport& transport, RollbackPeerConfig config)
    : m_session(session), m_transport(transport), m_config(std::move(config)) {
    if (m_config.tickRate == 0) m_config.tickRate = 1;
    if (m_config.waitSpacingTicks == 0) m_config.waitSpacingTicks = 1;
    m_shape = RollbackShape{m_session.Config().players, m_session.Config().inputBytes};
    const uint64_t now = m_transport.NowMicros();
    for (const RollbackRemote& rr : m_config.remotes) {
        Remote r;
        r.peer = rr.peer;
        r.index = static_cast<uint32_t>(m_remotes.size());
        for (uint32_t p : rr.players)
            if (p < m_session.Config().players && !m_session.IsLocal(p)) r.players.push_back(p);
        r.lastHeard = now;
        r.windowStart = now;
        // Registered before its first datagram: until this remote reports what it holds,
        // nothing becomes final (it may hold nothing yet).
        const std::vector<int32_t> nothing(m_session.Config().players, 0);
        m_session.SetPeerView(r.index, nothing);
        m_remotes.push_back(std::move(r));
    }
    if (m_config.snapshotResendMicros == 0) m_config.snapshotResendMicros = 1;
    if (m_config.snapshotChunksPerFlush == 0) m_config.snapshotChunksPerFlush = 1;
    for (PeerId sp : m_config.spectators) {
        Spectator s;
        s.peer = sp;
        m_spectators.push_back(std::move(s));
    }
    m_localPlayers = m_session.Config().localPlayers;
    if (m_config.startTimeoutMicros == 0) m_config.startTimeoutMicros = 1;
    m_startedAt = now;
    if (m_remotes.empty()) {
        m_state = RollbackPeerState::e_running;  // nobody to wait for (a host of spectators only)
    } else {
        m_session.SetSynchronizing(true);
    }
}

const char* RollbackPeerStateName(RollbackPeerState state) noexcept {
    switch (state) {
        case RollbackPeerState::e_synchronizing: return "synchronizing";
        case RollbackPeerState::e_running: return "running";
        case RollbackPeerState::e_startFailed: return "start failed";
    }
    return "unknown";
}

RollbackPeer::~RollbackPeer() = default;

RollbackPeer::Remote* RollbackPeer::Find(PeerId peer) {
    for (Remote& r : m_remotes)
        if (r.peer == peer) return &r;
    return nullptr;
}

void RollbackPeer::ForgetSilentSpectators(uint64_t now) {
    const auto silent = [&](const Spectator& s) {
        return s.late && now - std::min(now, s.lastHeard) > m_config.lateSpectatorTimeoutMicros;
    };
    const auto gone = static_cast<uint32_t>(std::count_if(m_spectators.begin(), m_spectators.end(), silent));
    if (gone == 0) return;
    m_spectators.erase(std::remove_if(m_spectators.begin(), m_spectators.end(), silent), m_spectators.end());
    m_lateSpectators -= gone;
}

void RollbackPeer::Poll() {
    m_inbox.clear();
    m_transport.Poll(m_inbox);
    const uint64_t now = m_transport.NowMicros();
    for (const Datagram& d : m_inbox) {
        RollbackHeader header;
        const DecodeError error = DecodeRollbackDatagram(d.bytes, m_shape, header, m_messages);
        Remote* r = Find(d.peer);
        Spectator* spec = r == nullptr ? FindSpectator(d.peer) : nullptr;
        // A stranger showing any reason is refused like any bad datagram; a known sender is
        // also named (once) and refused from then on.
        const RollbackIncompatibility why =
            FindIncompatibility(error, header, m_messages, m_config.matchId, m_config.determinismVersion);
        if (why != RollbackIncompatibility::e_none) {
            // Named once; refused from now on, so the remote times out as a silent one would.
            if (r != nullptr && r->alive && r->incompatible == RollbackIncompatibility::e_none) {
                r->incompatible = why;
                m_session.RaiseIncompatible(r->index, why);
            }
            if (spec != nullptr) spec->incompatible = true;
        }
        // A match id other than ours is a reason too (FindIncompatibility), so it is refused here.
        if (error != DecodeError::e_ok || why != RollbackIncompatibility::e_none ||
            (r != nullptr && r->incompatible != RollbackIncompatibility::e_none) ||
            (spec != nullptr && spec->incompatible)) {
            ++m_stats.refused;
            continue;
        }
        if (r != nullptr) {
            ++m_stats.datagramsReceived;
            if (!r->alive) continue;
            CountTraffic(*r, now, 0, d.bytes.size());
            r->lastHeard = now;
            if (!r->heard) {
                r->heard = true;
                if (m_state == RollbackPeerState::e_synchronizing)
                    m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_synchronizing, r->index);
            }
            if (r->interrupted) {
                r->interrupted = false;
                m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_resumed, r->index);
            }
            for (const RollbackMessage& m : m_messages) {
                if (!r->alive) break;  // it left (RbDisconnect) or was named gone
                Handle(*r, m, now);
            }
            continue;
        }
        if (spec == nullptr && m_lateSpectators < m_config.maxLateSpectators &&
            std::any_of(m_messages.begin(), m_messages.end(),
                        [](const RollbackMessage& m) { return std::holds_alternative<RbJoinRequest>(m); })) {
            // A stranger becomes a spectator only by asking to join, and only up to the limit.
            Spectator s;
            s.peer = d.peer;
            s.late = true;
            m_spectators.push_back(std::move(s));
            ++m_lateSpectators;
            spec = &m_spectators.back();
        }
        if (spec == nullptr) {
            ++m_stats.refused;
            continue;
        }
        ++m_stats.datagramsReceived;
        spec->lastHeard = now;
        for (const RollbackMessage& m : m_messages) HandleSpectator(*spec, m, now);
    }
    if (m_config.lateSpectatorTimeoutMicros != 0) ForgetSilentSpectators(now);
    if (m_state == RollbackPeerState::e_synchronizing) AdvanceStart(now);
    // The disconnect and interruption timers run only in the match: before it, a remote that
    // starts late is waited for (up to the start timeout), not cut at frame 0.
    if (m_state != RollbackPeerState::e_running) return;
    for (Remote& r : m_remotes) {
        if (!r.alive) continue;
        const uint64_t silence = now - r.lastHeard;
        if (!r.interrupted && silence > m_config.interruptTimeoutMicros) {
            r.interrupted = true;
            m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_interrupted, r.index);
        }
        if (silence <= m_config.disconnectTimeoutMicros) continue;
        DropRemote(r);
    }
}

void RollbackPeer::AdvanceStart(uint64_t now) {
    bool all = true;
    for (Remote& r : m_remotes) {
        if (r.synchronized) continue;
        // Its echo of one of our datagrams arrived in one of its own: both ways work.
        if (r.heard && r.rtt.Samples() > 0) {
            r.synchronized = true;
            m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_synchronized, r.index);
            continue;
        }
        all = false;
    }
    if (all) {
        m_state = RollbackPeerState::e_running;
        m_session.SetSynchronizing(false);
        m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_running, 0);
        // Time sync starts from the match, not from the wait before it.
        for (Remote& r : m_remotes) {
            r.localAdvantage.clear();
            r.remoteAdvantage.clear();
        }
        m_ticksSinceWait = 0;
        return;
    }
    if (now - m_startedAt <= m_config.startTimeoutMicros) return;
    m_state = RollbackPeerState::e_startFailed;
    for (const Remote& r : m_remotes)
        if (!r.synchronized) m_session.RaiseConnectionEvent(RollbackEvent::Kind::e_startTimeout, r.index);
    Leave();  // the remotes that did hear us stop waiting for us
}

bool RollbackPeer::RemoteSynchronized(size_t index) const noexcept {
    return index < m_remotes.size() && m_remotes[index].synchronized;
}

// A hello goes first in a datagram, before anything that needs the shape to be read.
void RollbackPeer::BeginDatagram(bool hello, size_t limit) {
    m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
    if (hello) m_writer.Add(HelloFor(m_config.determinismVersion, m_shape), m_shape, limit);
}

// The remote took one of our inputs, so it read a datagram of ours with a hello and found us
// compatible: the hello can stop.
bool RollbackPeer::HelloAcked(const Remote& r) const noexcept {
    for (uint32_t lp : m_localPlayers)
        if (r.acked[lp] > 0) return true;
    return false;
}

RollbackIncompatibility RollbackPeer::RemoteIncompatibility(size_t index) const noexcept {
    return index < m_remotes.size() ? m_remotes[index].incompatible : RollbackIncompatibility::e_none;
}

bool RollbackPeer::RemovedFromMatch() const noexcept {
    return std::any_of(m_removed.begin(), m_removed.end(), [](bool r) { return r; });
}

size_t RollbackPeer::IncompatibleSpectators() const noexcept {
    return static_cast<size_t>(
        std::count_if(m_spectators.begin(), m_spectators.end(), [](const Spectator& s) { return s.incompatible; }));
}

bool RollbackPeer::RemoteInterrupted(size_t index) const noexcept {
    return index < m_remotes.size() && m_remotes[index].alive && m_remotes[index].interrupted;
}

void RollbackPeer::Handle(Remote& r, const RollbackMessage& m, uint64_t now) {
    if (const auto* in = std::get_if<RbInputs>(&m)) {
        if (std::find(r.players.begin(), r.players.end(), in->player) == r.players.end()) return;
        const size_t width = m_shape.inputBytes;
        const size_t count = in->bytes.size() / width;
        for (size_t i = 0; i < count; ++i) {
            const int64_t f = int64_t{in->firstFrame} + static_cast<int64_t>(i);
            if (f > INT32_MAX) break;
            const std::span<const uint8_t> one(in->bytes.data() + i * width, width);
            const InputResult res = m_session.AddRemoteInput(in->player, static_cast<int32_t>(f), one);
            // A gap or a frame too far ahead: the rest of the run cannot be taken either.
            if (res != InputResult::e_ok && res != InputResult::e_duplicate) break;
        }
    } else if (const auto* ack = std::get_if<RbInputAck>(&m)) {
        if (ack->player < kRollbackMaxPlayers && m_session.IsLocal(ack->player)) {
            const int32_t known = std::min(ack->nextFrame, m_session.ReceivedFrame(ack->player));
            r.acked[ack->player] = std::max(r.acked[ack->player], known);
        }
    } else if (const auto* q = std::get_if<RbQuality>(&m)) {
        CountSequence(r, q->sequence);
        r.heardFrame = true;
        r.remoteFrame = q->frame;
        r.remoteFrameAt = now;
        Push(r.remoteAdvantage, q->advantageMilli);
        r.echoPending = true;
        r.echoTime = q->time;
        r.echoReceivedAt = now;
    } else if (const auto* reply = std::get_if<RbQualityReply>(&m)) {
        if (reply->echoTime <= now) {
            const uint64_t elapsed = now - reply->echoTime;
            r.rtt.Sample(reply->holdMicros < elapsed ? elapsed - reply->holdMicros : 0);
        }
    } else if (const auto* h = std::get_if<RbHash>(&m)) {
        m_session.AddRemoteHash(r.index, h->frame, h->hash);
        if (h->frame > r.finalHashFrame) {
            r.finalHashFrame = h->frame;
            r.finalHash = h->hash;
        }
    } else if (const auto* v = std::get_if<RbView>(&m)) {
        OnView(r, *v);
    } else if (const auto* fz = std::get_if<RbFrozen>(&m)) {
        OnFrozen(r, *fz);
    } else if (const auto* wish = std::get_if<RbDelayWish>(&m)) {
        r.delayWish = wish->frames;
    } else if (std::holds_alternative<RbDisconnect>(m)) {
        DropRemote(r, false);  // it left: nothing to tell
    }
}

int32_t RollbackPeer::LocalAdvantageMilli(const Remote& r, uint64_t now) const {
    if (!r.heardFrame) return 0;
    // Where the remote should be now: its last reported frame, plus the time since it
    // reported (half an RTT in flight, then the time since arrival) at the tick rate.
    const uint64_t since = now - r.remoteFrameAt + r.rtt.Srtt() / 2;
    const int64_t sinceMilli =
        static_cast<int64_t>(std::min<uint64_t>(since, 1000000000ull) * m_config.tickRate / 1000);
    const int64_t estimate = int64_t{r.remoteFrame} * 1000 + sinceMilli;
    return ClampMilli(int64_t{m_session.CurrentFrame()} * 1000 - estimate);
}

void RollbackPeer::Flush() {
    if (m_left) return;
    const uint64_t now = m_transport.NowMicros();
    for (Remote& r : m_remotes)
        if (r.alive) SendTo(r, now);
    for (Spectator& s : m_spectators) {
        if (s.incompatible) continue;
        if (s.lateJoin && (s.wantsSnapshot || (s.sender.Active() && !s.sender.Done())))
            SendSnapshot(s, now);
        else
            SendSpectator(s);
    }
}

void RollbackPeer::SendTo(Remote& r, uint64_t now) {
    const size_t limit = m_transport.MaxDatagram();  // a relay takes its header from it
    BeginDatagram(!HelloAcked(r), limit);
    const int32_t advantage = LocalAdvantageMilli(r, now);
    if (r.heardFrame) Push(r.localAdvantage, advantage);
    m_writer.Add(RbQuality{m_session.CurrentFrame(), advantage, now, r.sendSequence++}, m_shape, limit);
    if (r.echoPending && m_writer.Add(RbQualityReply{r.echoTime, now - r.echoReceivedAt}, m_shape, limit))
        r.echoPending = false;
    AddAgreement(limit);
    if (m_delayWish >= 0) m_writer.Add(RbDelayWish{static_cast<uint8_t>(m_delayWish)}, m_shape, limit);
    const size_t width = m_shape.inputBytes;
    for (uint32_t lp : m_localPlayers) {
        const int32_t end = m_session.ReceivedFrame(lp);
        const int32_t from = r.acked[lp];
        int32_t count = std::min<int32_t>(end - from, static_cast<int32_t>(kRollbackMaxRun));
        RbInputs in;
        in.player = static_cast<uint8_t>(lp);
        in.firstFrame = from;
        for (int32_t i = 0; i < count; ++i) {
            const auto one = m_session.ConfirmedInput(lp, from + i);
            if (one.size() != width) {
                count = i;
                break;
            }
            in.bytes.insert(in.bytes.end(), one.begin(), one.end());
        }
        // Halve the run until it fits beside the other messages.
        while (count > 0 && !m_writer.Add(in, m_shape, limit)) {
            count /= 2;
            in.bytes.resize(static_cast<size_t>(count) * width);
        }
    }
    const auto& finals = m_session.FinalHashes();
    for (const auto& [frame, hash] : finals) {
        uint8_t& copies = r.hashCopies[frame];
        if (copies < kHashCopies && m_writer.Add(RbHash{frame, hash}, m_shape, limit)) ++copies;
    }
    // Forget frames that left the session's list (they are never offered again).
    while (!r.hashCopies.empty() && (finals.empty() || r.hashCopies.begin()->first < finals.front().first))
        r.hashCopies.erase(r.hashCopies.begin());
    if (m_transport.Send(r.peer, m_writer.Bytes())) {
        ++m_stats.datagramsSent;
        CountTraffic(r, now, m_writer.Bytes().size(), 0);
    }
}

void RollbackPeer::CountTraffic(Remote& r, uint64_t now, size_t sentBytes, size_t receivedBytes) {
    if (now - r.windowStart >= kRateWindowMicros) {
        const uint64_t elapsed = now - r.windowStart;
        r.sendBps = r.windowSent * 8 * 1000000 / elapsed;
        r.receiveBps = r.windowReceived * 8 * 1000000 / elapsed;
        r.windowStart = now;
        r.windowSent = 0;
        r.windowReceived = 0;
    }
    if (sentBytes > 0) {
        ++r.datagramsSent;
        r.bytesSent += sentBytes;
        r.windowSent += sentBytes + kDatagramHeaderBytes;
    }
    if (receivedBytes > 0) {
        ++r.datagramsReceived;
        r.bytesReceived += receivedBytes;
        r.windowReceived += receivedBytes + kDatagramHeaderBytes;
    }
}

// Unwraps the remote's 8-bit datagram counter: a step of 1..127 past the highest is newer
// (the datagrams between were lost or are late), 0 a duplicate of it, anything else an older
// one arriving late (it still counts as arrived).
void RollbackPeer::CountSequence(Remote& r, uint8_t sequence) {
    if (!r.sequenceSeen) {
        r.sequenceSeen = true;
        r.sequenceFirst = r.sequenceHighest = sequence;
        r.sequenceArrived = 1;
        return;
    }
    const auto step = static_cast<uint8_t>(sequence - static_cast<uint8_t>(r.sequenceHighest));
    if (step == 0) return;
    if (step < 128) r.sequenceHighest += step;
    ++r.sequenceArrived;
}

RollbackRemoteStats RollbackPeer::RemoteStats(size_t index) const {
    RollbackRemoteStats out;
    if (index >= m_remotes.size()) return out;
    const Remote& r = m_remotes[index];
    out.synchronized = r.synchronized;
    out.alive = r.alive;
    out.interrupted = r.alive && r.interrupted;
    out.rttMicros = r.rtt.Srtt();
    out.rttDeviationMicros = r.rtt.Var();
    out.rttSamples = r.rtt.Samples();
    out.remoteFrame = r.remoteFrame;
    out.framesAheadMilli = Average(r.localAdvantage);
    out.remoteFramesAheadMilli = Average(r.remoteAdvantage);
    out.datagramsSent = r.datagramsSent;
    out.datagramsReceived = r.datagramsReceived;
    out.bytesSent = r.bytesSent;
    out.bytesReceived = r.bytesReceived;
    out.sendBitsPerSecond = r.sendBps;
    out.receiveBitsPerSecond = r.receiveBps;
    if (r.sequenceSeen) {
        const uint64_t expected = r.sequenceHighest - r.sequenceFirst + 1;
        out.datagramsLost = expected - std::min(expected, r.sequenceArrived);
        out.lossPermille = static_cast<uint32_t>(out.datagramsLost * 1000 / expected);
    }
    for (uint32_t p : r.players) out.mispredictedInputs += m_session.MispredictedInputs(p);
    const RollbackStats& s = m_session.Stats();
    out.rollbacks = s.rollbacks;
    out.framesResimulated = s.framesResimulated;
    out.deepestRollback = s.deepestRollback;
    out.finalHashFrame = r.finalHashFrame;
    out.finalHash = r.finalHash;
    return out;
}

void RollbackPeer::Leave() {
    const size_t limit = m_transport.MaxDatagram();  // a relay takes its header from it
    if (m_left) return;
    m_writer.Begin(RollbackHeader{kRollbackProtocolVersion, m_config.matchId});
    m_writer.Add(RbDisconnect{}, m_shape, limit);
    // Several copies: one of them gets through a lossy link; the remote times out otherwise.
    // Spectators hear it too: theirs is the only host, so they lose it now (e_hostLost).
    for (int copy = 0; copy < 3; ++copy) {
        for (Remote& r : m_remotes)
            if (r.alive && m_transport.Send(r.peer, m_writer.Bytes())) ++m_stats.datagramsSent;
        for (const Spectator& sp : m_spectators)
            if (!sp.incompatible && m_transport.Send(sp.peer, m_writer.Bytes())) ++m_stats.datagramsSent;
    }
    m_left = true;
}

int32_t RollbackPeer::RecommendedWaitMilli() const noexcept {
    int32_t wait = 0;
    for (const Remote& r : m_remotes) {
        if (!r.alive || r.localAdvantage.empty() || r.remoteAdvantage.empty()) continue;
        const int64_t w = (int64_t{Average(r.localAdvantage)} - int64_t{Average(r.remoteAdvantage)}) / 2;
        wait = std::max(wait, ClampMilli(w));
    }
    return wait;
}

int32_t RollbackPeer::RecommendedWaitFrames() const noexcept { return RecommendedWaitMilli() / 1000; }

bool RollbackPeer::WaitThisTick() {
    if (m_ticksSinceWait < UINT32_MAX) ++m_ticksSinceWait;
    if (m_ticksSinceWait < m_config.waitSpacingTicks || RecommendedWaitMilli() < 1000) return false;
    m_ticksSinceWait = 0;
    ++m_stats.waitsRecommended;
    // Samples taken before the wait describe a lead this tick just gave back.
    for (Remote& r : m_remotes) r.localAdvantage.clear();
    return true;
}

void RollbackPeer::AskInputDelay(uint32_t frames) noexcept {
    m_delayWish = static_cast<int32_t>(std::min(frames, kRollbackMaxInputDelay));
}

uint32_t RollbackPeer::RemoteDelayWish() const noexcept {
    uint32_t wish = 0;
    for (const Remote& r : m_remotes)
        if (r.alive) wish = std::max<uint32_t>(wish, r.delayWish);
    return wish;
}

uint64_t RollbackPeer::RttMicros(size_t index) const noexcept {
    return index < m_remotes.size() ? m_remotes[index].rtt.Srtt() : 0;
}
bool RollbackPeer::RemoteAlive(size_t index) const noexcept {
    return index < m_remotes.size() && m_remotes[index].alive;
}

}  // namespace lockbox::net
