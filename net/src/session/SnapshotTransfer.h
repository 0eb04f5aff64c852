#pragma once
// Chunked snapshot transfer over an unreliable transport (late join, docs/net.md "Late
// join"): the sender keeps a window of chunks in flight and resends each until its
// SnapshotAck arrives; the receiver reassembles chunks in any order and acks every one. The
// resend timer follows the round trip the acks show (chunks sent once only, as Karn's rule
// says), so a receiver farther away than the configured timer does not get every chunk twice.
// The blob travels as one zstd frame (level 1): world images shrink 3.5-7x, so a joiner waits
// for that many fewer chunks; the receiver hands out the decompressed bytes.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "lockbox/net/Protocol.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

/// A snapshot blob as one zstd frame, compressed once and shared by every sender of it (a
/// late join offered to several joiners at once compresses it once).
using CompressedSnapshot = std::shared_ptr<const std::vector<uint8_t>>;

/// How the lockstep server and client pace the snapshots they send (SnapshotSender::Pump): the
/// resend timer's floor, and the chunks sent per call. One setting for both ends of a late join.
inline constexpr uint64_t kSnapshotResendMicros = 100'000;
inline constexpr size_t kSnapshotWindow = 16;

/// Sends one snapshot blob, compressed, in kSnapshotChunkBytes pieces.
class SnapshotSender {
public:
    /// `blob` (1 .. kMaxSnapshotBytes bytes, and at most that compressed) as one zstd frame;
    /// null otherwise.
    static CompressedSnapshot Compress(std::span<const uint8_t> blob);
    /// Starts sending `blob` (see Compress) as the snapshot of `frame`; a blob Compress refuses
    /// sends nothing (Active() false).
    void Start(int32_t frame, std::span<const uint8_t> blob) { Start(frame, Compress(blob)); }
    /// Starts sending an already compressed blob; null sends nothing (Active() false).
    void Start(int32_t frame, CompressedSnapshot compressed);
    /// Forgets the current snapshot.
    void Stop() noexcept;
    bool Active() const noexcept { return m_blob != nullptr; }
    /// True when every chunk was acknowledged.
    bool Done() const noexcept { return Active() && m_acked == m_chunkCount; }
    int32_t Frame() const noexcept { return m_frame; }
    /// Chunks of the current snapshot (of its compressed bytes).
    uint32_t ChunkCount() const noexcept { return m_chunkCount; }
    /// Marks a chunk delivered (acks of another frame or out of range are ignored); `now` (the
    /// clock Pump is given) samples the round trip of a chunk that was sent once.
    void OnAck(const SnapshotAck& ack, uint64_t now) noexcept;
    /// Calls `send` for each chunk that is due: never sent, or unacked for ResendMicros; at
    /// most `window` chunks per call. Returns how many were sent.
    size_t Pump(uint64_t now, uint64_t resendMicros, size_t window,
                const std::function<void(const SnapshotChunk&)>& send);
    /// The resend timer: `floor` until an ack gave a round trip, then the smoothed round trip
    /// plus four deviations (RFC 6298's timeout), never below `floor` nor above one second.
    uint64_t ResendMicros(uint64_t floor) const noexcept;

private:
    int32_t m_frame = 0;
    CompressedSnapshot m_blob;  ///< the compressed snapshot (shared, never modified); null: inactive
    uint32_t m_chunkCount = 0, m_acked = 0;
    std::vector<uint8_t> m_ackedFlags;
    std::vector<uint64_t> m_sentAt;  ///< 0: never sent
    std::vector<uint8_t> m_sends;    ///< sends per chunk, saturating at 2 (only 1 gives a sample)
    RttEstimator m_rtt;              ///< kept across snapshots to the same receiver
    uint32_t m_cursor = 0;           ///< round-robin start, so resends do not starve later chunks
    SnapshotChunk m_chunk;
};

/// Reassembles one snapshot and decompresses it.
class SnapshotReceiver {
public:
    /// `maxBytes`: the largest decompressed snapshot accepted (at most kMaxSnapshotBytes).
    explicit SnapshotReceiver(uint32_t maxBytes = kMaxSnapshotBytes) noexcept : m_maxBytes(maxBytes) {}

    /// Takes a chunk. A chunk of a newer frame (or a different size) restarts the assembly; one
    /// of an older frame is ignored. Returns true when the chunk belongs to the current
    /// snapshot (the caller acks it). The last chunk decompresses the snapshot.
    bool Accept(const SnapshotChunk& chunk);
    bool Active() const noexcept { return m_active; }
    /// Every chunk arrived: Blob() is the snapshot, or Failed().
    bool Complete() const noexcept { return m_active && m_received == m_chunkCount; }
    /// Complete, but the bytes are not one whole zstd frame of 1 .. maxBytes bytes (a corrupt
    /// or hostile sender): Blob() is empty. Reset, then ask for the snapshot again.
    bool Failed() const noexcept { return Complete() && m_failed; }
    /// Distinct chunks of the current snapshot received so far.
    uint32_t Received() const noexcept { return m_received; }
    int32_t Frame() const noexcept { return m_frame; }
    /// The decompressed snapshot once Complete() (empty before, and when Failed()).
    std::span<const uint8_t> Blob() const noexcept { return m_plain; }
    void Reset() noexcept;

private:
    void Decompress();

    uint32_t m_maxBytes;
    bool m_active = false;
    bool m_failed = false;
    int32_t m_frame = 0;
    uint32_t m_total = 0, m_chunkCount = 0, m_received = 0;
    std::vector<uint8_t> m_blob;   ///< compressed, as the chunks arrive
    std::vector<uint8_t> m_plain;  ///< decompressed, once complete
    std::vector<uint8_t> m_have;
};

}  // namespace lockbox::net
