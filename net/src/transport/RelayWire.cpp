// The relay header codec (RelayWire.h).
#include "lockbox/net/RelayWire.h"

#include "lockbox/common/Bytes.h"

namespace lockbox::net {

std::optional<RelayFrame> ParseRelayFrame(std::span<const uint8_t> bytes) noexcept {
    bytes::Reader r(bytes);
    const uint8_t l = r.U8(), y = r.U8(), version = r.U8(), kind = r.U8();
    RelayFrame f;
    f.matchId = r.U32();
    f.slot = r.U8();
    if (!r.Ok() || l != 'L' || y != 'Y' || version != kRelayVersion || f.slot >= kRelayMaxSlots) return std::nullopt;
    switch (kind) {
        case static_cast<uint8_t>(RelayKind::e_join):
            f.kind = RelayKind::e_join;
            f.token = r.U64();
            if (!r.Ok() || !r.AtEnd()) return std::nullopt;
            return f;
        case static_cast<uint8_t>(RelayKind::e_welcome):
            if (!r.AtEnd()) return std::nullopt;
            f.kind = RelayKind::e_welcome;
            return f;
        case static_cast<uint8_t>(RelayKind::e_toSlot):
        case static_cast<uint8_t>(RelayKind::e_fromSlot):
            if (r.AtEnd()) return std::nullopt;  // data is never empty
            f.kind = static_cast<RelayKind>(kind);
            f.payload = r.Bytes(r.Remaining());
            return f;
        default: return std::nullopt;
    }
}

void WriteRelayFrame(std::vector<uint8_t>& out, RelayKind kind, uint32_t matchId, uint8_t slot, uint64_t token,
                     std::span<const uint8_t> payload) {
    out.clear();
    bytes::Writer w(out);
    w.U8('L');
    w.U8('Y');
    w.U8(kRelayVersion);
    w.U8(static_cast<uint8_t>(kind));
    w.U32(matchId);
    w.U8(slot);
    if (kind == RelayKind::e_join) w.U64(token);
    if (kind == RelayKind::e_toSlot || kind == RelayKind::e_fromSlot) w.Bytes(payload);
}

}  // namespace lockbox::net
