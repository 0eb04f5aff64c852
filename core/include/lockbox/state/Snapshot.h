#pragma once
/// @file
/// World snapshots (docs/determinism.md "Snapshot format"): b2World::Save writes
/// every field that influences future steps as a portable byte image (Cereal portable binary,
/// little-endian, fixed widths), and b2World::Restore reads one back, either in place
/// (rollback: surviving bodies, fixtures, contacts and joints keep their address and id) or
/// into a fresh world (late join). Stepping after a restore gives exactly the bits the saved
/// world gave. Listeners, the contact filter, the debug draw and the profile are not state:
/// a restore leaves them as they are.
///
/// Restore validates the whole image before it touches the world: a truncated, corrupted,
/// foreign or wrong-version image returns an error naming the problem and leaves the world
/// (and its hash) unchanged.

#include <span>
#include <string>

#include "lockbox/Export.h"
#include "lockbox/Version.h"
#include "lockbox/common/Settings.h"

namespace lockbox {

/// The "engine version" field of every snapshot header (and of every replay header): 0.7.0 in
/// every image, whatever the library's version (lockbox/Version.h). The field is informative
/// (Restore ignores it) and part of the bytes that the checksum and the image hash cover, so
/// writing the library's version there would change every snapshot and replay at each release;
/// the format and determinism versions below are what a reader checks.
///@{
inline constexpr uint16 b2_snapshotEngineMajor = 0;
inline constexpr uint16 b2_snapshotEngineMinor = 7;
inline constexpr uint16 b2_snapshotEnginePatch = 0;
///@}

/// Version of the snapshot layout; bump on any change to docs/determinism.md's format table.
/// History: 1 the six state sections; 2 adds a seventh, the joints' reaction directions (so a
/// restored joint answers GetReactionForce as the saved one did); 3 adds each body's velocity
/// and position remainders below Q16.16 to the body record.
inline constexpr uint16 b2_snapshotFormatVersion = 3;
/// The oldest format Restore still reads. Format 3 changed the body record, and images of the
/// older formats were written under an older determinism version, which Restore refuses anyway.
inline constexpr uint16 b2_snapshotOldestReadable = 3;

/// The four magic bytes that open every snapshot payload header ("LBSN").
inline constexpr uint32 b2_snapshotMagic = 0x4E53424Cu;  // 'L' 'B' 'S' 'N', low byte first

/// Why a restore was refused.
enum class b2SnapshotError : uint32 {
    e_ok = 0,                 ///< restored
    e_truncated,              ///< the image ends before a field or a section it announces
    e_badEndianFlag,          ///< the first byte is not Cereal's little-endian flag (1)
    e_badMagic,               ///< not a lockbox snapshot
    e_badFormatVersion,       ///< written by another snapshot format version
    e_badDeterminismVersion,  ///< written under another hash/number-format definition
    e_badChecksum,            ///< the payload does not match its XXH3-64 checksum
    e_corrupt,                ///< well formed but inconsistent (the message names the field)
    e_trailingBytes,          ///< bytes after the last section
    e_locked,                 ///< Restore called inside Step
    e_foreignFrame,           ///< RestoreFrame given an empty frame or another world's
};

/// Recomputes the checksum of an image after its bytes were edited (tools, tests, fuzzing);
/// does nothing to a span shorter than the header. The checksum covers the header fields
/// before it and the whole payload, so any flipped bit of a sealed image is detected.
LOCKBOX_API void b2SealSnapshot(std::span<uint8> image) noexcept;

/// Short name of an error ("truncated", "bad magic", ...).
LOCKBOX_API const char* b2SnapshotErrorName(b2SnapshotError error) noexcept;

/// Result of b2World::Restore.
struct b2RestoreResult {
    /// e_ok, or why the restore was refused (the world is then untouched).
    b2SnapshotError error = b2SnapshotError::e_ok;
    std::string message;  ///< what is wrong, naming the section, field and value; empty when ok
    /// True when the world now holds the image's state.
    bool ok() const noexcept { return error == b2SnapshotError::e_ok; }
    /// True on success, as ok().
    explicit operator bool() const noexcept { return ok(); }
};

/// Byte counts of one snapshot by section (b2World::SaveStats), for size reports.
struct b2SnapshotStats {
    uint32 headerBytes = 0;         ///< fixed header including the endianness flag
    uint32 settingsBytes = 0;       ///< world switches and carry-over
    uint32 bodyBytes = 0;           ///< body pool and bodies
    uint32 fixtureBytes = 0;        ///< fixture pool, fixtures and shapes
    uint32 contactBytes = 0;        ///< contact pool and contacts with manifolds
    uint32 jointBytes = 0;          ///< joints
    uint32 broadPhaseBytes = 0;     ///< dynamic tree and move buffer
    uint32 jointReactionBytes = 0;  ///< joints' reaction directions (not hashed)
    uint32 totalBytes = 0;          ///< the whole image
};

}  // namespace lockbox
