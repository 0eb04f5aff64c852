// Signing and checking admission tokens with libsodium's crypto_auth (TokenAuthority.h).
#include "lockbox_admission/TokenAuthority.h"

#include <sodium.h>

#include <stdexcept>
#include <utility>

namespace lockbox::admission {

namespace {

static_assert(crypto_auth_KEYBYTES == kKeyBytes);
static_assert(crypto_auth_BYTES == net::admission::kTokenSignatureBytes);

void InitSodium() {
    // sodium_init is idempotent and thread-safe; it fails only when no random source exists.
    if (sodium_init() < 0) throw std::runtime_error("libsodium could not be initialised");
}

int HexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

std::string ToHex(std::span<const uint8_t> bytes) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string s;
    s.reserve(2 * bytes.size());
    for (uint8_t b : bytes) {
        s += kDigits[b >> 4];
        s += kDigits[b & 15];
    }
    return s;
}

bool FromHex(std::string_view text, std::vector<uint8_t>& out) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\n' || text.back() == '\r'))
        text.remove_suffix(1);
    if (text.size() % 2 != 0) return false;
    std::vector<uint8_t> bytes(text.size() / 2);
    for (size_t i = 0; i < bytes.size(); ++i) {
        const int hi = HexDigit(text[2 * i]), lo = HexDigit(text[2 * i + 1]);
        if (hi < 0 || lo < 0) return false;
        bytes[i] = static_cast<uint8_t>(hi * 16 + lo);
    }
    out = std::move(bytes);
    return true;
}

std::optional<TokenKey> ParseKeyHex(std::string_view text) {
    std::vector<uint8_t> bytes;
    if (!FromHex(text, bytes) || bytes.size() != kKeyBytes) return std::nullopt;
    TokenKey key{};
    for (size_t i = 0; i < kKeyBytes; ++i) key[i] = bytes[i];
    return key;
}

std::string KeyHex(const TokenKey& key) { return ToHex(key); }

TokenKey NewKey() {
    InitSodium();
    TokenKey key{};
    crypto_auth_keygen(key.data());
    return key;
}

uint64_t NewNonce() {
    InitSodium();
    uint64_t n = 0;
    randombytes_buf(&n, sizeof n);
    return n;
}

std::string_view RefusalName(Refusal refusal) noexcept {
    switch (refusal) {
        case Refusal::e_none: return "none";
        case Refusal::e_malformed: return "malformed";
        case Refusal::e_badVersion: return "bad_version";
        case Refusal::e_forged: return "forged";
        case Refusal::e_expired: return "expired";
        case Refusal::e_tooLong: return "too_long";
        case Refusal::e_reused: return "reused";
        case Refusal::e_wrongMatch: return "wrong_match";
        case Refusal::e_replayCacheFull: return "replay_cache_full";
        case Refusal::e_count: break;
    }
    return "unknown";
}

TokenSigner::TokenSigner(const TokenKey& key) : m_key(key) { InitSodium(); }

TokenBytes TokenSigner::Sign(const AdmissionToken& token) const {
    const auto body = net::admission::EncodeTokenBody(token);
    TokenBytes out{};
    for (size_t i = 0; i < body.size(); ++i) out[i] = body[i];
    crypto_auth(out.data() + body.size(), body.data(), body.size(), m_key.data());
    return out;
}

TokenVerifier::TokenVerifier(const TokenKey& key, size_t replayCapacity, uint64_t maxLifetimeSeconds)
    : m_key(key), m_capacity(replayCapacity < 1 ? 1 : replayCapacity), m_maxLifetime(maxLifetimeSeconds) {
    InitSodium();
}

Refusal TokenVerifier::Check(std::span<const uint8_t> bytes, uint64_t nowSeconds, AdmissionToken& out) const {
    using net::admission::TokenFormatError;
    AdmissionToken token;
    switch (net::admission::ParseToken(bytes, token)) {
        case TokenFormatError::e_ok: break;
        case TokenFormatError::e_badVersion: return Refusal::e_badVersion;
        default: return Refusal::e_malformed;
    }
    // The signature first: nothing an unsigned token says is worth reading further.
    const size_t body = net::admission::kTokenBodyBytes;
    if (crypto_auth_verify(bytes.data() + body, bytes.data(), body, m_key.data()) != 0) return Refusal::e_forged;
    if (nowSeconds >= token.expiresAt) return Refusal::e_expired;
    if (token.expiresAt - nowSeconds > m_maxLifetime) return Refusal::e_tooLong;
    out = token;
    return Refusal::e_none;
}

void TokenVerifier::ForgetExpired(uint64_t nowSeconds) {
    for (auto it = m_used.begin(); it != m_used.end();) {
        if (it->second.expiresAt <= nowSeconds)
            it = m_used.erase(it);
        else
            ++it;
    }
}

Refusal TokenVerifier::Consume(const AdmissionToken& token, uint64_t presenter, uint64_t nowSeconds) {
    const auto found = m_used.find(token.nonce);
    if (found != m_used.end() && found->second.expiresAt > nowSeconds)
        return found->second.presenter == presenter ? Refusal::e_none : Refusal::e_reused;
    if (found != m_used.end()) m_used.erase(found);
    if (m_used.size() >= m_capacity) ForgetExpired(nowSeconds);
    if (m_used.size() >= m_capacity) return Refusal::e_replayCacheFull;
    m_used.emplace(token.nonce, Use{token.expiresAt, presenter});
    return Refusal::e_none;
}

}  // namespace lockbox::admission
