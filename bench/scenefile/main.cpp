// lockbox_scenefile_bench: how long a b2dJson scene file takes to load and to save.
//
//   lockbox_scenefile_bench [--bodies N] [--repeat R] [--write FILE]
//       builds a world of N dynamic bodies (alternating boxes and circles on a grid, every
//       tenth pair joined by a revolute joint) over a ground chain, saves it, then loads the
//       text R times (default N = 10000, R = 11).
//   lockbox_scenefile_bench --file FILE [--repeat R]
//       loads FILE instead.
//
// Prints the median and the fastest wall time of: parsing and validating (ReadScene), building
// the world (BuildScene), the whole load (LoadScene: both, also as CPU time), and saving
// (SaveScene), in ms.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/scenefile/SceneFile.h"
#include "lockbox/state/WorldHash.h"
#include "lockbox_cli/OptionReader.h"

using namespace lockbox;
using namespace lockbox::scenefile;

namespace {

using Clock = std::chrono::steady_clock;

double Ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// This thread's CPU time, ms: on a machine shared with other work it is what a load costs,
// while the wall time also counts the time slices given to others.
double CpuMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

struct Stat {
    double median = 0, best = 0;
};

Stat Summarise(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return {v[v.size() / 2], v.front()};
}

std::unique_ptr<b2World> MakeWorld(int bodies) {
    auto world = std::make_unique<b2World>(b2Vec2(0, -10));
    b2BodyDef groundDef;
    b2Body* ground = world->CreateBody(&groundDef);
    const b2Vec2 floor[4] = {b2Vec2(-200, 30), b2Vec2(-200, 0), b2Vec2(200, 0), b2Vec2(200, 30)};
    b2ChainShape chain;
    chain.CreateChain(floor, 4);
    ground->CreateFixture(&chain, 0);

    b2PolygonShape box;
    box.SetAsBox(Fixed::FromRatio(2, 5), Fixed::FromRatio(2, 5));
    b2CircleShape circle(Fixed::FromRatio(2, 5));
    b2FixtureDef fd;
    fd.density = 1;
    fd.friction = Fixed::FromRatio(3, 5);
    const int columns = 100;
    b2Body* previous = nullptr;
    for (int i = 0; i < bodies; ++i) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(Fixed(i % columns) - 50, Fixed(1 + i / columns) + Fixed::FromRatio(i % 7, 10));
        bd.angle = Fixed::FromRatio(i % 13, 10);
        b2Body* b = world->CreateBody(&bd);
        fd.shape = i % 2 ? static_cast<const b2Shape*>(&circle) : &box;
        b->CreateFixture(&fd);
        if (previous && i % 10 == 1) {
            b2RevoluteJointDef jd;
            jd.Initialize(previous, b, previous->GetPosition());
            world->CreateJoint(&jd);
        }
        previous = b;
    }
    return world;
}

}  // namespace

int main(int argc, char** argv) {
    int bodies = 10000;
    int repeat = 11;
    std::string file, write;
    lockbox::cli::OptionReader args("lockbox_scenefile_bench", argc, argv);
    while (args.Next()) {
        if (args.Is("--bodies"))
            args.Int(1, 10000000, bodies);
        else if (args.Is("--repeat"))
            args.Int(1, 100000, repeat);
        else if (args.Is("--file"))
            args.Text(file);
        else if (args.Is("--write"))
            args.Text(write);
        else
            args.Unknown();
    }
    if (args.Failed())
        return args.Fail(
            "usage: lockbox_scenefile_bench [--bodies N] [--repeat R] [--write FILE]\n"
            "       lockbox_scenefile_bench --file FILE [--repeat R]\n");

    std::string text;
    std::vector<double> saves;
    if (!file.empty()) {
        if (SceneResult r = ReadSceneFileBytes(file, text); !r) {
            std::fprintf(stderr, "%s\n", r.Describe().c_str());
            return 1;
        }
    } else {
        auto world = MakeWorld(bodies);
        for (int i = 0; i < repeat; ++i) {
            const auto t0 = Clock::now();
            text = SaveScene(*world);
            saves.push_back(Ms(t0, Clock::now()));
        }
        if (!write.empty() && !SaveSceneFile(write, *world)) return 1;
    }

    std::vector<double> reads, builds, loads, loadCpu;
    uint64_t hash = 0;
    int count = 0;
    for (int i = 0; i < repeat; ++i) {
        SceneDocument doc;
        auto t0 = Clock::now();
        SceneResult r = ReadScene(text, doc);
        auto t1 = Clock::now();
        if (!r) {
            std::fprintf(stderr, "%s\n", r.Describe().c_str());
            return 1;
        }
        b2World world(doc.world.gravity);
        auto t2 = Clock::now();
        r = BuildScene(doc, world);
        auto t3 = Clock::now();
        reads.push_back(Ms(t0, t1));
        builds.push_back(Ms(t2, t3));

        b2World again(b2Vec2(0, -10));
        const double c4 = CpuMs();
        auto t4 = Clock::now();
        r = LoadScene(text, again);
        loads.push_back(Ms(t4, Clock::now()));
        loadCpu.push_back(CpuMs() - c4);
        hash = b2WorldHash(again);
        count = again.GetBodyCount();
    }
    const Stat read = Summarise(reads), build = Summarise(builds), load = Summarise(loads), cpu = Summarise(loadCpu);
    std::printf("scene-file bodies=%d bytes=%zu repeat=%d hash=0x%016llx\n", count, text.size(), repeat,
                static_cast<unsigned long long>(hash));
    std::printf("  read   median %.2f ms  best %.2f ms\n", read.median, read.best);
    std::printf("  build  median %.2f ms  best %.2f ms\n", build.median, build.best);
    std::printf("  load   median %.2f ms  best %.2f ms  (CPU time: median %.2f ms  best %.2f ms)\n", load.median,
                load.best, cpu.median, cpu.best);
    if (!saves.empty()) {
        const Stat save = Summarise(saves);
        std::printf("  save   median %.2f ms  best %.2f ms\n", save.median, save.best);
    }
    return 0;
}
