// lockbox_web_native: the native half of the JavaScript API's node tests (tests/web/node).
// Each command prints one line on stdout that the tests compare with what the WebAssembly
// module computes:
//
//   scene-hash SCENE N               the state hash after N steps of a library scene
//   save SCENE N FILE                runs N steps, writes the world's snapshot to FILE, prints
//                                    the hash
//   continue FILE M                  restores FILE into a fresh world, steps M times at 1/60 s
//                                    (8 velocity, 3 position iterations), prints the hash
//   joint-rig N                      builds the rig of tests/web/node/rig.js (every joint type
//                                    and shape type) natively, prints the hash after N steps
//   record-divergent SCENE FRAMES F OUT
//                                    records a replay of SCENE whose recorded run is nudged
//                                    after frame F (one raw unit of a body's velocity), so
//                                    that verifying it diverges at frame F + 1
//   time SCENE N REPS                the median over REPS runs of the mean step time (ms) of
//                                    N steps of SCENE, and the final hash (the native column of
//                                    bench/web/step_time.js)
//
// Hashes print as 0x and 16 hex digits, as every lockbox tool prints them.
#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/lockbox.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox/scenes/LockboxScenes.h"

using namespace lockbox;

namespace {

void PrintHash(uint64 h) { std::printf("0x%016" PRIx64 "\n", h); }

int Usage() {
    std::fprintf(stderr,
                 "usage: lockbox_web_native scene-hash SCENE N | save SCENE N FILE | continue FILE M | "
                 "joint-rig N | record-divergent SCENE FRAMES F OUT | time SCENE N REPS\n");
    return 2;
}

// A library scene built and stepped as the golden hashes are (tests/cross/GoldenScenes.h).
struct SceneRun {
    std::unique_ptr<scenes::LockboxScene> scene;
    scenes::LockboxEngine engine;
    int steps = 0;

    explicit SceneRun(const char* name) : scene(scenes::MakeLockboxScene(name)) {
        if (!scene) return;
        scenes::RunSettings s;
        s.trackMetrics = false;
        scenes::ConfigureWorld(engine, scene->Info(), s);
        scene->Prepare(scenes::Resolve(scene->Info(), s));
        scene->Build(engine);
    }
    void Step(int n) {
        const scenes::SceneInfo& info = scene->Info();
        for (int i = 0; i < n; ++i, ++steps) {
            scene->BeforeStep(engine, steps);
            engine.Step(info.hz, info.velocityIterations, info.positionIterations);
        }
    }
};

Fixed Dec(const char* text) {
    Fixed v;
    if (!Fixed::Parse(text, v)) std::abort();
    return v;
}

b2Vec2 V(const char* x, const char* y) { return b2Vec2(Dec(x), Dec(y)); }

// The rig of tests/web/node/rig.js, statement for statement: the same definitions in the same
// order, with the same decimal values (the JavaScript side passes the same numbers).
void BuildRig(b2World& world) {
    b2BodyDef groundDef;
    b2Body* ground = world.CreateBody(&groundDef);
    {
        b2EdgeShape edge;
        edge.Set(V("-30", "0"), V("30", "0"));
        ground->CreateFixture(&edge, 0);
        b2ChainShape loop;
        const b2Vec2 pts[4] = {V("-29", "1"), V("-27", "1"), V("-27", "3"), V("-29", "3")};
        loop.CreateLoop(pts, 4);
        b2FixtureDef fd;
        fd.shape = &loop;
        fd.friction = Dec("0.4");
        ground->CreateFixture(&fd);
    }
    auto dynamicBox = [&](const char* x, const char* y, const char* hx, const char* hy) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = V(x, y);
        b2Body* b = world.CreateBody(&bd);
        b2PolygonShape box;
        box.SetAsBox(Dec(hx), Dec(hy));
        b->CreateFixture(&box, Dec("1"));
        return b;
    };
    auto dynamicCircle = [&](const char* x, const char* y, const char* r) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = V(x, y);
        b2Body* b = world.CreateBody(&bd);
        b2CircleShape c;
        c.Set(b2Vec2(0, 0), Dec(r));
        b2FixtureDef fd;
        fd.shape = &c;
        fd.density = Dec("2");
        fd.restitution = Dec("0.25");
        b->CreateFixture(&fd);
        return b;
    };

    // Revolute with limit and motor.
    b2Body* a = dynamicBox("-20", "5", "0.5", "0.125");
    {
        b2RevoluteJointDef jd;
        jd.Initialize(ground, a, V("-20.5", "5"));
        jd.enableLimit = true;
        jd.lowerAngle = Dec("-0.75");
        jd.upperAngle = Dec("0.5");
        jd.enableMotor = true;
        jd.motorSpeed = Dec("1.5");
        jd.maxMotorTorque = Dec("40");
        world.CreateJoint(&jd);
    }
    // Prismatic with limit and motor, then a gear between it and a second revolute.
    b2Body* slider = dynamicBox("-15", "4", "0.5", "0.5");
    b2Joint* prismatic;
    {
        b2PrismaticJointDef jd;
        jd.Initialize(ground, slider, V("-15", "4"), V("1", "1"));
        jd.enableLimit = true;
        jd.lowerTranslation = Dec("-1");
        jd.upperTranslation = Dec("2.5");
        jd.enableMotor = true;
        jd.maxMotorForce = Dec("100");
        jd.motorSpeed = Dec("0.75");
        prismatic = world.CreateJoint(&jd);
    }
    b2Body* wheel = dynamicCircle("-12", "4", "0.75");
    b2Joint* revolute;
    {
        b2RevoluteJointDef jd;
        jd.Initialize(ground, wheel, V("-12", "4"));
        revolute = world.CreateJoint(&jd);
    }
    {
        b2GearJointDef jd;
        jd.bodyA = slider;
        jd.bodyB = wheel;
        jd.joint1 = prismatic;
        jd.joint2 = revolute;
        jd.ratio = Dec("0.5");
        world.CreateJoint(&jd);
    }
    // Distance (soft) and rope.
    b2Body* d1 = dynamicCircle("-8", "6", "0.25");
    {
        b2DistanceJointDef jd;
        jd.Initialize(ground, d1, V("-8", "9"), V("-8", "6"));
        jd.frequencyHz = Dec("3");
        jd.dampingRatio = Dec("0.2");
        world.CreateJoint(&jd);
    }
    b2Body* r1 = dynamicBox("-5", "7", "0.25", "0.25");
    {
        b2RopeJointDef jd;
        jd.bodyA = ground;
        jd.bodyB = r1;
        jd.localAnchorA = V("-5", "10");
        jd.localAnchorB = V("0", "0.25");
        jd.maxLength = Dec("3.5");
        world.CreateJoint(&jd);
    }
    // Pulley between two boxes.
    b2Body* p1 = dynamicBox("-1", "5", "0.5", "0.5");
    b2Body* p2 = dynamicBox("2", "6", "0.5", "0.5");
    {
        b2PulleyJointDef jd;
        jd.Initialize(p1, p2, V("-1", "10"), V("2", "10"), V("-1", "5.5"), V("2", "6.5"), Dec("1.5"));
        world.CreateJoint(&jd);
    }
    // Weld (soft) of a triangle to a box, and friction on a box resting on the ground.
    b2Body* w1 = dynamicBox("6", "2", "1", "0.25");
    b2Body* w2;
    {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = V("7", "2.5");
        bd.angle = Dec("0.3");
        w2 = world.CreateBody(&bd);
        b2PolygonShape tri;
        const b2Vec2 pts[3] = {V("0", "0"), V("1", "0"), V("0", "0.75")};
        tri.Set(pts, 3);
        w2->CreateFixture(&tri, Dec("1.5"));
    }
    {
        b2WeldJointDef jd;
        jd.Initialize(w1, w2, V("7", "2.25"));
        jd.frequencyHz = Dec("4");
        jd.dampingRatio = Dec("0.5");
        world.CreateJoint(&jd);
    }
    b2Body* f1 = dynamicBox("10", "0.5", "0.5", "0.5");
    {
        b2FrictionJointDef jd;
        jd.Initialize(ground, f1, V("10", "0.5"));
        jd.maxForce = Dec("3");
        jd.maxTorque = Dec("1");
        world.CreateJoint(&jd);
    }
    f1->ApplyLinearImpulse(V("4", "0"), f1->GetWorldCenter());
    // Wheel joint with a spring and a motor.
    b2Body* chassis = dynamicBox("14", "2", "1", "0.25");
    b2Body* tyre = dynamicCircle("14.5", "1.25", "0.4");
    {
        b2WheelJointDef jd;
        jd.Initialize(chassis, tyre, V("14.5", "1.25"), V("0", "1"));
        jd.enableMotor = true;
        jd.maxMotorTorque = Dec("10");
        jd.motorSpeed = Dec("-4");
        jd.frequencyHz = Dec("5");
        jd.dampingRatio = Dec("0.7");
        world.CreateJoint(&jd);
    }
    // Mouse joint pulling a box towards a target.
    b2Body* m1 = dynamicBox("20", "3", "0.5", "0.5");
    {
        b2MouseJointDef jd;
        jd.bodyA = ground;
        jd.bodyB = m1;
        jd.target = V("20", "3");
        jd.maxForce = Wide::FromRaw(int64_t{500} << 32);
        jd.frequencyHz = Dec("2");
        jd.dampingRatio = Dec("0.5");
        b2MouseJoint* mj = static_cast<b2MouseJoint*>(world.CreateJoint(&jd));
        mj->SetTarget(V("22", "6"));
    }
}

bool ReadFile(const char* path, std::vector<uint8>& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
}

bool WriteFile(const char* path, const std::vector<uint8>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return static_cast<bool>(out);
}

int RecordDivergent(const char* sceneName, int frames, int nudgeAfter, const char* path) {
    using namespace lockbox::replay;
    SceneGame game(sceneName);
    if (!game.ok()) return Usage();
    MemorySink sink;
    RecorderConfig config = game.Config(2);
    config.keyframeInterval = 60;
    config.stageHashes = true;
    Recorder recorder(game.world(), game, sink, config);
    if (Error e = recorder.Begin(); !e.ok()) {
        std::fprintf(stderr, "%s\n", e.Describe().c_str());
        return 1;
    }
    ScriptedInputs script(7, 2);
    std::vector<uint8> inputs;
    for (int f = 0; f < frames; ++f) {
        script.Next(inputs);
        recorder.Advance(inputs);
        if (f == nudgeAfter) {
            // What a desync looks like: the recording machine's state moves by one raw unit
            // between two frames; a verifier re-simulating the inputs does not see it.
            for (b2Body* b = game.world().GetBodyList(); b; b = b->GetNext()) {
                if (b->GetType() != b2_dynamicBody) continue;
                const b2Vec2 v = b->GetLinearVelocity();
                b->SetLinearVelocity(b2Vec2(Fixed::FromRaw(v.x.Raw() + 1), v.y));
                break;
            }
        }
    }
    if (Error e = recorder.Finish(); !e.ok()) {
        std::fprintf(stderr, "%s\n", e.Describe().c_str());
        return 1;
    }
    if (!WriteFile(path, sink.bytes())) return Usage();
    std::printf("%d\n", nudgeAfter + 1);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return Usage();
    const std::string cmd = argv[1];
    if (cmd == "scene-hash" && argc == 4) {
        SceneRun run(argv[2]);
        if (!run.scene) return Usage();
        run.Step(std::atoi(argv[3]));
        PrintHash(run.engine.world().Hash());
        return 0;
    }
    if (cmd == "save" && argc == 5) {
        SceneRun run(argv[2]);
        if (!run.scene) return Usage();
        run.Step(std::atoi(argv[3]));
        if (!WriteFile(argv[4], run.engine.world().Save())) return Usage();
        PrintHash(run.engine.world().Hash());
        return 0;
    }
    if (cmd == "continue" && argc == 4) {
        std::vector<uint8> bytes;
        if (!ReadFile(argv[2], bytes)) return Usage();
        b2World world(b2Vec2(0, -10));
        if (const b2RestoreResult r = world.Restore(bytes); !r) {
            std::fprintf(stderr, "restore refused: %s\n", r.message.c_str());
            return 1;
        }
        const int steps = std::atoi(argv[3]);
        for (int i = 0; i < steps; ++i) world.Step(Fixed::FromRatio(1, 60), 8, 3);
        PrintHash(world.Hash());
        return 0;
    }
    if (cmd == "joint-rig" && argc == 3) {
        b2World world(b2Vec2(0, -10));
        BuildRig(world);
        const int steps = std::atoi(argv[2]);
        for (int i = 0; i < steps; ++i) world.Step(Fixed::FromRatio(1, 60), 8, 3);
        PrintHash(world.Hash());
        return 0;
    }
    if (cmd == "time" && argc == 5) {
        const int steps = std::atoi(argv[3]);
        const int reps = std::atoi(argv[4]);
        if (steps < 1 || reps < 1) return Usage();
        std::vector<double> means;
        uint64 hash = 0;
        for (int r = 0; r < reps; ++r) {
            SceneRun run(argv[2]);
            if (!run.scene) return Usage();
            const auto t0 = std::chrono::steady_clock::now();
            run.Step(steps);
            const auto t1 = std::chrono::steady_clock::now();
            means.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count() / steps);
            hash = run.engine.world().Hash();
        }
        std::sort(means.begin(), means.end());
        std::printf("%.4f 0x%016" PRIx64 "\n", means[means.size() / 2], hash);
        return 0;
    }
    if (cmd == "record-divergent" && argc == 6)
        return RecordDivergent(argv[2], std::atoi(argv[3]), std::atoi(argv[4]), argv[5]);
    return Usage();
}
