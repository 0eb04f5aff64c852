// Chunked snapshot transfer (SnapshotTransfer.h).

#include "session/SnapshotTransfer.h"

#include <zstd.h>

#include <algorithm>
#include <cstring>

namespace lockbox::net {

namespace {

// Level 1: a 5 MB world image compresses in about 16 ms and to within 2 % of level 3 (the
// images are mostly small integers and repeated shapes), and a late join compresses once.
constexpr int kCompressionLevel = 1;

}  // namespace

CompressedSnapshot SnapshotSender::Compress(std::span<const uint8_t> plain) {
    if (plain.empty() || plain.size() > kMaxSnapshotBytes) return nullptr;
    std::vector<uint8_t> out(ZSTD_compressBound(plain.size()));
    const size_t n = ZSTD_compress(out.data(), out.size(), plain.data(), plain.size(), kCompressionLevel);
    if (ZSTD_isError(n) || n > kMaxSnapshotBytes) return nullptr;
    out.resize(n);
    return std::make_shared<const std::vector<uint8_t>>(std::move(out));
}

void SnapshotSender::Start(int32_t frame, CompressedSnapshot compressed) {
    m_blob = compressed != nullptr && !compressed->empty() ? std::move(compressed) : nullptr;
    m_frame = frame;
    m_chunkCount =
        Active() ? static_cast<uint32_t>((m_blob->size() + kSnapshotChunkBytes - 1) / kSnapshotChunkBytes) : 0;
    m_acked = 0;
    m_ackedFlags.assign(m_chunkCount, 0);
    m_sentAt.assign(m_chunkCount, 0);
    m_sends.assign(m_chunkCount, 0);
    m_cursor = 0;
}

void SnapshotSender::Stop() noexcept {
    m_blob.reset();
    m_chunkCount = m_acked = 0;
}

void SnapshotSender::OnAck(const SnapshotAck& ack, uint64_t now) noexcept {
    if (!Active() || ack.frame != m_frame || ack.index >= m_chunkCount || m_ackedFlags[ack.index]) return;
    m_ackedFlags[ack.index] = 1;
    ++m_acked;
    // A resent chunk's ack may answer either send: no sample from it.
    if (m_sends[ack.index] == 1 && now >= m_sentAt[ack.index]) m_rtt.Sample(now - m_sentAt[ack.index]);
}

uint64_t SnapshotSender::ResendMicros(uint64_t floor) const noexcept {
    constexpr uint64_t kCeiling = 1'000'000;
    if (m_rtt.Samples() == 0) return floor;
    const uint64_t rto = std::min(m_rtt.Srtt() + 4 * std::min(m_rtt.Var(), kCeiling), kCeiling);
    return std::max(floor, rto);
}

size_t SnapshotSender::Pump(uint64_t now, uint64_t resendMicros, size_t window,
                            const std::function<void(const SnapshotChunk&)>& send) {
    if (!Active() || Done()) return 0;
    resendMicros = ResendMicros(resendMicros);
    size_t sent = 0;
    // One sweep from where the last call stopped (m_cursor moves as chunks go, so the sweep
    // keeps its own start).
    const uint32_t start = m_cursor;
    for (uint32_t step = 0; step < m_chunkCount && sent < window; ++step) {
        const uint32_t i = (start + step) % m_chunkCount;
        if (m_ackedFlags[i]) continue;
        // m_sentAt 0 means never; a resend waits resendMicros after the last send.
        if (m_sentAt[i] != 0 && now - m_sentAt[i] < resendMicros) continue;
        const size_t offset = size_t{i} * kSnapshotChunkBytes;
        const std::vector<uint8_t>& blob = *m_blob;
        const size_t len = std::min<size_t>(kSnapshotChunkBytes, blob.size() - offset);
        m_chunk.frame = m_frame;
        m_chunk.totalSize = static_cast<uint32_t>(blob.size());
        m_chunk.index = i;
        m_chunk.bytes.assign(blob.begin() + static_cast<std::ptrdiff_t>(offset),
                             blob.begin() + static_cast<std::ptrdiff_t>(offset + len));
        send(m_chunk);
        m_sentAt[i] = now == 0 ? 1 : now;
        m_sends[i] = static_cast<uint8_t>(std::min(m_sends[i] + 1, 2));
        ++sent;
        m_cursor = (i + 1) % m_chunkCount;
    }
    return sent;
}

bool SnapshotReceiver::Accept(const SnapshotChunk& chunk) {
    if (m_active && chunk.frame < m_frame) return false;
    if (!m_active || chunk.frame != m_frame || chunk.totalSize != m_total) {
        // A newer snapshot (the old source may have restarted): assemble that one instead.
        m_active = true;
        m_frame = chunk.frame;
        m_total = chunk.totalSize;
        m_chunkCount = (m_total + kSnapshotChunkBytes - 1) / kSnapshotChunkBytes;
        m_received = 0;
        m_failed = false;
        m_blob.assign(m_total, 0);
        m_plain.clear();
        m_have.assign(m_chunkCount, 0);
    }
    const size_t offset = size_t{chunk.index} * kSnapshotChunkBytes;
    // The codec already checked index and length against totalSize; check again before copying.
    // (Against m_total: the compressed bytes are freed once decompressed, and a repeated chunk
    // is still acked.)
    if (chunk.index >= m_chunkCount || offset + chunk.bytes.size() > m_total) return false;
    if (!m_have[chunk.index]) {
        if (!chunk.bytes.empty()) std::memcpy(m_blob.data() + offset, chunk.bytes.data(), chunk.bytes.size());
        m_have[chunk.index] = 1;
        ++m_received;
        if (m_received == m_chunkCount) Decompress();
    }
    return true;
}

void SnapshotReceiver::Decompress() {
    // The announced size is checked before anything is allocated, and the frame must fill the
    // bytes exactly: a hostile sender can neither make us allocate beyond m_maxBytes nor hide
    // trailing data.
    const uint64_t size = ZSTD_getFrameContentSize(m_blob.data(), m_blob.size());
    const size_t frameBytes = ZSTD_findFrameCompressedSize(m_blob.data(), m_blob.size());
    m_failed = size == ZSTD_CONTENTSIZE_UNKNOWN || size == ZSTD_CONTENTSIZE_ERROR || size == 0 ||
               size > std::min(m_maxBytes, kMaxSnapshotBytes) || ZSTD_isError(frameBytes) ||
               frameBytes != m_blob.size();
    if (!m_failed) {
        m_plain.resize(static_cast<size_t>(size));
        const size_t n = ZSTD_decompress(m_plain.data(), m_plain.size(), m_blob.data(), m_blob.size());
        m_failed = ZSTD_isError(n) || n != m_plain.size();
    }
    if (m_failed) m_plain.clear();
    m_blob.clear();
    m_blob.shrink_to_fit();
}

void SnapshotReceiver::Reset() noexcept {
    m_active = false;
    m_frame = 0;
    m_total = m_chunkCount = m_received = 0;
    m_failed = false;
    m_blob.clear();
    m_plain.clear();
    m_have.clear();
}

}  // namespace lockbox::net
