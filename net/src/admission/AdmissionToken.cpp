// The admission token layout (AdmissionToken.h).
#include "lockbox/net/admission/AdmissionToken.h"

#include <vector>

#include "lockbox/common/Bytes.h"
#include "lockbox/net/Protocol.h"

namespace lockbox::net::admission {

std::string_view TokenFormatErrorName(TokenFormatError error) noexcept {
    switch (error) {
        case TokenFormatError::e_ok: return "ok";
        case TokenFormatError::e_wrongLength: return "wrong length";
        case TokenFormatError::e_badMagic: return "bad magic";
        case TokenFormatError::e_badVersion: return "bad version";
        case TokenFormatError::e_badSlot: return "bad slot";
    }
    return "unknown";
}

TokenFormatError ParseToken(std::span<const uint8_t> bytes, AdmissionToken& out) noexcept {
    if (bytes.size() != kTokenBytes) return TokenFormatError::e_wrongLength;
    bytes::Reader r(bytes);
    const uint8_t l = r.U8(), t = r.U8(), version = r.U8();
    AdmissionToken token;
    token.slot = r.U8();
    token.matchId = r.U32();
    token.clientId = r.U64();
    token.expiresAt = r.U64();
    token.nonce = r.U64();
    // The length was checked, so every read above fits.
    if (!r.Ok() || l != 'L' || t != 'T') return TokenFormatError::e_badMagic;
    if (version != kTokenVersion) return TokenFormatError::e_badVersion;
    if (token.slot >= kMaxPlayers) return TokenFormatError::e_badSlot;
    out = token;
    return TokenFormatError::e_ok;
}

std::array<uint8_t, kTokenBodyBytes> EncodeTokenBody(const AdmissionToken& token) {
    // The body has a fixed size: write it into a small vector, then copy (Writer appends).
    std::vector<uint8_t> v;
    v.reserve(kTokenBodyBytes);
    bytes::Writer w(v);
    w.U8('L');
    w.U8('T');
    w.U8(kTokenVersion);
    w.U8(token.slot);
    w.U32(token.matchId);
    w.U64(token.clientId);
    w.U64(token.expiresAt);
    w.U64(token.nonce);
    std::array<uint8_t, kTokenBodyBytes> out{};
    for (size_t i = 0; i < out.size() && i < v.size(); ++i) out[i] = v[i];
    return out;
}

}  // namespace lockbox::net::admission
