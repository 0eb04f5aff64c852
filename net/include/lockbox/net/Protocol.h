#pragma once
/// @file
/// The lockstep wire protocol (docs/net.md "Protocol"): one versioned codec for every
/// datagram a LockstepServer and its LockstepClients exchange.
///
/// A datagram is a 9-byte header (magic u16 'L' 'K', protocol version u8, session token u32,
/// sequence number u16; little-endian) followed by one or more messages, each a type byte and
/// its fields, so one datagram carries a client's inputs, its acks and its hash report together.
/// Integers are little-endian fixed widths, except frame numbers, times and sizes, which are
/// minimal LEB128 varints (a non-minimal varint is malformed). Input runs are compressed: a
/// bitmap marks each entry that repeats the previous one of the same player (all zeros for
/// the run's first frame); only unmarked entries are stored.
///
/// Decoding never reads past the buffer and checks every field; the whole datagram is refused
/// (with a DecodeError saying why) when any message in it is malformed. Encoding is canonical:
/// decoding a datagram and encoding its messages again gives the same bytes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "lockbox/Export.h"

namespace lockbox::net {

/// First two bytes of every datagram: 'L' 'K'.
inline constexpr uint16_t kProtocolMagic = 0x4B4Cu;
/// Bumped whenever a message layout changes. A peer with another version gets
/// Reject{e_protocolVersion} (the header and Reject layouts never change). 2: snapshot chunks
/// carry the state as one zstd frame.
inline constexpr uint8_t kProtocolVersion = 2;
/// Bytes of the datagram header.
inline constexpr size_t kHeaderBytes = 9;
/// Largest players per session (a slot is one byte; 0xFF means "any slot").
inline constexpr uint32_t kMaxPlayers = 64;
/// Largest input per player per frame, in bytes.
inline constexpr uint32_t kMaxInputBytes = 256;
/// Largest frame count of one Inputs or Confirmed message.
inline constexpr uint32_t kMaxRunFrames = 255;
/// Payload bytes of every snapshot chunk but the last.
inline constexpr uint32_t kSnapshotChunkBytes = 1024;
/// Largest snapshot image the protocol transfers (64 MiB).
inline constexpr uint32_t kMaxSnapshotBytes = 64u << 20;
/// "Any free slot" in Hello.requestedSlot.
inline constexpr uint8_t kAnySlot = 0xFF;

/// The datagram header.
struct Header {
    uint8_t version = kProtocolVersion;  ///< protocol version of the sender
    uint32_t token = 0;                  ///< session token (0 before a Welcome)
    uint16_t sequence = 0;               ///< per-destination datagram counter, wraps
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Header&) const = default;
};

/// Why a Reject was sent or a Disconnect happened (one byte on the wire).
enum class RejectReason : uint8_t {
    e_none = 0,
    e_protocolVersion = 1,     ///< the header's protocol version differs
    e_determinismVersion = 2,  ///< lockbox b2_determinismVersion differs: states would diverge
    e_full = 3,                ///< no free slot
    e_slotTaken = 4,           ///< the requested slot is owned by someone else
    e_badToken = 5,            ///< reconnect token unknown
    e_hashMismatch = 6,        ///< a joiner's state hash did not match the others'
    e_timeout = 7,             ///< the peer was silent past the disconnect timeout
    e_left = 8,                ///< the peer left on purpose
    e_serverClosing = 9,       ///< the server is shutting down
    e_count
};
/// Short name of a reason ("full", "bad token", ...).
LOCKBOX_API std::string_view RejectReasonName(RejectReason reason) noexcept;

/// Handshake request, client -> server. The protocol version is the header's.
struct Hello {
    uint32_t determinismVersion = 0;   ///< the client's b2_determinismVersion
    uint32_t token = 0;                ///< a previous session's token to reconnect, else 0
    uint8_t requestedSlot = kAnySlot;  ///< 0 .. kMaxPlayers-1, or kAnySlot
    uint64_t clientTime = 0;           ///< the client's clock, microseconds (echoed in Welcome)
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Hello&) const = default;
};

/// Handshake answer, server -> client: the session's shape and the client's slot.
struct Welcome {
    uint8_t slot = 0;           ///< the client's slot, < playerCount
    uint8_t playerCount = 0;    ///< 1 .. kMaxPlayers
    uint16_t inputBytes = 0;    ///< per player per frame, 1 .. kMaxInputBytes
    uint16_t tickRate = 0;      ///< frames per second, >= 1
    uint8_t inputDelay = 0;     ///< frames; 0: the client picks it from its RTT
    uint32_t hashInterval = 0;  ///< report a hash after every frame f with f % hashInterval == 0; >= 1
    int32_t startFrame = 0;     ///< first frame of the match (>= 0)
    uint32_t token = 0;         ///< the session token, non-zero; carried by every later header
    bool lateJoin = false;      ///< true: a snapshot follows, inputs only after Admit
    uint64_t echoTime = 0;      ///< Hello.clientTime, for a first RTT sample
    uint64_t holdMicros = 0;    ///< how long the server held the Hello before answering
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Welcome&) const = default;
};

/// The server refuses a Hello (or drops a joiner).
struct Reject {
    /// Why the server refused.
    RejectReason reason = RejectReason::e_none;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Reject&) const = default;
};

/// One player's inputs for frames [firstFrame, firstFrame + count), client -> server: the
/// frames the server has not acknowledged yet, resent in every datagram until acked.
struct Inputs {
    uint8_t slot = 0;            ///< the slot these inputs claim
    int32_t firstFrame = 0;      ///< >= 0
    std::vector<uint8_t> bytes;  ///< count * inputBytes, count in 1 .. kMaxRunFrames
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Inputs&) const = default;
};

/// Server -> client: every input of the client's slot before nextFrame has arrived; every
/// hash report before hashFrame has arrived.
struct InputAck {
    int32_t nextFrame = 0;  ///< >= 0
    int32_t hashFrame = 0;  ///< >= 0
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const InputAck&) const = default;
};

/// Server -> client: the confirmed inputs of frames [firstFrame, firstFrame + count), every
/// player's bytes per frame (slot 0 first), resent until the client acks them.
struct Confirmed {
    int32_t firstFrame = 0;      ///< >= 0
    std::vector<uint8_t> bytes;  ///< count * playerCount * inputBytes, count in 1 .. kMaxRunFrames
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Confirmed&) const = default;
};

/// Client -> server: every confirmed frame before nextFrame has arrived.
struct ConfirmedAck {
    int32_t nextFrame = 0;  ///< >= 0
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const ConfirmedAck&) const = default;
};

/// RTT probe: the sender's clock in microseconds.
struct Ping {
    /// The sender's clock when it sent the probe, microseconds (any epoch: only the sender reads it
    /// back).
    uint64_t time = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Ping&) const = default;
};

/// RTT answer: the probe's time and how long the answerer held it (microseconds).
struct Pong {
    /// Ping.time of the probe being answered, microseconds on the prober's clock.
    uint64_t echoTime = 0;
    /// Microseconds between the answerer's receiving the Ping and sending this Pong; the prober
    /// subtracts it from the round trip.
    uint64_t holdMicros = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Pong&) const = default;
};

/// Client -> server: the state hash after the confirmed frame `frame` (world hash folded with
/// the game's user state). Resent until acked through InputAck.hashFrame.
struct HashReport {
    int32_t frame = 0;  ///< >= 0
    /// The state hash after that frame (b2WorldHash folded with the game's user state).
    uint64_t hash = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const HashReport&) const = default;
};

/// Nothing to say, still here.
struct KeepAlive {
    /// Always equal: the message has no fields.
    bool operator==(const KeepAlive&) const = default;
};

/// The sender leaves (sent a few times; the receiver also times out).
struct Disconnect {
    /// Why the sender leaves (e_left when on purpose).
    RejectReason reason = RejectReason::e_left;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Disconnect&) const = default;
};

/// Server -> client: send me a snapshot of your current confirmed state (relay mode late join).
struct SnapshotRequest {
    int32_t minFrame = 0;  ///< the snapshot's frame must be >= this
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const SnapshotRequest&) const = default;
};

/// One piece of a snapshot blob (LockstepClient::SnapshotBlob layout) of frame `frame`.
struct SnapshotChunk {
    int32_t frame = 0;           ///< the snapshot is the state before stepping this frame
    uint32_t totalSize = 0;      ///< 1 .. kMaxSnapshotBytes
    uint32_t index = 0;          ///< chunk index, index * kSnapshotChunkBytes < totalSize
    std::vector<uint8_t> bytes;  ///< exactly min(kSnapshotChunkBytes, totalSize - offset) bytes
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const SnapshotChunk&) const = default;
};

/// Receiver of a snapshot: chunk `index` of the snapshot of `frame` arrived.
struct SnapshotAck {
    /// The frame of the snapshot being acknowledged (SnapshotChunk.frame).
    int32_t frame = 0;
    /// The chunk index received (SnapshotChunk.index).
    uint32_t index = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const SnapshotAck&) const = default;
};

/// Server -> joiner: its hash matched; it sends inputs from joinFrame on (frames before are
/// empty for its slot). Resent until inputs for joinFrame arrive.
struct Admit {
    /// First frame for which the joiner sends its inputs (>= 0).
    int32_t joinFrame = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const Admit&) const = default;
};

/// Server -> client: the clients' states diverged at `frame` (first mismatching report).
struct DesyncNotice {
    /// First frame whose hash reports disagree (>= 0).
    int32_t frame = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const DesyncNotice&) const = default;
};

/// Any message.
using Message = std::variant<Hello, Welcome, Reject, Inputs, InputAck, Confirmed, ConfirmedAck, Ping, Pong, HashReport,
                             KeepAlive, Disconnect, SnapshotRequest, SnapshotChunk, SnapshotAck, Admit, DesyncNotice>;

/// Type byte of each message (the variant index + 1).
enum class MessageType : uint8_t {
    e_hello = 1,
    e_welcome,
    e_reject,
    e_inputs,
    e_inputAck,
    e_confirmed,
    e_confirmedAck,
    e_ping,
    e_pong,
    e_hashReport,
    e_keepAlive,
    e_disconnect,
    e_snapshotRequest,
    e_snapshotChunk,
    e_snapshotAck,
    e_admit,
    e_desyncNotice,
    e_end
};

/// Why a datagram was refused.
enum class DecodeError : uint8_t {
    e_ok = 0,
    e_tooShort,      ///< shorter than a header plus one type byte
    e_badMagic,      ///< not a lockbox datagram
    e_badVersion,    ///< another protocol version (only the header was read)
    e_badType,       ///< unknown message type
    e_truncated,     ///< a field runs past the end
    e_badVarint,     ///< a varint is non-minimal or too long
    e_badValue,      ///< a field is out of its range
    e_noShape,       ///< an input message arrived before the session shape is known
    e_incompatible,  ///< rollback: an RbHello describes another session shape (decoding stopped)
    e_count
};
/// Short name of an error ("truncated", ...).
LOCKBOX_API std::string_view DecodeErrorName(DecodeError error) noexcept;

/// What the decoder must know to size input runs: the session's player count and input
/// bytes. Zero players or zero input bytes: input messages are refused with e_noShape.
struct SessionShape {
    uint32_t playerCount = 0;  ///< 0 .. kMaxPlayers
    uint32_t inputBytes = 0;   ///< 0 .. kMaxInputBytes
};

/// Decodes only the header (magic, version, token, sequence). e_badVersion still fills
/// `header` so the caller can answer with Reject{e_protocolVersion}.
LOCKBOX_API DecodeError DecodeHeader(std::span<const uint8_t> datagram, Header& header) noexcept;

/// Decodes a whole datagram into its header and messages (appended to `out` after clearing
/// it). On any error `out` is left empty.
LOCKBOX_API DecodeError DecodeDatagram(std::span<const uint8_t> datagram, const SessionShape& shape, Header& header,
                                       std::vector<Message>& out);

/// Builds one datagram: the header, then messages appended one by one.
class LOCKBOX_API DatagramWriter {
public:
    /// Starts a datagram with this header (replaces any previous contents).
    void Begin(const Header& header);
    /// Appends one message. Its fields must be in range (as the decoder checks); input runs are
    /// sized with `shape`. Returns false, leaving the datagram unchanged, when the message is
    /// out of range or the datagram would exceed `limit` bytes.
    bool Add(const Message& message, const SessionShape& shape, size_t limit = 1200);
    /// Encoded size of a message (0 when out of range).
    static size_t SizeOf(const Message& message, const SessionShape& shape);
    /// Number of messages appended since Begin.
    size_t MessageCount() const noexcept { return m_messages; }
    /// The datagram so far.
    std::span<const uint8_t> Bytes() const noexcept { return m_bytes; }
    /// Bytes of the datagram so far (header included).
    size_t Size() const noexcept { return m_bytes.size(); }

private:
    std::vector<uint8_t> m_bytes;
    std::vector<uint8_t> m_scratch;
    size_t m_messages = 0;
};

/// Counts of refused datagrams by DecodeError (index = error value; e_ok unused).
using DecodeErrorCounts = std::array<uint64_t, static_cast<size_t>(DecodeError::e_count)>;

}  // namespace lockbox::net
