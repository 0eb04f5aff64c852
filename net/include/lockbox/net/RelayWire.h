#pragma once
/// @file
/// The relay's datagram header (RelayServer.h, RelayedTransport.h; docs/rollback.md "Relayed
/// matches"). A relay forwards opaque payloads between the members of one match, so players
/// behind NATs that cannot reach each other directly still play a peer-to-peer-style session:
/// each member talks to the relay only, and the relay rewrites the destination slot into the
/// source slot.
///
/// Every relay datagram starts with a 9-byte header, all fields little-endian:
///   0  u8  'L'        1  u8  'Y'         magic
///   2  u8  version    (kRelayVersion)
///   3  u8  kind       (RelayKind)
///   4  u32 match id
///   8  u8  slot       join: the slot claimed; welcome: the slot granted;
///                     to-relay data: the destination; from-relay data: the source
/// then: join carries a u64 token (the member's secret for its slot); data carries the payload
/// (1 .. kMaxDatagram - 9 bytes); welcome carries nothing.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "lockbox/Export.h"

namespace lockbox::net {

/// Version byte of the relay header; a datagram with another version is refused.
inline constexpr uint8_t kRelayVersion = 1;
/// Bytes of the relay header (magic 2, version 1, kind 1, match id 4, slot 1).
inline constexpr size_t kRelayHeaderBytes = 9;
/// Largest slot count a relay serves: players and spectators together (a rollback match has at
/// most 8 players). The header's slot byte could name 256 slots; 64 matches the slots an
/// admission token can name (kMaxPlayers), so a token-admitted relay is never bounded by the
/// relay first. Changing it changes no datagram's bytes, only which slots are accepted.
inline constexpr uint32_t kRelayMaxSlots = 64;

/// What a relay datagram is (byte 3 of the header).
enum class RelayKind : uint8_t {
    e_join = 1,      ///< member -> relay: claim a slot with its token
    e_welcome = 2,   ///< relay -> member: the slot is yours (answer to every valid join)
    e_toSlot = 3,    ///< member -> relay: forward the payload to `slot`
    e_fromSlot = 4,  ///< relay -> member: a payload from `slot`
};

/// A parsed relay datagram; `payload` views the input bytes (data kinds only).
struct RelayFrame {
    /// What the datagram is.
    RelayKind kind = RelayKind::e_join;
    /// The match id; the relay drops datagrams whose id is not the one it serves.
    uint32_t matchId = 0;
    /// join: the slot claimed; welcome: the slot granted; e_toSlot: the destination; e_fromSlot:
    /// the source (< kRelayMaxSlots).
    uint8_t slot = 0;
    uint64_t token = 0;                ///< join only
    std::span<const uint8_t> payload;  ///< e_toSlot / e_fromSlot only, never empty
};

/// Parses one datagram; nullopt for a wrong magic or version, an unknown kind, a wrong length
/// (join: exactly 17 bytes; welcome: exactly 9; data: at least 10) or a slot >= kRelayMaxSlots.
LOCKBOX_API std::optional<RelayFrame> ParseRelayFrame(std::span<const uint8_t> bytes) noexcept;

/// Writes the header (and the join token) into `out`, replacing its contents; data kinds
/// append `payload` after it.
LOCKBOX_API void WriteRelayFrame(std::vector<uint8_t>& out, RelayKind kind, uint32_t matchId, uint8_t slot,
                                 uint64_t token = 0, std::span<const uint8_t> payload = {});

}  // namespace lockbox::net
