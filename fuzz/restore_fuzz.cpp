// libFuzzer target for b2World::Restore. The first input byte picks how the rest
// becomes an image, so the fuzzer reaches every layer of the reader:
//   0: the bytes as they are (header checks, truncation, checksum);
//   1: the bytes, resealed (the structural checks see arbitrary payloads);
//   2: edits (offset, value) applied to a real image of a scene with joints, gears and
//      contacts, resealed (near-valid images: the cross-reference checks);
//   3: a real image cut to a length taken from the input.
// Every refused image must leave the world's hash unchanged; every accepted one must step.
// b2SnapshotHash reads every input too (its framing checks face the same hostile bytes), and
// for an accepted image of the current format it must give the restored world's hash, and
// saving that world must give the image back (but for the informative engine version and the
// checksum that covers it): an accepted image is canonical.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/WorldHash.h"

namespace {

using namespace lockbox;

struct Base {
    std::unique_ptr<scenes::LockboxScene> scene = scenes::MakeLockboxScene("pulley_gear");
    scenes::LockboxEngine engine;
    std::vector<uint8> image;
    uint64 hash = 0;
    Base() {
        scene->Build(engine);
        for (int i = 0; i < 20; ++i) engine.Step(60, 8, 3);
        image = engine.world().Save();
        hash = engine.world().Hash();
    }
};

Base& TheBase() {
    static Base base;
    return base;
}

std::vector<uint8> MakeImage(const uint8_t* data, size_t size, const std::vector<uint8>& real) {
    const uint8_t mode = data[0] % 4;
    ++data;
    --size;
    std::vector<uint8> image;
    switch (mode) {
        case 0:
        case 1:
            image.assign(data, data + size);
            if (mode == 1) b2SealSnapshot(image);
            break;
        case 2:
            image = real;
            for (size_t i = 0; i + 3 <= size; i += 3) {
                const size_t at = (size_t{data[i]} | (size_t{data[i + 1]} << 8)) * 7 % image.size();
                image[at] = data[i + 2];
            }
            b2SealSnapshot(image);
            break;
        default: {
            size_t len = 0;
            for (size_t i = 0; i < size && i < 4; ++i) len = (len << 8) | data[i];
            image.assign(real.begin(), real.begin() + static_cast<std::ptrdiff_t>(len % (real.size() + 1)));
            break;
        }
    }
    return image;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    Base& base = TheBase();
    b2World& world = base.engine.world();
    const std::vector<uint8> image = MakeImage(data, size, base.image);
    const b2SnapshotHashResult imageHash = b2SnapshotHash(image);
    const b2RestoreResult result = world.Restore(image);
    if (!result.ok()) {
        if (world.Hash() != base.hash) {
            std::fprintf(stderr, "refused image changed the world: %s\n", result.message.c_str());
            std::abort();
        }
        return 0;
    }
    if (!imageHash.ok()) {
        std::fprintf(stderr, "an image Restore accepts is refused by b2SnapshotHash: %s\n", imageHash.message.c_str());
        std::abort();
    }
    if (image.size() > 6 && image[5] == b2_snapshotFormatVersion && image[6] == 0) {
        if (imageHash.total != world.Hash()) {
            std::fprintf(stderr, "accepted image: b2SnapshotHash differs from the restored world's hash\n");
            std::abort();
        }
        // The engine version (bytes 7..12) is informative and the checksum (25..32) covers
        // it: everything else must come back as it was.
        std::vector<uint8> again = world.Save();
        if (again.size() != image.size()) {
            std::fprintf(stderr, "accepted image: saving the restored world gives another size\n");
            std::abort();
        }
        for (size_t i = 0; i < image.size(); ++i) {
            if ((i >= 7 && i < 13) || (i >= 25 && i < 33)) continue;
            if (again[i] != image[i]) {
                std::fprintf(stderr, "accepted image: byte %zu comes back as %u, not %u\n", i, again[i], image[i]);
                std::abort();
            }
        }
    }
    for (int i = 0; i < 3; ++i) world.Step(Fixed::FromRatio(1, 60), 8, 3);
    // Back to the base state for the next input.
    if (!world.Restore(base.image).ok() || world.Hash() != base.hash) {
        std::fprintf(stderr, "the base image no longer restores\n");
        std::abort();
    }
    return 0;
}
