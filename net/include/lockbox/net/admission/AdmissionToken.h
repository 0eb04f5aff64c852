#pragma once
/// @file
/// Admission tokens (docs/deploy.md "Admission tokens"): the matchmaker's permission for one
/// client to play one slot of one match until a deadline. The matchmaker signs the token with a
/// key it shares with the match servers; the client receives it as opaque bytes and presents it
/// in its first datagrams to the server (AdmissionTransport.h); the server checks the signature,
/// the deadline, that the token was not used before, and that it hosts the match.
///
/// This header is the token's layout only, with no cryptography, so a game client that links
/// lockbox::net can read its own token (its slot, its deadline) without a crypto library. The
/// signature (32 bytes of HMAC-SHA512-256, libsodium's crypto_auth, over bytes 0..31) is made
/// and checked by the minting tool and the server.
///
/// A token is exactly kTokenBytes bytes, little-endian:
///   0  u8  'L'   1  u8  'T'   magic
///   2  u8  version (kTokenVersion)
///   3  u8  slot (< kMaxPlayers)
///   4  u32 match id
///   8  u64 client id (the matchmaker's name for the player; logged, never trusted)
///   16 u64 expiry, seconds since the Unix epoch (UTC); the token is refused from then on
///   24 u64 nonce (random; a token is admitted once, so a copied token is refused)
///   32 32 bytes: the signature over bytes 0..31

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "lockbox/Export.h"

namespace lockbox::net::admission {

/// Layout version of a token; bumped whenever the layout changes.
inline constexpr uint8_t kTokenVersion = 1;
/// Bytes covered by the signature.
inline constexpr size_t kTokenBodyBytes = 32;
/// Bytes of the signature.
inline constexpr size_t kTokenSignatureBytes = 32;
/// Bytes of a whole token.
inline constexpr size_t kTokenBytes = kTokenBodyBytes + kTokenSignatureBytes;

/// What a token says (its signed fields).
struct AdmissionToken {
    uint32_t matchId = 0;    ///< the match the token admits to; a server refuses matches it does not host
    uint8_t slot = 0;        ///< 0 .. kMaxPlayers - 1
    uint64_t clientId = 0;   ///< the matchmaker's player id
    uint64_t expiresAt = 0;  ///< seconds since the Unix epoch; refused from this second on
    uint64_t nonce = 0;      ///< random; a token is admitted once
    /// Field-wise equality, as the tests compare ParseToken's result with what was encoded.
    bool operator==(const AdmissionToken&) const = default;
};

/// Why the bytes are not a token (before any signature check).
enum class TokenFormatError : uint8_t {
    e_ok = 0,
    e_wrongLength,  ///< not exactly kTokenBytes bytes
    e_badMagic,     ///< not 'L' 'T'
    e_badVersion,   ///< another layout version
    e_badSlot,      ///< slot >= kMaxPlayers
};
/// Short name of a format error ("wrong length", ...).
LOCKBOX_API std::string_view TokenFormatErrorName(TokenFormatError error) noexcept;

/// Reads the fields of `bytes` into `out`. Checks the layout only: the signature is not
/// checked here (TokenVerifier in the server does). On an error `out` is left untouched.
LOCKBOX_API TokenFormatError ParseToken(std::span<const uint8_t> bytes, AdmissionToken& out) noexcept;

/// The signed part of a token: bytes 0..31 of the layout above.
LOCKBOX_API std::array<uint8_t, kTokenBodyBytes> EncodeTokenBody(const AdmissionToken& token);

}  // namespace lockbox::net::admission
