// Shared session helpers (SessionCommon.h).

#include "session/SessionCommon.h"

#include <vector>

#include "lockbox/common/Bytes.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/state/WorldGame.h"

namespace lockbox::net {

void PackStateBlob(std::span<const uint8_t> image, std::span<const uint8_t> user, std::vector<uint8_t>& out) {
    out.clear();
    out.reserve(8 + image.size() + user.size());
    bytes::Writer w(out);
    w.Blob(image);
    w.Blob(user);
}

bool LoadStateBlob(std::span<const uint8_t> blob, b2World& world, WorldGame& game) {
    bytes::Reader r(blob);
    const std::span<const uint8_t> image = r.Blob();
    const std::span<const uint8_t> user = r.Blob();
    if (!r.Ok() || !r.AtEnd()) return false;
    if (!world.Restore(image).ok()) return false;
    game.LoadUserState(user);
    return true;
}

}  // namespace lockbox::net
