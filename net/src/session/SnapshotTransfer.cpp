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
    blob_ = compressed != nullptr && !compressed->empty() ? std::move(compressed) : nullptr;
    frame_ = frame;
    chunkCount_ = Active() ? static_cast<uint32_t>((blob_->size() + kSnapshotChunkBytes - 1) / kSnapshotChunkBytes) : 0;
    acked_ = 0;
    ackedFlags_.assign(chunkCount_, 0);
    sentAt_.assign(chunkCount_, 0);
    sends_.assign(chunkCount_, 0);
    cursor_ = 0;
}

void SnapshotSender::Stop() noexcept {
    blob_.reset();
    chunkCount_ = acked_ = 0;
}

void SnapshotSender::OnAck(const SnapshotAck& ack, uint64_t now) noexcept {
    if (!Active() || ack.frame != frame_ || ack.index >= chunkCount_ || ackedFlags_[ack.index]) return;
    ackedFlags_[ack.index] = 1;
    ++acked_;
    // A resent chunk's ack may answer either send: no sample from it.
    if (sends_[ack.index] == 1 && now >= sentAt_[ack.index]) rtt_.Sample(now - sentAt_[ack.index]);
}

uint64_t SnapshotSender::ResendMicros(uint64_t floor) const noexcept {
    constexpr uint64_t kCeiling = 1'000'000;
    if (rtt_.Samples() == 0) return floor;
    const uint64_t rto = std::min(rtt_.Srtt() + 4 * std::min(rtt_.Var(), kCeiling), kCeiling);
    return std::max(floor, rto);
}

size_t SnapshotSender::Pump(uint64_t now, uint64_t resendMicros, size_t window,
                            const std::function<void(const SnapshotChunk&)>& send) {
    if (!Active() || Done()) return 0;
    resendMicros = ResendMicros(resendMicros);
    size_t sent = 0;
    // One sweep from where the last call stopped (cursor_ moves as chunks go, so the sweep
    // keeps its own start).
    const uint32_t start = cursor_;
    for (uint32_t step = 0; step < chunkCount_ && sent < window; ++step) {
        const uint32_t i = (start + step) % chunkCount_;
        if (ackedFlags_[i]) continue;
        // sentAt_ 0 means never; a resend waits resendMicros after the last send.
        if (sentAt_[i] != 0 && now - sentAt_[i] < resendMicros) continue;
        const size_t offset = size_t{i} * kSnapshotChunkBytes;
        const std::vector<uint8_t>& blob = *blob_;
        const size_t len = std::min<size_t>(kSnapshotChunkBytes, blob.size() - offset);
        chunk_.frame = frame_;
        chunk_.totalSize = static_cast<uint32_t>(blob.size());
        chunk_.index = i;
        chunk_.bytes.assign(blob.begin() + static_cast<std::ptrdiff_t>(offset),
                            blob.begin() + static_cast<std::ptrdiff_t>(offset + len));
        send(chunk_);
        sentAt_[i] = now == 0 ? 1 : now;
        sends_[i] = static_cast<uint8_t>(std::min(sends_[i] + 1, 2));
        ++sent;
        cursor_ = (i + 1) % chunkCount_;
    }
    return sent;
}

bool SnapshotReceiver::Accept(const SnapshotChunk& chunk) {
    if (active_ && chunk.frame < frame_) return false;
    if (!active_ || chunk.frame != frame_ || chunk.totalSize != total_) {
        // A newer snapshot (the old source may have restarted): assemble that one instead.
        active_ = true;
        frame_ = chunk.frame;
        total_ = chunk.totalSize;
        chunkCount_ = (total_ + kSnapshotChunkBytes - 1) / kSnapshotChunkBytes;
        received_ = 0;
        failed_ = false;
        blob_.assign(total_, 0);
        plain_.clear();
        have_.assign(chunkCount_, 0);
    }
    const size_t offset = size_t{chunk.index} * kSnapshotChunkBytes;
    // The codec already checked index and length against totalSize; check again before copying.
    // (Against total_: the compressed bytes are freed once decompressed, and a repeated chunk
    // is still acked.)
    if (chunk.index >= chunkCount_ || offset + chunk.bytes.size() > total_) return false;
    if (!have_[chunk.index]) {
        if (!chunk.bytes.empty()) std::memcpy(blob_.data() + offset, chunk.bytes.data(), chunk.bytes.size());
        have_[chunk.index] = 1;
        ++received_;
        if (received_ == chunkCount_) Decompress();
    }
    return true;
}

void SnapshotReceiver::Decompress() {
    // The announced size is checked before anything is allocated, and the frame must fill the
    // bytes exactly: a hostile sender can neither make us allocate beyond maxBytes_ nor hide
    // trailing data.
    const uint64_t size = ZSTD_getFrameContentSize(blob_.data(), blob_.size());
    const size_t frameBytes = ZSTD_findFrameCompressedSize(blob_.data(), blob_.size());
    failed_ = size == ZSTD_CONTENTSIZE_UNKNOWN || size == ZSTD_CONTENTSIZE_ERROR || size == 0 ||
              size > std::min(maxBytes_, kMaxSnapshotBytes) || ZSTD_isError(frameBytes) || frameBytes != blob_.size();
    if (!failed_) {
        plain_.resize(static_cast<size_t>(size));
        const size_t n = ZSTD_decompress(plain_.data(), plain_.size(), blob_.data(), blob_.size());
        failed_ = ZSTD_isError(n) || n != plain_.size();
    }
    if (failed_) plain_.clear();
    blob_.clear();
    blob_.shrink_to_fit();
}

void SnapshotReceiver::Reset() noexcept {
    active_ = false;
    frame_ = 0;
    total_ = chunkCount_ = received_ = 0;
    failed_ = false;
    blob_.clear();
    plain_.clear();
    have_.clear();
}

}  // namespace lockbox::net
