#pragma once
// The snapshot image's layout in one place: what b2World::Save writes and Restore reads.
// docs/determinism.md ("Snapshot format") is its reference, with every section's fields; the
// public constants (b2_snapshotMagic, b2_snapshotFormatVersion, b2_snapshotOldestReadable)
// are in lockbox/state/Snapshot.h. Any change to what is described here is a new
// b2_snapshotFormatVersion.
//
// An image is a header of kHeaderBytes, then the sections:
//
//   offset  field
//   0       u8      1, Cereal portable binary's flag for little-endian data
//   1       u32     magic b2_snapshotMagic, the bytes "LBSN"
//   5       u16     format version: b2_snapshotFormatVersion (Restore reads
//                   b2_snapshotOldestReadable on)
//   7       u16 x3  engine version major, minor, patch (informative only)
//   13      u32     determinism version, b2_determinismVersion
//   17      u64     payload bytes: everything after the header
//   25      u64     checksum: XXH3-64 of the payload, seeded with XXH3-64 of bytes 0..24
//   33      the sections, in SectionTag order
//
// Each section is a u32 tag, a u32 byte length, then its contents. Sections 1 to 6 hold the
// state walk of the hash category of the same name (StateWalk.h, which also owns the record
// sizes such as kBodyRecordBytes), section 7 each joint's VisitReactionState fields. Every
// field is little-endian and fixed-width: the save writes them through FieldWriter
// (ByteStreams.h), the parser reads them through lockbox/common/Bytes.h (ImageReader,
// SnapshotCheck.h).

#include <cstddef>

#include "lockbox/common/Settings.h"
#include "lockbox/state/Snapshot.h"

namespace lockbox::state_detail {

/// Header field offsets (the table above) and the header's size.
inline constexpr size_t kEndianFlagOffset = 0;
inline constexpr size_t kMagicOffset = 1;
inline constexpr size_t kFormatVersionOffset = 5;
inline constexpr size_t kEngineVersionOffset = 7;
inline constexpr size_t kDeterminismVersionOffset = 13;
inline constexpr size_t kPayloadSizeOffset = 17;
inline constexpr size_t kChecksumOffset = 25;
inline constexpr size_t kHeaderBytes = 33;
static_assert(kMagicOffset == kEndianFlagOffset + 1 && kFormatVersionOffset == kMagicOffset + 4 &&
                  kEngineVersionOffset == kFormatVersionOffset + 2 &&
                  kDeterminismVersionOffset == kEngineVersionOffset + 3 * 2 &&
                  kPayloadSizeOffset == kDeterminismVersionOffset + 4 && kChecksumOffset == kPayloadSizeOffset + 8 &&
                  kHeaderBytes == kChecksumOffset + 8,
              "the header fields follow each other without gaps");

/// Section tags, in image order.
enum SectionTag : uint32 {
    e_sectionSettings = 1,
    e_sectionBodies = 2,
    e_sectionFixtures = 3,
    e_sectionContacts = 4,
    e_sectionJoints = 5,
    e_sectionBroadPhase = 6,
    e_sectionJointReactions = 7,  ///< format 2 on: not a hash category (Snapshot.h)
};
/// Sections of a current image; the first kHashedSections are the hash categories' walks.
inline constexpr uint32 kSectionCount = 7;
inline constexpr uint32 kHashedSections = 6;
/// Sections of an image of format version 1 (no joint-reaction section).
inline constexpr uint32 kSectionCountV1 = 6;
/// A section's tag and byte length, before its contents.
inline constexpr size_t kSectionHeaderBytes = 8;

/// Section names for messages, by tag - 1.
inline constexpr const char* kSectionNames[kSectionCount] = {"settings", "bodies",     "fixtures",      "contacts",
                                                             "joints",   "broadphase", "jointReactions"};

}  // namespace lockbox::state_detail
