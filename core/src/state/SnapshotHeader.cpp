// The checks every reader of a snapshot image makes before its sections: the header (through
// Cereal's portable binary archive, little-endian) and the framing of the sections.
// Restore (SnapshotParse.cpp) and the image hash (SnapshotHash.cpp) share them, so an image
// one accepts the other frames the same way.

#include <istream>
#include <string>

#include <cereal/archives/portable_binary.hpp>

#include "ByteStreams.h"
#include "SnapshotCheck.h"
#include "SnapshotImage.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::state_detail {

HeaderFields ReadHeader(std::span<const uint8> bytes) {
    if (bytes.size() < kHeaderBytes) {
        Fail(b2SnapshotError::e_truncated, "image of " + std::to_string(bytes.size()) + " bytes is shorter than the " +
                                               std::to_string(kHeaderBytes) + "-byte header");
    }
    if (bytes[0] != 1) {
        Fail(b2SnapshotError::e_badEndianFlag,
             "first byte is " + std::to_string(bytes[0]) + ", expected 1 (little-endian portable binary)");
    }
    uint32 magic = 0, determinism = 0;
    uint16 format = 0, major = 0, minor = 0, patch = 0;
    HeaderFields fields;
    {
        HeaderSource source(bytes.first(kHeaderBytes));
        std::istream stream(&source);
        cereal::PortableBinaryInputArchive archive(stream);
        archive(magic, format, major, minor, patch, determinism, fields.payload, fields.checksum);
    }
    if (magic != b2_snapshotMagic) Fail(b2SnapshotError::e_badMagic, "magic " + Hex(magic) + " is not 'LBSN'");
    if (format < b2_snapshotOldestReadable || format > b2_snapshotFormatVersion) {
        Fail(b2SnapshotError::e_badFormatVersion, "format version " + std::to_string(format) + ", this build reads " +
                                                      std::to_string(b2_snapshotOldestReadable) + " to " +
                                                      std::to_string(b2_snapshotFormatVersion));
    }
    fields.format = format;
    // The engine version (major.minor.patch) is informative: the format and determinism
    // versions decide whether this build can continue the simulation.
    if (determinism != b2_determinismVersion) {
        Fail(b2SnapshotError::e_badDeterminismVersion,
             "determinism version " + Hex(determinism) + ", this build is " + Hex(b2_determinismVersion));
    }
    const uint64 present = bytes.size() - kHeaderBytes;
    if (fields.payload > present) {
        Fail(b2SnapshotError::e_truncated, "payload of " + std::to_string(fields.payload) + " bytes announced, " +
                                               std::to_string(present) + " present");
    }
    if (fields.payload < present) {
        Fail(b2SnapshotError::e_trailingBytes, std::to_string(present - fields.payload) + " bytes after the payload");
    }
    return fields;
}

SectionSpans FrameSections(std::span<const uint8> bytes, uint16 format) {
    const uint32 count = format >= 2 ? kSectionCount : kSectionCountV1;
    SectionSpans sections;
    bytes::Reader r(bytes, kHeaderBytes);
    for (uint32 s = 0; s < count; ++s) {
        const uint32 tag = r.U32();
        const uint32 length = r.U32();
        if (!r.Ok()) Fail(b2SnapshotError::e_truncated, std::string(kSectionNames[s]) + ": section header missing");
        Check(tag == s + 1, kSectionNames[s], "section tag is wrong", tag);
        if (length > r.Remaining()) {
            Fail(b2SnapshotError::e_truncated, std::string(kSectionNames[s]) + ": section announces " +
                                                   std::to_string(length) + " bytes, " + std::to_string(r.Remaining()) +
                                                   " are left");
        }
        sections[s] = r.Bytes(length);
    }
    if (!r.AtEnd()) {
        Fail(b2SnapshotError::e_trailingBytes, std::to_string(r.Remaining()) + " bytes after the last section");
    }
    return sections;
}

}  // namespace lockbox::state_detail
