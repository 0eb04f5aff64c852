// The lockstep server's datagrams (LockstepServer.h): decoding and checking what clients send,
// and the one datagram per tick per client with its confirmed inputs and acks.

#include <algorithm>

#include "lockstep/LockstepServerImpl.h"

namespace lockbox::net {
namespace {
using State = SlotInfo::State;
}  // namespace

void LockstepServer::Impl::SendTo(PeerId peer, const Message& m, uint32_t token, Delivery d) {
    Header h;
    h.token = token;
    writer.Begin(h);
    if (!writer.Add(m, shape, transport.MaxDatagram())) return;
    transport.Send(peer, writer.Bytes(), d);
    ++stats.datagramsSent;
}

void LockstepServer::Impl::Begin(Slot& slot) {
    Header h;
    h.token = slot.token;
    h.sequence = slot.sequence++;
    writer.Begin(h);
}

void LockstepServer::Impl::Receive(uint64_t now) {
    inbox.clear();
    transport.Poll(inbox);
    for (const Datagram& d : inbox) {
        Header header;
        DecodeError e = DecodeHeader(d.bytes, header);
        if (e == DecodeError::e_badVersion) {
            // The header and Reject layouts never change, so another version can read why.
            ++stats.malformed[static_cast<size_t>(e)];
            ++stats.rejected;
            SendTo(d.peer, Reject{RejectReason::e_protocolVersion}, header.token, Delivery::e_reliable);
            continue;
        }
        if (e == DecodeError::e_ok) e = DecodeDatagram(d.bytes, shape, header, messages);
        if (e != DecodeError::e_ok) {
            ++stats.malformed[static_cast<size_t>(e)];
            continue;
        }
        for (const Message& m : messages)
            if (const auto* hello = std::get_if<Hello>(&m)) OnHello(d.peer, *hello, now);
        const int32_t s = SlotOf(d.peer);
        bool onlyHello = true;
        for (const Message& m : messages) onlyHello = onlyHello && std::holds_alternative<Hello>(m);
        if (onlyHello) continue;
        if (s < 0) {
            ++stats.unknownPeer;
            continue;
        }
        Slot& slot = slots[static_cast<size_t>(s)];
        if (header.token != slot.token) {
            ++stats.badToken;
            continue;
        }
        slot.lastHeard = now;
        if (slot.state == State::e_interrupted) {
            slot.state = State::e_live;
            Event(Ev(ServerEvent::Kind::e_resumed, s, d.peer, confirmedNext));
        }
        for (const Message& m : messages) {
            // A Disconnect (or a dropped joiner) ends the slot: ignore the rest of the datagram.
            if (SlotOf(d.peer) != s) break;
            Handle(s, d.peer, m, now);
        }
    }
}

void LockstepServer::Impl::Handle(int32_t s, PeerId peer, const Message& message, uint64_t now) {
    Slot& slot = slots[static_cast<size_t>(s)];
    if (std::holds_alternative<Hello>(message) || std::holds_alternative<KeepAlive>(message)) return;
    if (const auto* in = std::get_if<Inputs>(&message)) return OnInputs(s, peer, *in);
    if (const auto* a = std::get_if<ConfirmedAck>(&message)) {
        if (slot.receivesConfirmed) slot.acked = std::clamp(a->nextFrame, slot.acked, confirmedNext);
        return;
    }
    if (const auto* h = std::get_if<HashReport>(&message)) {
        if (h->frame < confirmedNext) slot.hashNext = std::max(slot.hashNext, h->frame + 1);
        return OnHash(s, h->frame, h->hash);
    }
    if (const auto* p = std::get_if<Ping>(&message)) {
        slot.pongPending = true;
        slot.pongEcho = p->time;
        slot.pongAt = now;
        return;
    }
    if (std::holds_alternative<Disconnect>(message)) return Drop(s, RejectReason::e_left);
    if (const auto* c = std::get_if<SnapshotChunk>(&message)) {
        // Ack whatever arrives so the sender stops; keep it only from the source we asked.
        SendTo(peer, SnapshotAck{c->frame, c->index}, slot.token, Delivery::e_unreliable);
        if (s != pullSource || !pull.Accept(*c) || !pull.Complete()) return;
        if (pull.Failed()) {
            // Not a snapshot: forget it; the join logic pulls again (kPullRetryMicros).
            pull.Reset();
            pullSource = -1;
            return;
        }
        // Kept compressed: every joiner it is sent to shares the one compression.
        cache = SnapshotSender::Compress(pull.Blob());
        cacheFrame = pull.Frame();
        pull.Reset();
        pullSource = -1;
        return;
    }
    if (const auto* k = std::get_if<SnapshotAck>(&message)) {
        slot.snapshot.OnAck(*k, now);
        if (slot.state == State::e_joining && !slot.loaded && slot.snapshot.Done()) {
            // The joiner has the state of the snapshot frame: confirmed inputs flow from there.
            slot.loaded = true;
            slot.receivesConfirmed = true;
            slot.acked = slot.sentConfirmedEnd = slot.snapshot.Frame();
            ++stats.snapshotsServed;
        }
        return;
    }
    ++stats.unexpected;
}

void LockstepServer::Impl::SendAll(uint64_t now) {
    for (size_t i = 0; i < slots.size(); ++i) {
        const State st = slots[i].state;
        if (slots[i].peer == kNoPeer || st == State::e_free || st == State::e_disconnected) continue;
        SendSlot(static_cast<int32_t>(i), now);
    }
}

void LockstepServer::Impl::SendSlot(int32_t s, uint64_t now) {
    Slot& slot = slots[static_cast<size_t>(s)];
    if (slot.snapshot.Active() && !slot.snapshot.Done()) {
        slot.snapshot.Pump(now, kSnapshotResendMicros, kSnapshotWindow, [&](const SnapshotChunk& chunk) {
            Begin(slot);
            writer.Add(chunk, shape, transport.MaxDatagram());
            transport.Send(slot.peer, writer.Bytes(), Delivery::e_reliable);
            ++stats.datagramsSent;
        });
    }
    const uint64_t tick = Tick();
    const uint64_t since = now - slot.lastSent;
    const bool fresh = slot.receivesConfirmed && confirmedNext > slot.sentConfirmedEnd;
    // TrimHistory keeps every frame a receiving client has not acked; the bound is a guard.
    const bool unacked = slot.receivesConfirmed && slot.acked < confirmedNext && slot.acked >= historyBase;
    const bool pending = unacked || slot.ackDirty || slot.pongPending || slot.admitFrame >= 0 || slot.desyncNotices > 0;
    // New confirmed frames go at once (at most two datagrams per tick); acks and resends ride
    // on them, or wait two ticks when nothing is confirmed (a stall).
    const bool due = (fresh && since >= tick / 2) || (pending && since >= 2 * tick) || since >= config.keepAliveMicros;
    if (!due) return;

    const size_t limit = transport.MaxDatagram();
    Begin(slot);
    writer.Add(InputAck{slot.nextInput, slot.hashNext}, shape, limit);
    if (unacked) {
        const int64_t n0 = std::min<int64_t>(confirmedNext - slot.acked, kMaxRunFrames);
        Confirmed c;
        c.firstFrame = slot.acked;
        const size_t row = RowBytes();
        const auto first = history.begin() + (Row(slot.acked) - history.data());
        // The tail may not fit one datagram (a joiner catching up): halve until it does.
        for (int64_t n = n0; n > 0; n /= 2) {
            c.bytes.assign(first, first + static_cast<std::ptrdiff_t>(static_cast<size_t>(n) * row));
            if (writer.Add(c, shape, limit)) {
                slot.sentConfirmedEnd = std::max(slot.sentConfirmedEnd, static_cast<int32_t>(slot.acked + n));
                break;
            }
        }
    }
    if (slot.pongPending) writer.Add(Pong{slot.pongEcho, now - slot.pongAt}, shape, limit);
    if (slot.admitFrame >= 0) writer.Add(net::Admit{slot.admitFrame}, shape, limit);
    if (slot.desyncNotices > 0 && desyncFrame >= 0) {
        writer.Add(DesyncNotice{desyncFrame}, shape, limit);
        --slot.desyncNotices;
    }
    transport.Send(slot.peer, writer.Bytes());
    ++stats.datagramsSent;
    slot.lastSent = now;
    slot.ackDirty = false;
    slot.pongPending = false;
}

}  // namespace lockbox::net
