#pragma once
// Snapshot bytes across builds: the snapshot bytes of one scene must be the same in every
// build. The cross driver runs one light scene for a few steps, saves the
// world with b2World::Save, and hashes the image with XXH3-64; every compiler, flag set and
// architecture must give the same bytes, hence the same hash. The golden value lives in
// tests/cross/snapshot_golden.txt as
//   snapshot <scene> step<N> format=<b2_snapshotFormatVersion> bytes=<size> xxh3=0x<16 hex>
//
// The snapshot API is new: this header compiles to nothing unless LOCKBOX_CROSS_SNAPSHOT is
// defined (tests/cross/run.sh defines it when core/src defines b2World::Save) and the header
// declaring it exists.
#if defined(LOCKBOX_CROSS_SNAPSHOT) && __has_include("lockbox/state/Snapshot.h")
#define LOCKBOX_CROSS_HAS_SNAPSHOT 1

#include <xxhash.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "lockbox/dynamics/World.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/Snapshot.h"

namespace lockbox::snapshot_hash {

/// The scenes whose snapshots are compared: light (they run quickly under qemu) and together
/// holding every kind of state a snapshot carries: ragdolls (polygons, contacts, revolute
/// joints) and car (a chain shape, circles, wheel joints, whose reaction directions fill the
/// joint-reaction section that no hash covers).
inline constexpr std::string_view kScenes[] = {"ragdolls", "car"};
/// Steps before the snapshot: enough for contacts and warm-start impulses to exist.
inline constexpr int kSteps = 60;

/// The golden-file line for the snapshot of `scene` after `steps` steps, or an empty string
/// when the scene does not exist.
inline std::string SnapshotLine(std::string_view scene, int steps) {
    auto s = scenes::MakeLockboxScene(scene);
    if (!s) return {};
    scenes::LockboxEngine e;
    scenes::RunSettings settings;
    settings.steps = steps;
    settings.trackMetrics = false;
    const scenes::Resolved r = scenes::Resolve(s->Info(), settings);
    scenes::ConfigureWorld(e, s->Info(), settings);
    s->Prepare(r);
    s->Build(e);
    for (int i = 0; i < steps; ++i) {
        s->BeforeStep(e, i);
        e.Step(r.hz, r.velocityIterations, r.positionIterations);
    }
    const std::vector<uint8> image = e.world().Save();
    const uint64_t h = XXH3_64bits(image.data(), image.size());
    char buf[96];
    std::snprintf(buf, sizeof buf, " step%d format=%u bytes=%zu xxh3=0x%016llx", steps,
                  static_cast<unsigned>(b2_snapshotFormatVersion), image.size(), static_cast<unsigned long long>(h));
    return "snapshot " + std::string(scene) + buf;
}

/// The first line of `path` that starts with "snapshot <scene> ", or "" when there is none.
inline std::string ReadSnapshotGolden(const std::string& path, std::string_view scene) {
    std::ifstream in(path);
    const std::string prefix = "snapshot " + std::string(scene) + " ";
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.compare(0, prefix.size(), prefix) == 0) return line;
    }
    return {};
}

}  // namespace lockbox::snapshot_hash

#endif
