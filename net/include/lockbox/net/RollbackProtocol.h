#pragma once
/// @file
/// The rollback wire protocol (docs/rollback.md): what RollbackPeer sessions and
/// their spectators exchange. Same conventions as the lockstep codec (Protocol.h): a header,
/// then one or more messages, each a type byte and its fields; little-endian fixed widths,
/// minimal LEB128 varints for frames, times and counts; input runs with the repeat bitmap.
///
/// Header (7 bytes): magic u16 'R' 'B', protocol version u8, match id u32 (both peers are
/// given the same id; a datagram of another match is refused before its messages are read).
/// A known sender whose datagrams show another version, match id, engine determinism version
/// or session shape (RbHello) is reported once as incompatible (RollbackIncompatibility).
///
/// Decoding never reads past the buffer and checks every field; a datagram with any malformed
/// message is refused whole, with a DecodeError (Protocol.h) saying why. Encoding is
/// canonical: decoding and encoding again gives the same bytes.

#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Protocol.h"
#include "lockbox/net/RollbackSession.h"

namespace lockbox::net {

/// First two bytes of every rollback datagram: 'R' 'B'.
inline constexpr uint16_t kRollbackMagic = 0x4252u;
/// Bumped whenever a message layout or a rule of the exchange changes (2: the late-join
/// snapshot messages; 3: RbView and RbFrozen, the disconnect agreement; 4: RbHello, the
/// compatibility check; 5: snapshot chunks carry the state as one zstd frame; 6: RbDelayWish,
/// the budget guard's delay; 7: the start phase, same layouts: a peer waits for a round trip
/// with every remote before frame 0 and times none out before it, where a version-6 peer
/// started at once and cut a late remote at frame 0; 8: RbQuality's sequence byte, the loss
/// estimate). Other versions are refused by name.
inline constexpr uint8_t kRollbackProtocolVersion = 8;
/// Bytes of the header.
inline constexpr size_t kRollbackHeaderBytes = 7;
/// Largest frame count of one input run.
inline constexpr uint32_t kRollbackMaxRun = 128;
/// Payload bytes of every snapshot chunk but the last (a chunk datagram stays under 1100 bytes).
inline constexpr uint32_t kRbSnapshotChunkBytes = 1024;
/// Largest snapshot a spectator accepts, on the wire and decompressed (16 MiB).
inline constexpr uint32_t kRbMaxSnapshotBytes = 16u << 20;

/// The datagram header.
struct RollbackHeader {
    /// Protocol version of the sender (kRollbackProtocolVersion); another version is refused by
    /// name.
    uint8_t version = kRollbackProtocolVersion;
    uint32_t matchId = 0;  ///< the match both peers were configured with
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RollbackHeader&) const = default;
};

/// One player's inputs for frames [firstFrame, firstFrame + count): the frames the receiver
/// has not acknowledged yet, resent in every datagram until acked.
struct RbInputs {
    uint8_t player = 0;          ///< < players
    int32_t firstFrame = 0;      ///< >= 0
    std::vector<uint8_t> bytes;  ///< count * inputBytes, count in 1 .. kRollbackMaxRun
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbInputs&) const = default;
};

/// Every input of `player` before nextFrame has arrived. (Peers since version 3 send RbView
/// instead, which carries the same for every player; this one still decodes.)
struct RbInputAck {
    /// The player whose inputs are acknowledged (< players).
    uint8_t player = 0;
    int32_t nextFrame = 0;  ///< >= 0
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbInputAck&) const = default;
};

/// Time sync and RTT: the sender's current frame, its frame advantage over the receiver as it
/// sees it (thousandths of a frame, positive: the sender is ahead), and its clock for the
/// receiver to echo.
struct RbQuality {
    int32_t frame = 0;           ///< >= 0
    int32_t advantageMilli = 0;  ///< any int32 (zigzag varint)
    uint64_t time = 0;           ///< sender clock, microseconds
    /// Counts the sender's datagrams to this receiver, wrapping at 256 (loss estimate).
    uint8_t sequence = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbQuality&) const = default;
};

/// Answer to RbQuality: its time and how long the answerer held it (microseconds).
struct RbQualityReply {
    /// RbQuality.time of the message being answered, microseconds on the asker's clock.
    uint64_t echoTime = 0;
    /// Microseconds between the answerer's receiving the RbQuality and sending this reply; the
    /// asker subtracts it from the round trip.
    uint64_t holdMicros = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbQualityReply&) const = default;
};

/// The sender's final state hash of `frame` (all inputs before it confirmed, no rollback
/// pending). Sent several times; duplicates are harmless.
struct RbHash {
    int32_t frame = 0;  ///< >= 0
    /// The state hash after that frame (the world hash folded with the game's saved state).
    uint64_t hash = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbHash&) const = default;
};

/// Every player's confirmed inputs of [firstFrame, firstFrame + count), for spectators
/// (players * inputBytes per frame, player 0 first), resent until acked.
struct RbConfirmed {
    int32_t firstFrame = 0;      ///< >= 0
    std::vector<uint8_t> bytes;  ///< count * players * inputBytes, count in 1 .. kRollbackMaxRun
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbConfirmed&) const = default;
};

/// Spectator -> host: every confirmed frame before nextFrame has arrived.
struct RbConfirmedAck {
    /// First confirmed frame the spectator does not hold yet (>= 0).
    int32_t nextFrame = 0;
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbConfirmedAck&) const = default;
};

/// Spectator -> host: "I join late, send me a snapshot". `attempt` starts at 1 and grows
/// by one each time the spectator refuses an assembled snapshot (bad checksum): the host
/// starts a new snapshot when it sees a larger attempt than the last one it served.
struct RbJoinRequest {
    uint32_t attempt = 1;  ///< >= 1
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbJoinRequest&) const = default;
};

/// Host -> spectator: one piece of the game state saved at confirmed frame `frame` (the
/// state before frame `frame`'s inputs). Every chunk repeats the size and checksum so any
/// chunk can start the assembly; the payload is the bytes [index * kRbSnapshotChunkBytes,
/// + min(kRbSnapshotChunkBytes, totalSize - index * kRbSnapshotChunkBytes)).
struct RbSnapshotChunk {
    int32_t frame = 0;           ///< >= 0
    uint32_t totalSize = 0;      ///< 1 .. kRbMaxSnapshotBytes
    uint64_t checksum = 0;       ///< XXH3-64 of the whole snapshot
    uint32_t index = 0;          ///< index * kRbSnapshotChunkBytes < totalSize
    std::vector<uint8_t> bytes;  ///< exactly the payload length above
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbSnapshotChunk&) const = default;
};

/// Spectator -> host: chunk `index` of the snapshot of `frame` arrived.
struct RbSnapshotAck {
    int32_t frame = 0;   ///< >= 0
    uint32_t index = 0;  ///< < kRbMaxSnapshotBytes / kRbSnapshotChunkBytes
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbSnapshotAck&) const = default;
};

/// Nothing to say, still here.
struct RbKeepAlive {
    /// Always equal: the message has no fields.
    bool operator==(const RbKeepAlive&) const = default;
};

/// The sender leaves the match.
struct RbDisconnect {
    /// Always equal: the message has no fields.
    bool operator==(const RbDisconnect&) const = default;
};

/// The sender's view: for every player of the match (player 0 first), the first frame of its
/// inputs the sender does not hold. The receiver takes its own players' entries as acks, and
/// no frame at or past any entry becomes final on the receiver (RollbackSession::SetPeerView).
/// Wire: the smallest entry as a varint, then each entry minus it as a varint (at least one
/// of them 0, so the encoding is canonical).
struct RbView {
    std::vector<int32_t> received;  ///< exactly `players` entries, each >= 0
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbView&) const = default;
};

/// The sender considers `player` gone and froze it at `frame` (its received frame for that
/// player then). Repeated in every datagram to every live remote for the rest of the match.
/// A receiver that has not frozen the player yet does so now (gossip); the cut is the
/// smallest frozen value once every live peer's is known.
struct RbFrozen {
    uint8_t player = 0;  ///< < players
    int32_t frame = 0;   ///< >= 0
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbFrozen&) const = default;
};

/// What the sender simulates with, so that a peer or spectator that could only desync is
/// named at once instead of playing on: the first message of a datagram, sent by a peer to a
/// remote until the remote's view shows it took one of this peer's inputs (so it read a
/// hello), by a host in every input-stream and keep-alive datagram to a spectator, and by a
/// spectator in every datagram to its host. Decoded without the session shape: a hello whose
/// shape differs from the receiver's stops the decoding (DecodeError::e_incompatible).
struct RbHello {
    uint32_t determinismVersion = 0;  ///< the sender's b2_determinismVersion (state/WorldHash.h)
    uint8_t players = 0;              ///< 1 .. kRollbackMaxPlayers
    uint32_t inputBytes = 0;          ///< 1 .. kRollbackMaxInputBytes (varint)
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbHello&) const = default;
};

/// The input delay the sender asks the receiver to use at least: its budget guard's choice
/// (RollbackBudgetGuard.h). A peer's rollbacks are as deep as the other peers' inputs are
/// late, so it is their delay that makes them shallower. Sent in every datagram to every
/// remote once the game has set a wish (RollbackPeer::AskInputDelay).
struct RbDelayWish {
    uint8_t frames = 0;  ///< 0 .. kRollbackMaxInputDelay
    /// Field-wise equality, as the round-trip tests compare decode(encode(m)) with m.
    bool operator==(const RbDelayWish&) const = default;
};

/// Any rollback message.
using RollbackMessage =
    std::variant<RbInputs, RbInputAck, RbQuality, RbQualityReply, RbHash, RbConfirmed, RbConfirmedAck, RbKeepAlive,
                 RbDisconnect, RbJoinRequest, RbSnapshotChunk, RbSnapshotAck, RbView, RbFrozen, RbHello, RbDelayWish>;

/// Type byte of each message (the variant index + 1).
enum class RollbackMessageType : uint8_t {
    e_inputs = 1,
    e_inputAck,
    e_quality,
    e_qualityReply,
    e_hash,
    e_confirmed,
    e_confirmedAck,
    e_keepAlive,
    e_disconnect,
    e_joinRequest,
    e_snapshotChunk,
    e_snapshotAck,
    e_view,
    e_frozen,
    e_hello,
    e_delayWish,
    e_end
};

/// The reason a datagram from a known sender shows, from its decoding (`error`, `header`
/// and, when the decoding succeeded or stopped at a hello, `messages`): e_none when it
/// carries no sign of one. `determinismVersion` is the receiver's.
LOCKBOX_API RollbackIncompatibility FindIncompatibility(DecodeError error, const RollbackHeader& header,
                                                        std::span<const RollbackMessage> messages, uint32_t matchId,
                                                        uint32_t determinismVersion) noexcept;

/// What the decoder must know to size input runs.
struct RollbackShape {
    uint32_t players = 0;     ///< 1 .. kRollbackMaxPlayers (RollbackSession.h); 0 refuses inputs
    uint32_t inputBytes = 0;  ///< 1 .. kRollbackMaxInputBytes
};

/// The hello of a sender simulating with `determinismVersion` and `shape`.
inline RbHello HelloFor(uint32_t determinismVersion, const RollbackShape& shape) noexcept {
    return RbHello{determinismVersion, static_cast<uint8_t>(shape.players), shape.inputBytes};
}

/// Decodes a whole datagram (messages appended to `out` after clearing it; empty on error,
/// except e_incompatible: an RbHello for another shape, which is then all `out` holds).
LOCKBOX_API DecodeError DecodeRollbackDatagram(std::span<const uint8_t> datagram, const RollbackShape& shape,
                                               RollbackHeader& header, std::vector<RollbackMessage>& out);

/// Builds one datagram: the header, then messages appended one by one.
class LOCKBOX_API RollbackDatagramWriter {
public:
    /// Starts a datagram (replaces any previous contents).
    void Begin(const RollbackHeader& header);
    /// Appends a message whose fields are in range; false (datagram unchanged) when a field is
    /// out of range or the datagram would exceed `limit` bytes.
    bool Add(const RollbackMessage& message, const RollbackShape& shape, size_t limit = 1200);
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

}  // namespace lockbox::net
