// lockbox_replay_bench: what a replay costs. For a few scenes it records a run with
// two players' scripted 8-byte inputs, then measures in the same process the thread CPU time
// of (a) the bare simulation of the same frames (the game's inputs applied, Step, nothing
// else) and (b) Player::Verify (restore the seed, the same frames, a state hash after every
// frame), alternating the two; it prints the median ratio, the input stream's bytes per second
// before compression, the file's compressed size by chunk type and the time ParseReplay takes to
// read the whole file back, and, with --out, writes a CSV (without the parse time).
//
// Usage: lockbox_replay_bench [--reps N] [--frames N] [--out FILE] [--only SCENE]

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "lockbox/replay/Player.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox_cli/OptionReader.h"

namespace {

using namespace lockbox;
using namespace lockbox::replay;

double ThreadMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double Median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

struct Row {
    std::string scene;
    int frames = 0, bodies = 0;
    double bareMs = 0, verifyMs = 0, ratio = 0, realTime = 0;
    double parseMs = 0;                                ///< ParseReplay of the whole file (stdout only)
    double inputPayloadPerS = 0, inputFramedPerS = 0;  // bytes/s before compression
    uint64 fileBytes = 0, inptStored = 0, hashStored = 0, keyfStored = 0, seedStored = 0;
};

}  // namespace

int main(int argc, char** argv) {
    int reps = 5, frames = 600;
    std::string out, only;  // CSV only with --out: the committed tables are not overwritten by accident
    lockbox::cli::OptionReader args("lockbox_replay_bench", argc, argv);
    while (args.Next()) {
        if (args.Is("--reps"))
            args.Int(1, 1000000, reps);
        else if (args.Is("--frames"))
            args.Int(1, 100000000, frames);
        else if (args.Is("--out"))
            args.Text(out);
        else if (args.Is("--only"))
            args.Text(only);
        else
            args.Unknown();
    }
    if (args.Failed())
        return args.Fail("usage: lockbox_replay_bench [--reps N] [--frames N] [--out FILE] [--only SCENE]\n");
    const char* scenesToRun[] = {"pyramid20", "ragdolls", "tumbler", "rain"};
    std::vector<Row> rows;
    for (const char* scene : scenesToRun) {
        if (!only.empty() && only != scene) continue;
        Row row;
        row.scene = scene;
        row.frames = frames;
        // Record (keyframe every 10 s, hash every frame, zstd level 3: the defaults).
        MemorySink sink;
        std::vector<std::vector<uint8>> inputs;
        {
            SceneGame game(scene);
            Recorder rec(game.world(), game, sink, game.Config(2));
            rec.Begin();
            ScriptedInputs script(42, 2);
            for (int f = 0; f < frames; ++f) {
                inputs.emplace_back();
                script.Next(inputs.back());
                rec.Advance(inputs.back());
            }
            rec.Finish();
            row.bodies = game.world().GetBodyCount();
        }
        ReplayFile file;
        if (Error e = ParseReplay(sink.bytes(), file); !e.ok()) {
            std::fprintf(stderr, "%s: %s\n", scene, e.Describe().c_str());
            return 1;
        }
        // The reader alone: parse the whole file again (header, chunk checksums, zstd, every
        // payload field), the median of 15 parses.
        {
            std::vector<double> parses;
            for (int r = 0; r < 15; ++r) {
                ReplayFile again;
                const double t0 = ThreadMs();
                const Error e = ParseReplay(sink.bytes(), again);
                parses.push_back(ThreadMs() - t0);
                if (!e.ok()) return 1;
            }
            row.parseMs = Median(parses);
        }
        const double seconds = static_cast<double>(frames) / file.header.tickRate;
        row.fileBytes = file.fileBytes;
        for (const ChunkStat& s : file.chunkStats) {
            if (s.type == e_chunkInputs) {
                row.inptStored = s.storedBytes;
                row.inputPayloadPerS = static_cast<double>(s.rawBytes) / seconds;
                row.inputFramedPerS = static_cast<double>(s.rawBytes + 24ull * s.count) / seconds;
            }
            if (s.type == e_chunkHashes) row.hashStored = s.storedBytes;
            if (s.type == e_chunkKeyframe) row.keyfStored = s.storedBytes;
            if (s.type == e_chunkSeed) row.seedStored = s.storedBytes;
        }
        // Both runs start from a freshly built scene restored to the seed, so they do the
        // same work; only the per-frame hash (and the hash compare) is extra in (b).
        std::vector<double> bare, verify;
        for (int r = 0; r < reps; ++r) {
            {
                SceneGame game(scene);
                game.world().Restore(file.seed.world);
                const Fixed dt = Fixed::FromRaw(file.header.timeStepRaw);
                const double t0 = ThreadMs();
                for (int f = 0; f < frames; ++f) {
                    game.Apply(game.world(), f, inputs[static_cast<size_t>(f)]);
                    game.world().Step(dt, file.header.velocityIterations, file.header.positionIterations);
                }
                bare.push_back(ThreadMs() - t0);
            }
            {
                SceneGame game(scene);
                Player player(file, game.world(), game);
                const double t0 = ThreadMs();
                const VerifyResult v = player.Verify();
                verify.push_back(ThreadMs() - t0);
                if (!v.ok) {
                    std::fprintf(stderr, "%s: verify failed: %s\n", scene, v.message.c_str());
                    return 1;
                }
            }
        }
        row.bareMs = Median(bare);
        row.verifyMs = Median(verify);
        row.ratio = row.bareMs > 0 ? row.verifyMs / row.bareMs : 0;
        row.realTime = row.verifyMs > 0 ? seconds * 1e3 / row.verifyMs : 0;
        rows.push_back(row);
        std::printf(
            "%-14s frames=%d bodies=%d bare=%.1f ms verify=%.1f ms ratio=%.3f speed=%.1fx real time parse=%.3f ms | "
            "inputs %.0f B/s raw (%.0f with chunk frames), file %llu B (INPT %llu, HASH %llu, KEYF %llu, SEED %llu)\n",
            scene, row.frames, row.bodies, row.bareMs, row.verifyMs, row.ratio, row.realTime, row.parseMs,
            row.inputPayloadPerS, row.inputFramedPerS, static_cast<unsigned long long>(row.fileBytes),
            static_cast<unsigned long long>(row.inptStored), static_cast<unsigned long long>(row.hashStored),
            static_cast<unsigned long long>(row.keyfStored), static_cast<unsigned long long>(row.seedStored));
        std::fflush(stdout);
    }
    if (!out.empty() && only.empty()) {
        if (std::FILE* f = std::fopen(out.c_str(), "w")) {
            std::fprintf(
                f,
                "scene,frames,bodies_end,bare_ms,verify_ms,ratio,realtime_x,input_Bps_payload,input_Bps_framed,"
                "file_bytes,inpt_bytes,hash_bytes,keyf_bytes,seed_bytes\n");
            for (const Row& r : rows)
                std::fprintf(
                    f, "%s,%d,%d,%.2f,%.2f,%.4f,%.1f,%.1f,%.1f,%llu,%llu,%llu,%llu,%llu\n", r.scene.c_str(), r.frames,
                    r.bodies, r.bareMs, r.verifyMs, r.ratio, r.realTime, r.inputPayloadPerS, r.inputFramedPerS,
                    static_cast<unsigned long long>(r.fileBytes), static_cast<unsigned long long>(r.inptStored),
                    static_cast<unsigned long long>(r.hashStored), static_cast<unsigned long long>(r.keyfStored),
                    static_cast<unsigned long long>(r.seedStored));
            std::fclose(f);
            std::printf("wrote %s\n", out.c_str());
        }
    }
    return 0;
}
