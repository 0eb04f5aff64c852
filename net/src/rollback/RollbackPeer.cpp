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
    : session_(session), transport_(transport), config_(std::move(config)) {
    if (config_.tickRate == 0) config_.tickRate = 1;
    if (config_.waitSpacingTicks == 0) config_.waitSpacingTicks = 1;
    shape_ = RollbackShape{session_.Config().players, session_.Config().inputBytes};
    const uint64_t now = transport_.NowMicros();
    for (const RollbackRemote& rr : config_.remotes) {
        Remote r;
        r.peer = rr.peer;
        r.index = static_cast<uint32_t>(remotes_.size());
        for (uint32_t p : rr.players)
            if (p < session_.Config().players && !session_.IsLocal(p)) r.players.push_back(p);
        r.lastHeard = now;
        // Registered before its first datagram: until this remote reports what it holds,
        // nothing becomes final (it may hold nothing yet).
        const std::vector<int32_t> nothing(session_.Config().players, 0);
        session_.SetPeerView(r.index, nothing);
        remotes_.push_back(std::move(r));
    }
    if (config_.snapshotResendMicros == 0) config_.snapshotResendMicros = 1;
    if (config_.snapshotChunksPerFlush == 0) config_.snapshotChunksPerFlush = 1;
    for (PeerId sp : config_.spectators) {
        Spectator s;
        s.peer = sp;
        spectators_.push_back(std::move(s));
    }
    localPlayers_ = session_.Config().localPlayers;
}

RollbackPeer::~RollbackPeer() = default;

RollbackPeer::Remote* RollbackPeer::Find(PeerId peer) {
    for (Remote& r : remotes_)
        if (r.peer == peer) return &r;
    return nullptr;
}

void RollbackPeer::Poll() {
    inbox_.clear();
    transport_.Poll(inbox_);
    const uint64_t now = transport_.NowMicros();
    for (const Datagram& d : inbox_) {
        RollbackHeader header;
        const DecodeError error = DecodeRollbackDatagram(d.bytes, shape_, header, messages_);
        Remote* r = Find(d.peer);
        Spectator* spec = r == nullptr ? FindSpectator(d.peer) : nullptr;
        // A stranger showing any reason is refused like any bad datagram; a known sender is
        // also named (once) and refused from then on.
        const RollbackIncompatibility why =
            FindIncompatibility(error, header, messages_, config_.matchId, config_.determinismVersion);
        if (why != RollbackIncompatibility::e_none) {
            // Named once; refused from now on, so the remote times out as a silent one would.
            if (r != nullptr && r->alive && r->incompatible == RollbackIncompatibility::e_none) {
                r->incompatible = why;
                session_.RaiseIncompatible(r->index, why);
            }
            if (spec != nullptr) spec->incompatible = true;
        }
        // A match id other than ours is a reason too (FindIncompatibility), so it is refused here.
        if (error != DecodeError::e_ok || why != RollbackIncompatibility::e_none ||
            (r != nullptr && r->incompatible != RollbackIncompatibility::e_none) ||
            (spec != nullptr && spec->incompatible)) {
            ++stats_.refused;
            continue;
        }
        if (r != nullptr) {
            ++stats_.datagramsReceived;
            if (!r->alive) continue;
            r->lastHeard = now;
            if (r->interrupted) {
                r->interrupted = false;
                session_.RaiseConnectionEvent(RollbackEvent::Kind::e_resumed, r->index);
            }
            for (const RollbackMessage& m : messages_) {
                if (!r->alive) break;  // it left (RbDisconnect) or was named gone
                Handle(*r, m, now);
            }
            continue;
        }
        if (spec == nullptr && lateSpectators_ < config_.maxLateSpectators &&
            std::any_of(messages_.begin(), messages_.end(),
                        [](const RollbackMessage& m) { return std::holds_alternative<RbJoinRequest>(m); })) {
            // A stranger becomes a spectator only by asking to join, and only up to the limit.
            Spectator s;
            s.peer = d.peer;
            spectators_.push_back(std::move(s));
            ++lateSpectators_;
            spec = &spectators_.back();
        }
        if (spec == nullptr) {
            ++stats_.refused;
            continue;
        }
        ++stats_.datagramsReceived;
        for (const RollbackMessage& m : messages_) HandleSpectator(*spec, m, now);
    }
    for (Remote& r : remotes_) {
        if (!r.alive) continue;
        const uint64_t silence = now - r.lastHeard;
        if (!r.interrupted && silence > config_.interruptTimeoutMicros) {
            r.interrupted = true;
            session_.RaiseConnectionEvent(RollbackEvent::Kind::e_interrupted, r.index);
        }
        if (silence <= config_.disconnectTimeoutMicros) continue;
        DropRemote(r);
    }
}

// A hello goes first in a datagram, before anything that needs the shape to be read.
void RollbackPeer::BeginDatagram(bool hello, size_t limit) {
    writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
    if (hello) writer_.Add(HelloFor(config_.determinismVersion, shape_), shape_, limit);
}

// The remote took one of our inputs, so it read a datagram of ours with a hello and found us
// compatible: the hello can stop.
bool RollbackPeer::HelloAcked(const Remote& r) const noexcept {
    for (uint32_t lp : localPlayers_)
        if (r.acked[lp] > 0) return true;
    return false;
}

RollbackIncompatibility RollbackPeer::RemoteIncompatibility(size_t index) const noexcept {
    return index < remotes_.size() ? remotes_[index].incompatible : RollbackIncompatibility::e_none;
}

bool RollbackPeer::RemovedFromMatch() const noexcept {
    return std::any_of(removed_.begin(), removed_.end(), [](bool r) { return r; });
}

size_t RollbackPeer::IncompatibleSpectators() const noexcept {
    return static_cast<size_t>(
        std::count_if(spectators_.begin(), spectators_.end(), [](const Spectator& s) { return s.incompatible; }));
}

bool RollbackPeer::RemoteInterrupted(size_t index) const noexcept {
    return index < remotes_.size() && remotes_[index].alive && remotes_[index].interrupted;
}

void RollbackPeer::Handle(Remote& r, const RollbackMessage& m, uint64_t now) {
    if (const auto* in = std::get_if<RbInputs>(&m)) {
        if (std::find(r.players.begin(), r.players.end(), in->player) == r.players.end()) return;
        const size_t width = shape_.inputBytes;
        const size_t count = in->bytes.size() / width;
        for (size_t i = 0; i < count; ++i) {
            const int64_t f = int64_t{in->firstFrame} + static_cast<int64_t>(i);
            if (f > INT32_MAX) break;
            const std::span<const uint8_t> one(in->bytes.data() + i * width, width);
            const InputResult res = session_.AddRemoteInput(in->player, static_cast<int32_t>(f), one);
            // A gap or a frame too far ahead: the rest of the run cannot be taken either.
            if (res != InputResult::e_ok && res != InputResult::e_duplicate) break;
        }
    } else if (const auto* ack = std::get_if<RbInputAck>(&m)) {
        if (ack->player < kRollbackMaxPlayers && session_.IsLocal(ack->player)) {
            const int32_t known = std::min(ack->nextFrame, session_.ReceivedFrame(ack->player));
            r.acked[ack->player] = std::max(r.acked[ack->player], known);
        }
    } else if (const auto* q = std::get_if<RbQuality>(&m)) {
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
        session_.AddRemoteHash(r.index, h->frame, h->hash);
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
    const int64_t sinceMilli = static_cast<int64_t>(std::min<uint64_t>(since, 1000000000ull) * config_.tickRate / 1000);
    const int64_t estimate = int64_t{r.remoteFrame} * 1000 + sinceMilli;
    return ClampMilli(int64_t{session_.CurrentFrame()} * 1000 - estimate);
}

void RollbackPeer::Flush() {
    if (left_) return;
    const uint64_t now = transport_.NowMicros();
    for (Remote& r : remotes_)
        if (r.alive) SendTo(r, now);
    for (Spectator& s : spectators_) {
        if (s.incompatible) continue;
        if (s.lateJoin && (s.wantsSnapshot || (s.sender.Active() && !s.sender.Done())))
            SendSnapshot(s, now);
        else
            SendSpectator(s);
    }
}

void RollbackPeer::SendTo(Remote& r, uint64_t now) {
    const size_t limit = transport_.MaxDatagram();  // a relay takes its header from it
    BeginDatagram(!HelloAcked(r), limit);
    const int32_t advantage = LocalAdvantageMilli(r, now);
    if (r.heardFrame) Push(r.localAdvantage, advantage);
    writer_.Add(RbQuality{session_.CurrentFrame(), advantage, now}, shape_, limit);
    if (r.echoPending && writer_.Add(RbQualityReply{r.echoTime, now - r.echoReceivedAt}, shape_, limit))
        r.echoPending = false;
    AddAgreement(limit);
    if (delayWish_ >= 0) writer_.Add(RbDelayWish{static_cast<uint8_t>(delayWish_)}, shape_, limit);
    const size_t width = shape_.inputBytes;
    for (uint32_t lp : localPlayers_) {
        const int32_t end = session_.ReceivedFrame(lp);
        const int32_t from = r.acked[lp];
        int32_t count = std::min<int32_t>(end - from, static_cast<int32_t>(kRollbackMaxRun));
        RbInputs in;
        in.player = static_cast<uint8_t>(lp);
        in.firstFrame = from;
        for (int32_t i = 0; i < count; ++i) {
            const auto one = session_.ConfirmedInput(lp, from + i);
            if (one.size() != width) {
                count = i;
                break;
            }
            in.bytes.insert(in.bytes.end(), one.begin(), one.end());
        }
        // Halve the run until it fits beside the other messages.
        while (count > 0 && !writer_.Add(in, shape_, limit)) {
            count /= 2;
            in.bytes.resize(static_cast<size_t>(count) * width);
        }
    }
    const auto& finals = session_.FinalHashes();
    for (const auto& [frame, hash] : finals) {
        uint8_t& copies = r.hashCopies[frame];
        if (copies < kHashCopies && writer_.Add(RbHash{frame, hash}, shape_, limit)) ++copies;
    }
    // Forget frames that left the session's list (they are never offered again).
    while (!r.hashCopies.empty() && (finals.empty() || r.hashCopies.begin()->first < finals.front().first))
        r.hashCopies.erase(r.hashCopies.begin());
    if (transport_.Send(r.peer, writer_.Bytes())) ++stats_.datagramsSent;
}

void RollbackPeer::Leave() {
    const size_t limit = transport_.MaxDatagram();  // a relay takes its header from it
    if (left_) return;
    writer_.Begin(RollbackHeader{kRollbackProtocolVersion, config_.matchId});
    writer_.Add(RbDisconnect{}, shape_, limit);
    // Several copies: one of them gets through a lossy link; the remote times out otherwise.
    // Spectators hear it too: theirs is the only host, so they lose it now (e_hostLost).
    for (int copy = 0; copy < 3; ++copy) {
        for (Remote& r : remotes_)
            if (r.alive && transport_.Send(r.peer, writer_.Bytes())) ++stats_.datagramsSent;
        for (const Spectator& sp : spectators_)
            if (!sp.incompatible && transport_.Send(sp.peer, writer_.Bytes())) ++stats_.datagramsSent;
    }
    left_ = true;
}

int32_t RollbackPeer::RecommendedWaitMilli() const noexcept {
    int32_t wait = 0;
    for (const Remote& r : remotes_) {
        if (!r.alive || r.localAdvantage.empty() || r.remoteAdvantage.empty()) continue;
        const int64_t w = (int64_t{Average(r.localAdvantage)} - int64_t{Average(r.remoteAdvantage)}) / 2;
        wait = std::max(wait, ClampMilli(w));
    }
    return wait;
}

int32_t RollbackPeer::RecommendedWaitFrames() const noexcept { return RecommendedWaitMilli() / 1000; }

bool RollbackPeer::WaitThisTick() {
    if (ticksSinceWait_ < UINT32_MAX) ++ticksSinceWait_;
    if (ticksSinceWait_ < config_.waitSpacingTicks || RecommendedWaitMilli() < 1000) return false;
    ticksSinceWait_ = 0;
    ++stats_.waitsRecommended;
    // Samples taken before the wait describe a lead this tick just gave back.
    for (Remote& r : remotes_) r.localAdvantage.clear();
    return true;
}

void RollbackPeer::AskInputDelay(uint32_t frames) noexcept {
    delayWish_ = static_cast<int32_t>(std::min(frames, kRollbackMaxInputDelay));
}

uint32_t RollbackPeer::RemoteDelayWish() const noexcept {
    uint32_t wish = 0;
    for (const Remote& r : remotes_)
        if (r.alive) wish = std::max<uint32_t>(wish, r.delayWish);
    return wish;
}

uint64_t RollbackPeer::RttMicros(size_t index) const noexcept {
    return index < remotes_.size() ? remotes_[index].rtt.Srtt() : 0;
}
bool RollbackPeer::RemoteAlive(size_t index) const noexcept { return index < remotes_.size() && remotes_[index].alive; }

}  // namespace lockbox::net
