// Bisect: binary search over stored states, scan of one interval, then the fencepost.
#include "lockbox/replay/Bisect.h"

#include <vector>

#include "HexText.h"

namespace lockbox::replay {

using detail::Hex;

namespace {

// A stored state with a known hash: the seed, a keyframe, or the end.
struct Point {
    int32 frame;
    uint64 hash;
    const Keyframe* snapshot;  // nullptr for the end record
};

// The first velocity/position phase whose hash differs, when the file stores them.
int32 FirstSolvePhase(const uint64* want, const uint64* got) {
    if (want == nullptr) return -1;
    for (uint32 p = 0; p < kSolvePhasesPerFrame; ++p)
        if (want[p] != got[p]) return static_cast<int32>(p);
    return -1;
}

}  // namespace

BisectResult Bisect(Player& player) {
    BisectResult r;
    const ReplayFile& file = player.file();
    const int32 restores0 = player.Restores();
    const int64_t played0 = player.FramesPlayed();
    auto finish = [&]() -> BisectResult& {
        r.restores = player.Restores() - restores0;
        r.framesPlayed = player.FramesPlayed() - played0;
        return r;
    };

    std::vector<Point> points;
    points.push_back({0, file.seed.hash, &file.seed});
    for (const Keyframe& k : file.keyframes) points.push_back({k.frame, k.hash, &k});
    if (points.back().frame < file.frameCount) points.push_back({file.frameCount, file.finalHash, nullptr});

    // Invariant: re-simulation from points[lo] reaches points[lo] (restored, so true for the
    // seed) and, by assumption until the scan says otherwise, differs by points[hi].
    size_t lo = 0, hi = points.size() - 1;
    bool atLo = false;  // the player's world holds points[lo]'s state
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        ++r.probes;
        if (!atLo) {
            if (Error e = player.Restore(*points[lo].snapshot); !e.ok()) {
                r.error = e;
                return finish();
            }
        }
        while (player.Frame() < points[mid].frame) player.Step();
        if (player.world().Hash() == points[mid].hash) {
            lo = mid;
            atLo = true;
        } else {
            hi = mid;
            atLo = false;
        }
    }
    r.lowKeyframe = points[lo].frame;
    r.highKeyframe = points[hi].frame;

    // Scan the interval (lo, hi] frame by frame, with fencepost hashes when they are stored.
    if (!atLo) {
        if (Error e = player.Restore(*points[lo].snapshot); !e.ok()) {
            r.error = e;
            return finish();
        }
    }
    const bool stages = !file.stageHashes.empty();
    player.SetStageHashing(stages);
    while (player.Frame() < points[hi].frame) {
        const int32 frame = player.Frame();
        player.Step();
        if (stages) {
            const uint64* want = file.Stages(frame);
            const uint64* got = player.LastStages();
            for (uint32 s = 0; s < kStagesPerFrame; ++s) {
                if (want[s] == got[s]) continue;
                r.diverged = true;
                r.frame = frame;
                r.stage = static_cast<int32>(s);
                r.expected = want[s];
                r.actual = got[s];
                if (s == 2) r.solvePhase = FirstSolvePhase(file.SolvePhases(frame), player.LastSolvePhases());
                player.SetStageHashing(false);
                return finish();
            }
        }
        const bool last = player.Frame() == file.frameCount;
        if (!file.HasHash(frame) && !last) continue;
        const uint64 want = file.HasHash(frame) ? file.hashes[static_cast<size_t>(frame)] : file.finalHash;
        const uint64 got = player.world().Hash();
        if (want == got) continue;
        r.diverged = true;
        r.frame = frame;
        r.frameExact = stages || file.header.hashInterval == 1;
        r.stage = stages ? kStageAfterToi : -1;
        r.expected = want;
        r.actual = got;
        break;
    }
    player.SetStageHashing(false);
    return finish();
}

std::string BisectResult::Describe() const {
    if (!error.ok()) return "error: " + error.Describe() + "\n";
    std::string s;
    if (!diverged) {
        s = "NO DIVERGENCE: re-simulation matches the recording at every keyframe probed and every stored hash after "
            "frame " +
            std::to_string(lowKeyframe) + "\n  " + std::to_string(probes) + " probes, " + std::to_string(restores) +
            " restores, " + std::to_string(framesPlayed) + " frames simulated\n";
        return s;
    } else {
        s = "DIVERGED at frame " + std::to_string(frame) + (frameExact ? "" : " (or earlier in its hash interval)");
        if (stage >= 0 && stage < kStageAfterToi) {
            s += ", stage " + std::string(StageName(static_cast<uint32>(stage)));
            if (solvePhase >= 0) s += " (" + std::string(SolvePhaseName(static_cast<uint32>(solvePhase))) + ")";
            s += stage == 0 ? " (the inputs or the state before the step)" : "";
        } else if (stage == kStageAfterToi) {
            s += ", after the toi stage (force clearing, world bounds)";
        } else {
            s += ", stage unknown (record with fencepost hashes: --stage-hashes)";
        }
        s += "\n  recorded " + Hex(expected) + "  re-simulated " + Hex(actual);
    }
    s += "\n  keyframes: good at frame " + std::to_string(lowKeyframe) + ", bad by frame " +
         std::to_string(highKeyframe) + "; " + std::to_string(probes) + " probes, " + std::to_string(restores) +
         " restores, " + std::to_string(framesPlayed) + " frames simulated\n";
    return s;
}

}  // namespace lockbox::replay
