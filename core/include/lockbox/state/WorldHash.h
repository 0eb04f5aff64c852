#pragma once
/// @file
/// World state hash (docs/determinism.md, "State hash"): an XXH3-64 over a canonical
/// walk of every field that influences future steps, written as little-endian fixed-width
/// integers (never raw memory, padding or free slots). Equal hashes on two machines mean, with
/// overwhelming probability, bit-identical simulations from here on.
///
/// The walk is split into categories (settings, bodies, fixtures, contacts, joints,
/// broad-phase) with their own sub-hashes, and each body has a sub-hash (its fields plus its
/// fixtures), so a mismatch can be narrowed to a category and then to a body.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/state/Snapshot.h"

namespace lockbox {

class b2World;
class b2Body;

/// Version of the hash definition; folded into every hash. Bump it whenever the field list,
/// order or widths in docs/determinism.md change.
/// History: 1 first definition; 2 one walk shared with the snapshot (exact joint state through
/// VisitState, joint edges with their side, the world's saturation count, compact widths); 3 each
/// body's velocity and position remainders below Q16.16.
inline constexpr uint32 b2_hashVersion = 3;

/// Identifies everything that decides the bits of a step for peers and files: the hash
/// definition (high 16 bits) and the step's arithmetic (low 16: the number formats, Q16.16 and
/// Q32.32 rounded to nearest with ties away from zero and symmetric saturation, and the
/// formulas the solvers evaluate with them). Snapshots and replays carry it; bump the low half
/// whenever a step of the same state gives other bits.
/// History of the low half: 1 first; 2 the contact solver's velocity pass evaluates point speeds
/// exactly in Q32.32 from per-step lever arms and applies angular impulses through per-step
/// angular responses (fewer roundings, about 1.2x faster steps on stacks), and the revolute,
/// prismatic and weld joints' point iterations multiply by their point block's inverse,
/// computed once per step, instead of solving the block each iteration; 3 velocities are Q32.32
/// through the whole step and positions integrate in Q32.32 (the body keeps both parts below
/// Q16.16), so forces and impulses below 1/65536 m/s per step accumulate instead of rounding
/// away and a slow body moves at its velocity's rate, and a slow body pressed into a
/// static or kinematic contact gets 2.2.1's immediate time of impact; 4 the contacts of an
/// island of 1,024 or more, and apart its joints when they are 1,024 or more, are solved colour
/// by colour (a colour's constraints share no dynamic body), the one order that any number of
/// workers reproduces while sharing the island; 5 a time-of-impact sub-step's position solve
/// ends only once the overlap is less than 1.5 linearSlop, so that the tie its first correction
/// lands on takes one more, as in float Box2D; 6 the joints' 2x2 point solves normalise their
/// matrix to 31 significant bits (from 36), so that each solve is one 128-by-64-bit division.
inline constexpr uint32 b2_determinismVersion = (b2_hashVersion << 16) | 6u;

/// Hash categories, in the order they are folded into the world hash.
enum class b2HashCategory : uint32 {
    e_settings = 0,    ///< world switches, gravity, bounds, step carry-over
    e_bodies = 1,      ///< body pool and every body in body-list order
    e_fixtures = 2,    ///< fixture pool and every fixture (body-list order, then fixture list)
    e_contacts = 3,    ///< contact pool and every contact in contact-list order
    e_joints = 4,      ///< every joint in joint-list order
    e_broadphase = 5,  ///< dynamic tree nodes, root, free list, counts, move buffer
    e_count = 6
};

/// Name of a category ("settings", "bodies", ...); "none" for e_count.
LOCKBOX_API std::string_view b2HashCategoryName(b2HashCategory category) noexcept;

/// Sub-hash of one body.
struct b2BodyHashEntry {
    int32 bodyId = -1;  ///< b2Body::GetId()
    uint64 hash = 0;    ///< XXH3-64 of the body's fields then its fixtures' fields
};

/// The world hash with its breakdown.
struct b2WorldHashReport {
    uint64 total = 0;                                                      ///< equals b2WorldHash(world)
    uint64 categories[static_cast<uint32>(b2HashCategory::e_count)] = {};  ///< by b2HashCategory
    std::vector<b2BodyHashEntry> bodies;                                   ///< one per body, in body-list order
};

/// Where two reports first differ.
struct b2HashMismatch {
    b2HashCategory category = b2HashCategory::e_count;  ///< e_count when the reports agree
    int32 bodyId = -1;  ///< first body (list order) whose sub-hash differs; -1 if none does
};

/// XXH3-64 of the world's state (definition version b2_hashVersion). Listeners, the contact
/// filter, the debug draw and the profile are not state and do not enter it. Call it outside
/// Step. Cost: one pass over the world, no allocation.
LOCKBOX_API uint64 b2WorldHash(const b2World& world);

/// The world hash with per-category and per-body sub-hashes (allocates the body vector).
LOCKBOX_API b2WorldHashReport b2WorldHashDetailed(const b2World& world);

/// Sub-hash of one body: its own fields then its fixtures' fields (the b2WorldHashReport
/// body entry).
LOCKBOX_API uint64 b2BodyStateHash(const b2Body& body);

/// The format of a body field's raw value (b2BodyField).
enum class b2FieldFormat : uint8 {
    e_integer = 0,  ///< an integer (id, flags, counts, user data)
    e_fixed = 1,    ///< Q16.16 (Fixed::Raw)
    e_wide = 2,     ///< Q32.32 (Wide::Raw)
};

/// One field of a body's record in the canonical state walk: what the hash and the snapshot
/// read of the body itself (its fixtures are not listed; b2BodyStateHash covers them).
struct b2BodyField {
    const char* name = "";  ///< "position.x", "sweep.a0", "invMass", ...
    /// How to read `raw`: an integer, Q16.16 or Q32.32.
    b2FieldFormat format = b2FieldFormat::e_integer;
    int64_t raw = 0;  ///< the value as the walk writes it
};

/// The fields of a body's record in walk order (about 40), values read by the same walk as
/// the hash: two bodies whose lists differ nowhere have equal records. For telling where two
/// runs split (the replay diff); allocates.
LOCKBOX_API std::vector<b2BodyField> b2BodyStateFields(const b2Body& body);

/// The first category whose sub-hash differs and the first differing body (by position in
/// list order; a differing body count reports the first body past the shorter list).
LOCKBOX_API b2HashMismatch b2CompareHashReports(const b2WorldHashReport& a, const b2WorldHashReport& b) noexcept;

/// The world hash read back from a snapshot image (b2SnapshotHash).
struct b2SnapshotHashResult {
    /// e_ok, or why the image's framing could not be read.
    b2SnapshotError error = b2SnapshotError::e_ok;
    std::string message;  ///< what is wrong with the image's framing; empty when ok
    uint64 total = 0;     ///< b2WorldHash of the world the image was saved from
    uint64 categories[static_cast<uint32>(b2HashCategory::e_count)] = {};  ///< by b2HashCategory
    /// True when the image was read and total and categories hold its hash.
    bool ok() const noexcept { return error == b2SnapshotError::e_ok; }
};

/// The state hash of the world an image was saved from, computed from the image alone: equal
/// to b2WorldHash (and the categories of b2WorldHashDetailed) of that world at the Save,
/// because each image section holds exactly the walk its hash category streams. It reads the
/// image once, in order, so it costs a fraction of b2WorldHash's walk over the world's objects
/// (docs/determinism.md, "Measured sizes and speeds"): a session that saves every frame gets
/// the frame's hash almost free. It checks the header and the framing of the sections, not the
/// checksum or the records (Restore does both): an edited image gives the hash of what it says.
LOCKBOX_API b2SnapshotHashResult b2SnapshotHash(std::span<const uint8> image);

}  // namespace lockbox
