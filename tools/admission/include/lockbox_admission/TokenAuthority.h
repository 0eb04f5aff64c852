#pragma once
// Signing and checking admission tokens (lockbox/net/admission/AdmissionToken.h) with a key the
// matchmaker shares with its match servers.
//
// Why a MAC (libsodium crypto_auth: HMAC-SHA512-256) and not signatures or AEAD:
// - The matchmaker and the match servers belong to the same studio and already share secrets;
//   a token needs integrity and authenticity, not secrecy (a match id, a slot and a deadline
//   are nothing a client must not read; the client even reads its slot).
// - A server checks every token that reaches it, including a flood of forged ones: an HMAC
//   check costs about a microsecond, an Ed25519 verification (crypto_sign) about fifty. The
//   price of a MAC is that every server holds the minting key; a studio whose servers run on
//   machines it trusts less than its backend would switch to crypto_sign (a new token version).
// - AEAD (as netcode.io's connect tokens) hides fields from the client, which only matters when
//   the token carries per-connection secrets; lockbox's sessions have none.
//
// This library links libsodium and is used by the server and the minting tool only, so a game
// client that links lockbox::net needs no crypto library.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/net/admission/AdmissionToken.h"

namespace lockbox::admission {

using net::admission::AdmissionToken;
using net::admission::kTokenBytes;

/// Bytes of a shared key (crypto_auth_KEYBYTES).
inline constexpr size_t kKeyBytes = 32;
using TokenKey = std::array<uint8_t, kKeyBytes>;
using TokenBytes = std::array<uint8_t, kTokenBytes>;

/// Lower-case hexadecimal digits of `bytes`.
std::string ToHex(std::span<const uint8_t> bytes);
/// Reads hexadecimal digits (either case; surrounding blanks and a final newline are ignored)
/// into `out`; false, `out` untouched, for an odd count or a non-digit.
bool FromHex(std::string_view text, std::vector<uint8_t>& out);

/// Reads a key written as 64 hexadecimal digits (surrounding blanks and a final newline are
/// ignored); nullopt otherwise.
std::optional<TokenKey> ParseKeyHex(std::string_view text);
/// The key as 64 lower-case hexadecimal digits.
std::string KeyHex(const TokenKey& key);
/// A new random key (libsodium's generator).
TokenKey NewKey();
/// A random nonce for a token.
uint64_t NewNonce();

/// Why a token was refused; every refusal is counted by reason.
enum class Refusal : uint8_t {
    e_none = 0,
    e_malformed,        ///< not a token: wrong length, magic or slot
    e_badVersion,       ///< a token layout this server does not read
    e_forged,           ///< the signature does not match (unsigned, altered, another key)
    e_expired,          ///< its deadline has passed
    e_tooLong,          ///< its deadline is further away than the longest lifetime allowed
    e_reused,           ///< its nonce was already admitted (from another address)
    e_wrongMatch,       ///< it names a match this server does not host (or a slot outside it)
    e_replayCacheFull,  ///< too many live tokens to remember: refused rather than forgotten
    e_count
};
/// Short name of a refusal, used in logs and metric labels ("forged", "wrong_match", ...).
std::string_view RefusalName(Refusal refusal) noexcept;

/// Mints tokens (the matchmaker's side).
class TokenSigner {
public:
    explicit TokenSigner(const TokenKey& key);
    /// The token's bytes: its fields and their signature.
    TokenBytes Sign(const AdmissionToken& token) const;

private:
    TokenKey m_key;
};

/// Checks tokens (the server's side) and remembers the admitted ones until they expire.
class TokenVerifier {
public:
    /// `replayCapacity` (>= 1) bounds the nonces remembered at once; `maxLifetimeSeconds` bounds
    /// how far in the future a deadline may be, so no nonce is remembered longer than that.
    TokenVerifier(const TokenKey& key, size_t replayCapacity = 65536, uint64_t maxLifetimeSeconds = 3600);

    /// Checks the layout, the signature and the deadline at `nowSeconds` (Unix time). On success
    /// returns e_none and fills `out`; nothing is remembered yet (Consume does).
    Refusal Check(std::span<const uint8_t> bytes, uint64_t nowSeconds, AdmissionToken& out) const;

    /// Marks a checked token's nonce as used by `presenter` (the caller's name for the source
    /// address). The same presenter may present it again (its first datagrams are resent);
    /// another presenter gets e_reused. e_replayCacheFull when `replayCapacity` live nonces are
    /// remembered already.
    Refusal Consume(const AdmissionToken& token, uint64_t presenter, uint64_t nowSeconds);

    /// True when `token`'s nonce was consumed and is still remembered (by any presenter).
    bool Used(const AdmissionToken& token) const noexcept { return m_used.count(token.nonce) != 0; }

    /// Nonces remembered now.
    size_t Remembered() const noexcept { return m_used.size(); }

private:
    struct Use {
        uint64_t expiresAt = 0;
        uint64_t presenter = 0;
    };
    void ForgetExpired(uint64_t nowSeconds);

    TokenKey m_key;
    size_t m_capacity;
    uint64_t m_maxLifetime;
    std::map<uint64_t, Use> m_used;  // nonce -> its use
};

}  // namespace lockbox::admission
