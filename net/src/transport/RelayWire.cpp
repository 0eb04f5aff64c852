// The relay header codec (RelayWire.h).
#include "lockbox/net/RelayWire.h"

namespace lockbox::net {

namespace {

uint64_t ReadLe(std::span<const uint8_t> b, size_t at, int bytes) noexcept {
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<uint64_t>(b[at + static_cast<size_t>(i)]) << (8 * i);
    return v;
}

void WriteLe(std::vector<uint8_t>& out, uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

}  // namespace

std::optional<RelayFrame> ParseRelayFrame(std::span<const uint8_t> bytes) noexcept {
    if (bytes.size() < kRelayHeaderBytes || bytes[0] != 'L' || bytes[1] != 'Y' || bytes[2] != kRelayVersion)
        return std::nullopt;
    RelayFrame f;
    f.matchId = static_cast<uint32_t>(ReadLe(bytes, 4, 4));
    f.slot = bytes[8];
    if (f.slot >= kRelayMaxSlots) return std::nullopt;
    switch (bytes[3]) {
        case static_cast<uint8_t>(RelayKind::e_join):
            if (bytes.size() != kRelayHeaderBytes + 8) return std::nullopt;
            f.kind = RelayKind::e_join;
            f.token = ReadLe(bytes, kRelayHeaderBytes, 8);
            return f;
        case static_cast<uint8_t>(RelayKind::e_welcome):
            if (bytes.size() != kRelayHeaderBytes) return std::nullopt;
            f.kind = RelayKind::e_welcome;
            return f;
        case static_cast<uint8_t>(RelayKind::e_toSlot):
        case static_cast<uint8_t>(RelayKind::e_fromSlot):
            if (bytes.size() == kRelayHeaderBytes) return std::nullopt;  // data is never empty
            f.kind = static_cast<RelayKind>(bytes[3]);
            f.payload = bytes.subspan(kRelayHeaderBytes);
            return f;
        default: return std::nullopt;
    }
}

void WriteRelayFrame(std::vector<uint8_t>& out, RelayKind kind, uint32_t matchId, uint8_t slot, uint64_t token,
                     std::span<const uint8_t> payload) {
    out.clear();
    out.push_back('L');
    out.push_back('Y');
    out.push_back(kRelayVersion);
    out.push_back(static_cast<uint8_t>(kind));
    WriteLe(out, matchId, 4);
    out.push_back(slot);
    if (kind == RelayKind::e_join) WriteLe(out, token, 8);
    if (kind == RelayKind::e_toSlot || kind == RelayKind::e_fromSlot)
        out.insert(out.end(), payload.begin(), payload.end());
}

}  // namespace lockbox::net
