// b2World::Save, SaveStats, Restore and Hash: the snapshot image is a fixed header then six
// sections (settings, bodies, fixtures, contacts, joints, broad-phase), each a tag, a byte
// length and the state walk of StateWalk.h, all through Cereal's portable binary archive.
// docs/determinism.md ("Snapshot format") is the layout's reference.

#include <xxhash.h>

#include "ByteStreams.h"
#include "SnapshotImage.h"
#include "StateWalk.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

using namespace state_detail;

namespace {

template <class WriteFn>
void WriteSection(SnapshotWriter& w, uint32 tag, WriteFn write) {
    w.U32(tag);
    const size_t lengthAt = w.Position();
    w.U32(0);
    write();
    w.Patch32(lengthAt, static_cast<uint32>(w.Position() - lengthAt - 4));
}

}  // namespace

const char* b2SnapshotErrorName(b2SnapshotError error) noexcept {
    switch (error) {
        case b2SnapshotError::e_ok: return "ok";
        case b2SnapshotError::e_truncated: return "truncated";
        case b2SnapshotError::e_badEndianFlag: return "bad endianness flag";
        case b2SnapshotError::e_badMagic: return "bad magic";
        case b2SnapshotError::e_badFormatVersion: return "bad format version";
        case b2SnapshotError::e_badDeterminismVersion: return "bad determinism version";
        case b2SnapshotError::e_badChecksum: return "bad checksum";
        case b2SnapshotError::e_corrupt: return "corrupt";
        case b2SnapshotError::e_trailingBytes: return "trailing bytes";
        case b2SnapshotError::e_locked: return "locked";
    }
    return "unknown";
}

uint64 b2World::Hash() const { return b2WorldHash(*this); }

void b2World::Save(std::vector<uint8>& out) const {
    out.clear();
    SnapshotWriter w(out);  // Cereal writes its endianness flag (1: little-endian) first
    w.U32(b2_snapshotMagic);
    w.U16(b2_snapshotFormatVersion);
    w.U16(lockbox_versionMajor);
    w.U16(lockbox_versionMinor);
    w.U16(lockbox_versionPatch);
    w.U32(b2_determinismVersion);
    w.U64(0);  // payload size, patched below
    w.U64(0);  // payload checksum, patched below
    WriteSection(w, e_sectionSettings, [&] { WriteSettings(w, *this); });
    WriteSection(w, e_sectionBodies, [&] { WriteBodies(w, *this); });
    WriteSection(w, e_sectionFixtures, [&] { WriteFixtures(w, *this); });
    WriteSection(w, e_sectionContacts, [&] { WriteContacts(w, *this); });
    WriteSection(w, e_sectionJoints, [&] { WriteJoints(w, *this); });
    WriteSection(w, e_sectionBroadPhase, [&] { WriteBroadPhase(w, *this); });
    const size_t payload = w.Position() - kHeaderBytes;
    w.Patch64(kPayloadSizeOffset, payload);
    w.Patch64(kChecksumOffset, XXH3_64bits(w.Data(kHeaderBytes), payload));
    w.Finish();
}

std::vector<uint8> b2World::Save() const {
    std::vector<uint8> out;
    Save(out);
    return out;
}

b2SnapshotStats b2World::SaveStats() const {
    const std::vector<uint8> image = Save();
    b2SnapshotStats stats;
    stats.headerBytes = static_cast<uint32>(kHeaderBytes);
    stats.totalBytes = static_cast<uint32>(image.size());
    uint32* bySection[kSectionCount] = {&stats.settingsBytes, &stats.fixtureBytes, &stats.bodyBytes,
                                        &stats.contactBytes, &stats.jointBytes, &stats.broadPhaseBytes};
    bySection[1] = &stats.bodyBytes;
    bySection[2] = &stats.fixtureBytes;
    // Walk the section headers: tag, length (little-endian), contents. The 8 header bytes
    // count toward their section.
    size_t at = kHeaderBytes;
    auto le32 = [&](size_t i) {
        return uint32{image[i]} | (uint32{image[i + 1]} << 8) | (uint32{image[i + 2]} << 16) | (uint32{image[i + 3]} << 24);
    };
    for (uint32 s = 0; s < kSectionCount && at + 8 <= image.size(); ++s) {
        const uint32 length = le32(at + 4);
        *bySection[s] = length + 8;
        at += 8 + length;
    }
    return stats;
}

b2RestoreResult b2World::Restore(std::span<const uint8> image) {
    if (IsLocked()) {
        CheckLocked("b2World::Restore called inside a Step callback (the world is locked)");
        return {b2SnapshotError::e_locked, "the world is locked (inside Step)"};
    }
    Image parsed;
    b2RestoreResult result = ParseSnapshot(image, parsed);
    if (!result.ok()) return result;
    ApplySnapshot(parsed, *this);
    return result;
}

}  // namespace lockbox
