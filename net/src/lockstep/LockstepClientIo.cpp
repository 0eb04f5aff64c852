// The lockstep client's datagrams (LockstepClient.h): decoding and handling what the server
// sends, and building the one datagram per tick that carries our inputs, acks and reports.

#include <algorithm>

#include "lockbox/dynamics/World.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"
#include "lockstep/LockstepClientImpl.h"

namespace lockbox::net {
namespace {
constexpr uint64_t kSyncPingMicros = 20'000;  // handshake RTT probes, a few per 100 ms
constexpr size_t kMaxHashesPerDatagram = 4;
// Newest inputs sent in every datagram: each input goes out this many times (covers that many
// minus one losses in a row) before only the retransmit timeout sends it again.
constexpr size_t kEagerInputs = 4;
}  // namespace

void LockstepClient::Impl::Begin(DatagramWriter& w) {
    Header h;
    h.token = token;
    h.sequence = sequence++;
    w.Begin(h);
}

void LockstepClient::Impl::Receive(uint64_t now) {
    inbox.clear();
    transport.Poll(inbox);
    for (const Datagram& d : inbox) {
        if (state == ClientState::e_closed) return;
        if (d.peer != server) continue;  // only the server talks to a client
        Header header;
        const DecodeError e = DecodeDatagram(d.bytes, shape, header, messages);
        if (e != DecodeError::e_ok) {
            ++malformed[static_cast<size_t>(e)];
            continue;
        }
        // Before the Welcome the server answers with our Hello's token; afterwards only ours.
        if (token != 0 && header.token != token) {
            ++malformed[static_cast<size_t>(DecodeError::e_badValue)];
            continue;
        }
        lastHeard = now;
        if (interrupted) {
            interrupted = false;
            Event(ClientEvent::Kind::e_resumed, frame);
        }
        for (const Message& m : messages) Handle(m, now);
    }
}

void LockstepClient::Impl::Handle(const Message& message, uint64_t now) {
    if (const auto* w = std::get_if<Welcome>(&message)) {
        if (state != ClientState::e_connecting) return;  // a duplicate
        shape = SessionShape{w->playerCount, w->inputBytes};
        slot = w->slot;
        token = w->token;
        tickRate = w->tickRate;
        hashInterval = w->hashInterval;
        serverDelay = w->inputDelay;
        startFrame = w->startFrame;
        frame = confirmedEnd = w->startFrame;
        if (now >= w->echoTime + w->holdMicros) {
            const uint64_t sample = now - w->echoTime - w->holdMicros;
            rtt.Sample(sample);
            rttMin = rttMax = sample;
        }
        Event(ClientEvent::Kind::e_connected, startFrame);
        if (w->lateJoin) {
            state = ClientState::e_loading;
        } else {
            state = ClientState::e_syncing;
            const bool automatic = config.inputDelay == 0 || (config.inputDelay < 0 && serverDelay == 0);
            if (!automatic) {
                UpdateDelay();
                StartRunning(startFrame, true);
            }
        }
        return;
    }
    if (const auto* r = std::get_if<Reject>(&message)) {
        Close(ClientEvent::Kind::e_rejected, r->reason);
        return;
    }
    if (const auto* d = std::get_if<Disconnect>(&message)) {
        Close(ClientEvent::Kind::e_disconnected, d->reason);
        return;
    }
    if (state == ClientState::e_connecting) return;  // nothing else makes sense before a Welcome
    if (const auto* a = std::get_if<InputAck>(&message)) {
        const int32_t next = std::min(a->nextFrame, nextInputFrame);
        while (unackedBase < next && !unacked.empty()) {
            unacked.pop_front();
            unackedSentAt.pop_front();
            ++unackedBase;
        }
        while (!hashes.empty() && hashes.front().report.frame < a->hashFrame) hashes.pop_front();
    } else if (const auto* c = std::get_if<Confirmed>(&message)) {
        if (state == ClientState::e_loading) return;  // no base state yet
        const size_t row = size_t{shape.playerCount} * shape.inputBytes;
        const int64_t count = static_cast<int64_t>(c->bytes.size() / row);
        // Only a run that touches what we have extends it; a gap waits for the resend.
        if (c->firstFrame > confirmedEnd) return;
        for (int64_t f = confirmedEnd; f < c->firstFrame + count; ++f) {
            const size_t at = static_cast<size_t>(f - c->firstFrame) * row;
            confirmed.emplace_back(c->bytes.begin() + static_cast<std::ptrdiff_t>(at),
                                   c->bytes.begin() + static_cast<std::ptrdiff_t>(at + row));
            ++confirmedEnd;
        }
    } else if (const auto* p = std::get_if<Pong>(&message)) {
        if (p->echoTime > now || now - p->echoTime < p->holdMicros) return;
        const uint64_t sample = now - p->echoTime - p->holdMicros;
        rtt.Sample(sample);
        rttMin = rtt.Samples() == 1 ? sample : std::min(rttMin, sample);
        rttMax = std::max(rttMax, sample);
    } else if (const auto* n = std::get_if<DesyncNotice>(&message)) {
        if (desyncFrame < 0) {
            desyncFrame = n->frame;
            Event(ClientEvent::Kind::e_desync, n->frame);
        }
    } else if (const auto* q = std::get_if<SnapshotRequest>(&message)) {
        if ((state == ClientState::e_running || state == ClientState::e_catchingUp) && frame >= q->minFrame &&
            !(snapshotOut.Active() && !snapshotOut.Done() && snapshotOut.Frame() >= q->minFrame)) {
            snapshotOut.Start(frame, LockstepClient::SnapshotBlob(world, game));
        }
    } else if (const auto* k = std::get_if<SnapshotAck>(&message)) {
        snapshotOut.OnAck(*k, now);
    } else if (const auto* ch = std::get_if<SnapshotChunk>(&message)) {
        if (state != ClientState::e_loading) {
            // Already loaded: ack anyway so the server stops resending.
            snapshotAcks.push_back(SnapshotAck{ch->frame, ch->index});
            urgent = true;
            return;
        }
        if (!snapshotIn.Accept(*ch)) return;
        snapshotAcks.push_back(SnapshotAck{ch->frame, ch->index});
        urgent = true;
        if (!snapshotIn.Complete()) return;
        if (!LockstepClient::LoadSnapshotBlob(snapshotIn.Blob(), world, game)) {
            Close(ClientEvent::Kind::e_disconnected, RejectReason::e_hashMismatch);
            return;
        }
        frame = confirmedEnd = snapshotIn.Frame();
        confirmed.clear();
        lastHash = FoldedStateHash(world, game);
        state = ClientState::e_catchingUp;
        Event(ClientEvent::Kind::e_snapshotLoaded, frame);
    } else if (const auto* ad = std::get_if<Admit>(&message)) {
        if (state != ClientState::e_catchingUp) return;
        StartRunning(std::max(ad->joinFrame, frame), false);
        Event(ClientEvent::Kind::e_admitted, ad->joinFrame);
    }
}

void LockstepClient::Impl::SendHello(uint64_t now) {
    if (anySent && now - lastHello < config.helloRetryMicros) return;
    Header h;
    h.token = config.reconnectToken;
    h.sequence = sequence++;
    writer.Begin(h);
    writer.Add(Hello{b2_determinismVersion, config.reconnectToken, config.requestedSlot, now}, shape);
    transport.Send(server, writer.Bytes(), Delivery::e_reliable);
    lastHello = now;
    anySent = true;
}

void LockstepClient::Impl::SendSnapshot(uint64_t now) {
    snapshotOut.Pump(now, kSnapshotResendMicros, kSnapshotWindow, [&](const SnapshotChunk& chunk) {
        Begin(writer);
        writer.Add(chunk, shape, transport.MaxDatagram());
        transport.Send(server, writer.Bytes(), Delivery::e_reliable);
    });
}

void LockstepClient::Impl::Send(uint64_t now) {
    if (state == ClientState::e_closed) return;
    if (state == ClientState::e_connecting) return SendHello(now);
    if (snapshotOut.Active() && !snapshotOut.Done()) SendSnapshot(now);

    const uint64_t tick = Tick();
    const uint64_t since = now - lastSent;
    const bool syncing = state == ClientState::e_syncing;
    const uint64_t pingEvery = syncing ? kSyncPingMicros : config.pingMicros;
    const bool pingDue = now - lastPing >= pingEvery;
    const bool pending = !unacked.empty() || !hashes.empty() || confirmedAckSent != confirmedEnd;
    // One datagram per tick in steady state: a new input (or snapshot acks) goes at once;
    // acks and resends ride on it, or wait two ticks when no input flows (a stall); silence is
    // broken by a keepalive.
    const bool due = (urgent && since >= tick / 2) || (pending && since >= 2 * tick) ||
                     since >= config.keepAliveMicros || (syncing && pingDue) || !snapshotAcks.empty();
    if (!due) return;

    const size_t limit = transport.MaxDatagram();
    Begin(writer);
    const uint64_t rto = rtt.Srtt() + 4 * rtt.Var() + 2 * tick;
    if (!unacked.empty()) {
        // The newest kEagerInputs go every time; the whole unacked tail only when its oldest
        // input has waited longer than the retransmit timeout (lost, or its ack was), at most
        // once per timeout. So the no-loss size does not grow with the RTT.
        size_t from = unacked.size() > kEagerInputs ? unacked.size() - kEagerInputs : 0;
        const bool neverSent = unackedSentAt.front() == 0;  // the empty inputs of the delay window
        if (from > 0 && (neverSent || (now - unackedSentAt.front() >= rto && now - lastFullResend >= rto))) {
            from = 0;
            lastFullResend = now;
        }
        Inputs in;
        in.slot = static_cast<uint8_t>(slot);
        in.firstFrame = unackedBase + static_cast<int32_t>(from);
        const size_t count = std::min<size_t>(unacked.size() - from, kMaxRunFrames);
        for (size_t i = from; i < from + count; ++i)
            in.bytes.insert(in.bytes.end(), unacked[i].begin(), unacked[i].end());
        // A run too large for one datagram (a long stall): halve it until it fits.
        size_t n = count;
        while (n > 0 && !writer.Add(in, shape, limit)) {
            n /= 2;
            in.bytes.resize(n * shape.inputBytes);
        }
        for (size_t i = from; i < from + n; ++i)
            if (unackedSentAt[i] == 0) unackedSentAt[i] = now == 0 ? 1 : now;
    }
    if (state != ClientState::e_loading) {
        writer.Add(ConfirmedAck{confirmedEnd}, shape, limit);
        confirmedAckSent = confirmedEnd;
    }
    // Hash reports like inputs: twice eagerly, then again only after the retransmit timeout.
    size_t hashCount = 0;
    for (PendingHash& h : hashes) {
        if (hashCount == kMaxHashesPerDatagram) break;
        if (h.sends >= 2 && now - h.lastSent < rto) continue;
        if (!writer.Add(h.report, shape, limit)) break;
        ++h.sends;
        h.lastSent = now;
        ++hashCount;
    }
    if (pingDue && writer.Add(Ping{now}, shape, limit)) lastPing = now;
    while (!snapshotAcks.empty() && writer.Add(snapshotAcks.back(), shape, limit)) snapshotAcks.pop_back();
    snapshotAcks.clear();  // whatever did not fit is acked again when its chunk is resent
    if (writer.MessageCount() == 0) writer.Add(KeepAlive{}, shape, limit);
    transport.Send(server, writer.Bytes());
    lastSent = now;
    urgent = false;
}

}  // namespace lockbox::net
