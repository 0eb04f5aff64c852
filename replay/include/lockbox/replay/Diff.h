#pragma once
/// @file
/// Finding where two runs disagree (`lockbox_replay diff`): play two replays in
/// lockstep, stop at the first frame whose states hash differently, then narrow it to the
/// first differing hash category, body and field, with both values.

#include <string>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Player.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::replay {

/// One field that differs between two bodies.
struct FieldDifference {
    std::string field;  ///< e.g. "linearVelocity.x"
    /// The two values, as "decimal (raw 0x...)": a from the first body, b from the second.
    ///@{
    std::string a, b;
    ///@}
};

/// Where two worlds or two runs first differ.
struct LOCKBOX_API DiffResult {
    bool same = true;            ///< no difference found
    int32 frame = -1;            ///< first frame after which the states differ (-1: the seed)
    int32 firstInputFrame = -1;  ///< first frame whose recorded inputs differ (-1: none)
    /// The two world hashes at the difference: A from the first world or run, B from the second.
    ///@{
    uint64 hashA = 0, hashB = 0;
    ///@}
    b2HashMismatch where;                 ///< first differing category and body
    std::vector<FieldDifference> fields;  ///< differing fields of where.bodyId (all of them)
    std::string note;                     ///< anything else (different lengths, settings)
    Error error;                          ///< a replay could not be played
    /// A multi-line account for people.
    std::string Describe() const;
};

/// Compares two worlds now: hash, category, body, fields.
LOCKBOX_API DiffResult DiffWorlds(const b2World& a, const b2World& b);

/// Every differing field of two bodies (same id in two worlds), in a fixed order.
LOCKBOX_API std::vector<FieldDifference> CompareBodies(const b2Body& a, const b2Body& b);

/// Plays two replays in lockstep from their seeds (each player on its own world) and reports
/// the first frame whose states differ. Both players are left at that frame.
LOCKBOX_API DiffResult DiffReplays(Player& a, Player& b, const ReplayFile& fileA, const ReplayFile& fileB);

/// "1.500000 (raw 0x00018000)": a Q16.16 value for people (exact raw, decimal truncated to
/// 6 places).
LOCKBOX_API std::string FormatFixed(Fixed v);
/// The same for a Q32.32 value.
LOCKBOX_API std::string FormatWide(Wide v);

}  // namespace lockbox::replay
