// b2World::Save, SaveStats, Restore and Hash: the snapshot image is a fixed header then seven
// sections (settings, bodies, fixtures, contacts, joints, broad-phase, joint reactions), each
// a tag, a byte length and a walk of StateWalk.h (the first six are the hash categories'), the
// header through Cereal's portable binary archive. SnapshotFormat.h holds the layout and
// docs/determinism.md ("Snapshot format") every field.

#include <ostream>

#include <cereal/archives/portable_binary.hpp>

#include "ByteStreams.h"
#include "FastXxh3.h"
#include "SnapshotImage.h"
#include "StateWalk.h"
#include "dynamics/WorldState.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

using namespace state_detail;

namespace {

template <class WriteFn>
void WriteSection(FieldWriter& w, uint32 tag, WriteFn write) {
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
        case b2SnapshotError::e_foreignFrame: return "foreign frame";
    }
    return "unknown";
}

void state_detail::ImageDeleter::operator()(Image* image) const noexcept { delete image; }

uint64 state_detail::SnapshotChecksum(std::span<const uint8> image, size_t payloadBytes) noexcept {
    const uint64 seed = Xxh3(image.data(), kChecksumOffset);
    return Xxh3Seeded(image.data() + kHeaderBytes, payloadBytes, seed);
}

void b2SealSnapshot(std::span<uint8> image) noexcept {
    if (image.size() < kHeaderBytes) return;
    const uint64 sum = SnapshotChecksum(image, image.size() - kHeaderBytes);
    for (size_t i = 0; i < 8; ++i) image[kChecksumOffset + i] = static_cast<uint8>(sum >> (8 * i));
}

uint64 b2World::Hash() const { return b2WorldHash(*this); }

void b2World::Save(std::vector<uint8>& out) const { SaveImage(*this, out, /*withContacts=*/true); }

void state_detail::SaveImage(const b2World& world, std::vector<uint8>& out, bool withContacts) {
    // Sections first, after room for the header: their size goes into the header.
    FieldWriter w(out, kHeaderBytes);
    WriteSection(w, e_sectionSettings, [&] { WriteSettings(w, world, withContacts); });
    WriteSection(w, e_sectionBodies, [&] { WriteBodies(w, world); });
    WriteSection(w, e_sectionFixtures, [&] { WriteFixtures(w, world); });
    WriteSection(w, e_sectionContacts, [&] {
        if (withContacts)
            WriteContacts(w, world);
        else
            WriteNoContacts(w);
    });
    WriteSection(w, e_sectionJoints, [&] { WriteJoints(w, world); });
    WriteSection(w, e_sectionBroadPhase, [&] { WriteBroadPhase(w, world); });
    WriteSection(w, e_sectionJointReactions, [&] { WriteJointReactions(w, world); });
    const uint64 payload = w.Position() - kHeaderBytes;
    w.Finish();
    {
        // The header through Cereal's portable binary archive: its endianness flag (1), then
        // the fields little-endian; the checksum is patched in last.
        HeaderSink sink(out.data(), kHeaderBytes);
        std::ostream stream(&sink);
        cereal::PortableBinaryOutputArchive archive(stream,
                                                    cereal::PortableBinaryOutputArchive::Options::LittleEndian());
        archive(b2_snapshotMagic, b2_snapshotFormatVersion, b2_snapshotEngineMajor, b2_snapshotEngineMinor,
                b2_snapshotEnginePatch, b2_determinismVersion, payload, uint64{0});
    }
    b2SealSnapshot(out);  // the checksum of the payload just written
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
    uint32* bySection[kSectionCount] = {&stats.settingsBytes,     &stats.bodyBytes,  &stats.fixtureBytes,
                                        &stats.contactBytes,      &stats.jointBytes, &stats.broadPhaseBytes,
                                        &stats.jointReactionBytes};
    // Walk the section headers: tag, length, contents. The 8 header bytes count toward their
    // section.
    bytes::Reader r(image, kHeaderBytes);
    for (uint32 s = 0; s < kSectionCount && r.Remaining() >= kSectionHeaderBytes; ++s) {
        (void)r.U32();
        const uint32 length = r.U32();
        *bySection[s] = static_cast<uint32>(length + kSectionHeaderBytes);
        r.Skip(length);
    }
    return stats;
}

b2RestoreResult b2World::Restore(std::span<const uint8> image) {
    core_detail::Engine::World& world = core_detail::Engine::Of(*this);
    if (world.IsLocked()) {
        world.CheckLocked("b2World::Restore called inside a Step callback (the world is locked)");
        return {b2SnapshotError::e_locked, "the world is locked (inside Step)"};
    }
    if (!world.m_restoreScratch) world.m_restoreScratch.reset(new Image());
    Image& parsed = *world.m_restoreScratch;
    b2RestoreResult result = ParseSnapshot(image, parsed);
    if (!result.ok()) return result;
    ApplySnapshot(parsed, *this);
    world.MarkStructureChanged();
    return result;
}

}  // namespace lockbox
