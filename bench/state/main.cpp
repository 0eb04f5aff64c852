// lockbox_state_bench: what the world state costs. For scenes from ~200 to ~5000
// bodies it measures, in the same run, the median time of a step, of a state hash (the walk
// over the world, b2WorldHash, and the same value read from the image just saved,
// b2SnapshotHash), of a save and of an in-place restore, and the snapshot's bytes per
// section; and the hash floor (the image hashed again after a step: the packed state bytes
// read back from memory). It prints tables and, with --out, writes them as CSV (the committed tables live in
// bench/results/<machine>/state.csv).
//
// Usage: lockbox_state_bench [--reps N] [--out FILE] [--only SCENE] [--profile ROUNDS]

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/scenes/LockboxScenes.h"
#include "lockbox/state/WorldHash.h"
#include "lockbox_cli/OptionReader.h"
#include "lockbox_internal/WorldInternals.h"

namespace {

using namespace lockbox;

double MedianMs(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

// Thread CPU time, not wall time: on a shared 2-core machine a descheduled thread would
// otherwise charge other processes' time to whichever phase was running.
double ThreadMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

template <class F>
double TimeMs(F&& f) {
    const double t0 = ThreadMs();
    f();
    return ThreadMs() - t0;
}

struct Case {
    const char* scene;
    int warmup;  ///< frames before measuring (rain: until ~1000 bodies have spawned)
};

struct Row {
    std::string scene;
    int bodies = 0, awake = 0, contacts = 0, joints = 0;
    double stepMs = 0, hashMs = 0, imageHashMs = 0, saveMs = 0, restoreMs = 0;
    /// The hash floor: b2SnapshotHash of the image saved before a step, measured after that
    /// step. The canonical state bytes, already packed, read back from wherever the step left
    /// them: what any hash of this state pays at least, however the world stored it.
    double coldImageHashMs = 0;
    b2SnapshotStats stats;
    // Rollback frames, from their own interleaved pass (a full Restore moves the structure
    // epoch, so the two kinds cannot share one loop): medians, the step of that pass, and the
    // mean save (which carries the structure image of frames after a structural change), all
    // after 8 unmeasured frames.
    double frameSaveMs = 0, frameRestoreMs = 0, frameStepMs = 0, frameSaveMeanMs = 0;
    int frameBodies = 0;     ///< at the end of the frame pass
    double frameBackMs = 0;  ///< median RestoreFrame of a frame 8 frames old
    double imageBackMs = 0;  ///< median Restore of an image 8 frames old
    int backCrossings = 0;   ///< how many of those 8 crossed a structural change
    int backUndone = 0;      ///< how many of those crossings destroyed the bodies made since
    b2FrameStats frameStats;
};

/// --profile N: after warmup, N rounds of save, hash, cold-cache hash and restore with no
/// step in between, printing the minimum and median of each. The state paths alone: for a
/// sampling profiler, and for A/B comparisons of two builds, where the minimum is steadier
/// than the stepped medians on a shared machine.
int g_profileRounds = 0;

Row Measure(const Case& c, int reps) {
    Row row;
    row.scene = c.scene;
    auto scene = scenes::MakeLockboxScene(c.scene);
    scenes::LockboxEngine engine;
    scenes::ConfigureWorld(engine, scene->Info(), scenes::RunSettings{});
    scene->Prepare(scenes::Resolve(scene->Info(), scenes::RunSettings{}));
    scene->Build(engine);
    const auto& info = scene->Info();
    int frame = 0;
    auto advance = [&] {
        scene->BeforeStep(engine, frame++);
        engine.Step(info.hz, info.velocityIterations, info.positionIterations);
    };
    for (int i = 0; i < c.warmup; ++i) advance();
    b2World& world = engine.world();

    std::vector<double> step, hash, imageHash, coldImageHash, save, restore;
    std::vector<uint8> image;
    image.reserve(1 << 20);
    volatile uint64 sink = 0;
    if (g_profileRounds > 0) {
        std::vector<double> ps, ph, pr, ph2, pi;
        std::vector<char> evict(16u << 20, 0);
        for (int r = 0; r < g_profileRounds; ++r) {
            ps.push_back(TimeMs([&] { world.Save(image); }));
            pi.push_back(TimeMs([&] { sink = sink + b2SnapshotHash(image).total; }));
            ph.push_back(TimeMs([&] { sink = sink + world.Hash(); }));
            // The same hash from a cold cache: a 16 MiB sweep first evicts the world from L1
            // and L2 (what a step and other processes do between two hashes in a game).
            for (size_t i = 0; i < evict.size(); i += 64) evict[i] = static_cast<char>(evict[i] + 1);
            ph2.push_back(TimeMs([&] { sink = sink + world.Hash(); }));
            pr.push_back(TimeMs([&] {
                if (!world.Restore(image).ok()) std::abort();
            }));
        }
        auto lo = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
        std::printf("%s profile: save %.4f / %.4f, hash %.4f / %.4f, restore %.4f / %.4f ms (min / median)\n", c.scene,
                    lo(ps), MedianMs(ps), lo(ph), MedianMs(ph), lo(pr), MedianMs(pr));
        std::printf("%s profile: cold-cache hash %.4f / %.4f, image hash %.4f / %.4f ms (min / median)\n", c.scene,
                    lo(ph2), MedianMs(ph2), lo(pi), MedianMs(pi));
    }
    for (int r = 0; r < reps; ++r) {
        // The same state is saved, hashed, restored, then stepped: every figure is for the
        // world as it is at that frame, and the ratios come from interleaved measurements.
        save.push_back(TimeMs([&] { world.Save(image); }));
        // What a session that saves every frame pays for that frame's hash.
        imageHash.push_back(TimeMs([&] { sink = sink + b2SnapshotHash(image).total; }));
        hash.push_back(TimeMs([&] { sink = sink + world.Hash(); }));
        restore.push_back(TimeMs([&] {
            if (!world.Restore(image).ok()) std::abort();
        }));
        step.push_back(TimeMs(advance));
        coldImageHash.push_back(TimeMs([&] { sink = sink + b2SnapshotHash(image).total; }));
    }
    row.stepMs = MedianMs(step);
    row.coldImageHashMs = MedianMs(coldImageHash);
    row.hashMs = MedianMs(hash);
    row.imageHashMs = MedianMs(imageHash);
    row.saveMs = MedianMs(save);
    row.restoreMs = MedianMs(restore);
    row.stats = world.SaveStats();
    row.bodies = world.GetBodyCount();
    row.contacts = world.GetContactCount();
    row.joints = world.GetJointCount();
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) row.awake += b->IsAwake() ? 1 : 0;
    {
        std::vector<double> fs, fr, fstep;
        b2WorldFrame saved;
        // One spawn cycle of rain unmeasured first: the first saves allocate the frame's arrays
        // and the structure buffers (a ring's first lap), which the steady state never does.
        for (int r = 0; r < 8; ++r) {
            world.SaveFrame(saved);
            if (!world.RestoreFrame(saved).ok()) std::abort();
            advance();
        }
        for (int r = 0; r < reps; ++r) {
            fs.push_back(TimeMs([&] { world.SaveFrame(saved); }));
            fr.push_back(TimeMs([&] {
                if (!world.RestoreFrame(saved).ok()) std::abort();
            }));
            fstep.push_back(TimeMs(advance));
        }
        row.frameSaveMs = MedianMs(fs);
        row.frameRestoreMs = MedianMs(fr);
        row.frameStepMs = MedianMs(fstep);
        double sum = 0;
        for (double v : fs) sum += v;
        row.frameSaveMeanMs = fs.empty() ? 0 : sum / static_cast<double>(fs.size());
        row.frameStats = saved.Stats();
        row.frameBodies = world.GetBodyCount();
        // A rollback's restore: the frame of 8 frames ago (steps in between change contacts,
        // and in rain a spawn changes the structure, so the structure image goes in too).
        // The same for images, alternating with the frames so both see the same stretch of
        // the scene.
        std::vector<double> back, imageBack;
        b2WorldFrame old;
        for (int r = 0; r < 16; ++r) {
            const bool frames = r % 2 == 0;
            if (frames)
                world.SaveFrame(old);
            else
                world.Save(image);
            const uint64 epoch = lockbox::test::StructureEpoch(world);
            const int at = frame;
            for (int k = 0; k < 8; ++k) advance();
            if (frames) row.backCrossings += lockbox::test::StructureEpoch(world) != epoch ? 1 : 0;
            const uint64 undone = lockbox::test::FrameRestores(world).undoneCreations;
            (frames ? back : imageBack).push_back(TimeMs([&] {
                if (!(frames ? world.RestoreFrame(old) : world.Restore(image)).ok()) std::abort();
            }));
            row.backUndone += static_cast<int>(lockbox::test::FrameRestores(world).undoneCreations - undone);
            frame = at;
            for (int k = 0; k < 8; ++k) advance();
        }
        row.frameBackMs = MedianMs(back);
        row.imageBackMs = MedianMs(imageBack);
    }
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    int reps = 31;
    std::string only;
    std::string out;  // no CSV unless asked: the committed tables are not overwritten by accident
    lockbox::cli::OptionReader args("lockbox_state_bench", argc, argv);
    while (args.Next()) {
        if (args.Is("--reps"))
            args.Int(1, 1000000, reps);
        else if (args.Is("--out"))
            args.Text(out);
        else if (args.Is("--only"))
            args.Text(only);
        else if (args.Is("--profile"))
            args.Int(0, 1000000, g_profileRounds);
        else
            args.Unknown();
    }
    if (args.Failed())
        return args.Fail("usage: lockbox_state_bench [--reps N] [--out FILE] [--only SCENE] [--profile ROUNDS]\n");
    const Case cases[] = {{"pyramid20", 120}, {"ragdolls", 60},   {"rain", 320},
                          {"tumbler", 60},    {"joint_grid", 10}, {"large_pyramid", 10}};
    std::FILE* csv = nullptr;
    if (!out.empty()) {
        csv = std::fopen(out.c_str(), "w");
        if (csv == nullptr) {
            std::fprintf(stderr, "cannot write %s\n", out.c_str());
            return 1;
        }
        std::fprintf(csv,
                     "scene,bodies,awake,contacts,joints,step_ms,hash_ms,image_hash_ms,save_ms,restore_ms,"
                     "hash_pct_of_step,image_hash_pct_of_step,save_restore_pct_of_step,image_bytes,body_bytes,"
                     "fixture_bytes,contact_bytes,joint_bytes,broadphase_bytes,bytes_per_body,bytes_per_contact,"
                     "bytes_per_joint,frame_step_ms,frame_save_ms,frame_save_mean_ms,frame_restore_ms,"
                     "frame_save_restore_pct_of_step,frame_bytes,frame_structure_bytes,frame_body_bytes_per_body,"
                     "frame_restore_back8_ms,back8_structure_changes,image_restore_back8_ms,image_hash_after_step_ms,"
                     "image_hash_after_step_pct_of_step,back8_undone\n");
    }
    std::printf("%-14s %6s %6s %6s %9s %8s %8s %8s %9s %7s %7s %9s %9s %8s %8s %8s\n", "scene", "bodies", "contct",
                "joints", "step ms", "hash ms", "img h ms", "save ms", "restor ms", "hash %", "img h %", "s+r %",
                "image KB", "B/body", "B/cont", "B/joint");
    struct FrameLine {
        std::string scene;
        double stepMs, saveMs, saveMeanMs, restoreMs, pct, frameKb, structureKb, bodyBytes, backMs;
        int crossings, undone;
        double imageBackMs;
    };
    struct FloorLine {
        std::string scene;
        double stepMs, hashMs, imageHashMs, coldImageHashMs;
    };
    std::vector<FloorLine> floors;
    std::vector<FrameLine> frames;
    for (const Case& c : cases) {
        if (!only.empty() && only != c.scene) continue;
        const Row r = Measure(c, reps);
        const double hashPct = 100 * r.hashMs / r.stepMs;
        const double imageHashPct = 100 * r.imageHashMs / r.stepMs;
        const double srPct = 100 * (r.saveMs + r.restoreMs) / r.stepMs;
        // Bodies carry their fixtures (shapes, proxies) in these per-body figures.
        const double perBody = r.bodies ? double(r.stats.bodyBytes + r.stats.fixtureBytes) / r.bodies : 0;
        const double perContact = r.contacts ? double(r.stats.contactBytes) / r.contacts : 0;
        const double perJoint = r.joints ? double(r.stats.jointBytes) / r.joints : 0;
        std::printf("%-14s %6d %6d %6d %9.3f %8.3f %8.3f %8.3f %9.3f %7.2f %7.2f %9.2f %9.1f %8.1f %8.1f %8.1f\n",
                    r.scene.c_str(), r.bodies, r.contacts, r.joints, r.stepMs, r.hashMs, r.imageHashMs, r.saveMs,
                    r.restoreMs, hashPct, imageHashPct, srPct, r.stats.totalBytes / 1024.0, perBody, perContact,
                    perJoint);
        const double frameSrPct = 100 * (r.frameSaveMs + r.frameRestoreMs) / r.frameStepMs;
        const double frameBodyBytes =
            r.frameBodies
                ? double(r.frameStats.bodyBytes + r.frameStats.forceBytes + r.frameStats.proxyBytes) / r.frameBodies
                : 0;
        frames.push_back({r.scene, r.frameStepMs, r.frameSaveMs, r.frameSaveMeanMs, r.frameRestoreMs, frameSrPct,
                          r.frameStats.frameBytes / 1024.0, r.frameStats.structureBytes / 1024.0, frameBodyBytes,
                          r.frameBackMs, r.backCrossings, r.backUndone, r.imageBackMs});
        floors.push_back({r.scene, r.stepMs, r.hashMs, r.imageHashMs, r.coldImageHashMs});
        const double coldPct = 100 * r.coldImageHashMs / r.stepMs;
        if (csv != nullptr) {
            std::fprintf(csv,
                         "%s,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%u,%u,%u,%u,%u,%u,%.1f,%.1f,%.1f,"
                         "%.4f,%.4f,%.4f,%.4f,%.3f,%u,%u,%.1f,%.4f,%d,%.4f,%.4f,%.3f,%d\n",
                         r.scene.c_str(), r.bodies, r.awake, r.contacts, r.joints, r.stepMs, r.hashMs, r.imageHashMs,
                         r.saveMs, r.restoreMs, hashPct, imageHashPct, srPct, r.stats.totalBytes, r.stats.bodyBytes,
                         r.stats.fixtureBytes, r.stats.contactBytes, r.stats.jointBytes, r.stats.broadPhaseBytes,
                         perBody, perContact, perJoint, r.frameStepMs, r.frameSaveMs, r.frameSaveMeanMs,
                         r.frameRestoreMs, frameSrPct, r.frameStats.frameBytes, r.frameStats.structureBytes,
                         frameBodyBytes, r.frameBackMs, r.backCrossings, r.imageBackMs, r.coldImageHashMs, coldPct,
                         r.backUndone);
        }
    }
    std::printf("(medians of %d interleaved repetitions, thread CPU time)\n\n", reps);
    std::printf("rollback frames (SaveFrame/RestoreFrame, own pass)\n");
    std::printf("%-14s %9s %8s %9s %9s %7s %9s %9s %8s %9s %15s %9s\n", "scene", "step ms", "save ms", "save mean",
                "restor ms", "s+r %", "frame KB", "struct KB", "B/body", "back8 ms", "struct (undone)", "img back8");
    for (const FrameLine& f : frames) {
        std::printf("%-14s %9.3f %8.3f %9.3f %9.3f %7.2f %9.1f %9.1f %8.1f %9.3f %6d/8 (%d) %9.3f\n", f.scene.c_str(),
                    f.stepMs, f.saveMs, f.saveMeanMs, f.restoreMs, f.pct, f.frameKb, f.structureKb, f.bodyBytes,
                    f.backMs, f.crossings, f.undone, f.imageBackMs);
    }
    std::printf(
        "(B/body: motion, pending forces and proxy boxes; contacts, joints and the tree apart; back8: "
        "restore of the frame 8 frames old, struct: how many of 8 such restores crossed a structural change, undone: "
        "how many of those only destroyed the bodies made since; img back8: the same for images)\n");
    std::printf("\nhash floor (shares of the step in the first pass)\n");
    std::printf("%-14s %9s %8s %8s %8s %9s\n", "scene", "step ms", "walk %", "img h %", "floor ms", "floor %");
    for (const FloorLine& f : floors) {
        std::printf("%-14s %9.3f %8.2f %8.2f %8.4f %9.2f\n", f.scene.c_str(), f.stepMs, 100 * f.hashMs / f.stepMs,
                    100 * f.imageHashMs / f.stepMs, f.coldImageHashMs, 100 * f.coldImageHashMs / f.stepMs);
    }
    std::printf(
        "(walk: b2WorldHash; img h: b2SnapshotHash of the image just saved; floor: the same image's hash "
        "after a step, the packed state bytes read back from where the step left them)\n");
    if (csv != nullptr) {
        std::fclose(csv);
        std::printf("wrote %s\n", out.c_str());
    }
    return 0;
}
