// A running scene: stepping, switches, the mouse joint and recording.
#include "Simulation.h"

#include <cstdio>

#include "SceneCatalog.h"
#include "lockbox/replay/SceneGame.h"

namespace lockbox::testbed {

namespace {

scenes::RunSettings ToRunSettings(const StepSettings& s) {
    scenes::RunSettings r;
    r.velocityIterations = s.velocityIterations;
    r.positionIterations = s.positionIterations;
    r.hz = s.hz;
    r.warmStarting = s.warmStarting;
    r.continuous = s.continuous;
    r.subStepping = s.subStepping;
    r.trackMetrics = false;
    return r;
}

// Finds the first dynamic fixture containing a point (Box2D testbed's QueryCallback).
class PointQuery : public b2QueryCallback {
public:
    explicit PointQuery(const b2Vec2& p) : point_(p) {}
    bool ReportFixture(b2Fixture* fixture) override {
        if (fixture->GetBody()->GetType() != b2_dynamicBody || !fixture->TestPoint(point_)) return true;
        found = fixture;
        return false;  // the first hit will do
    }
    b2Fixture* found = nullptr;

private:
    b2Vec2 point_;
};

}  // namespace

Simulation::~Simulation() { DropRecorder(); }

StepSettings Simulation::DefaultsFor(std::string_view name, const StepSettings& base) {
    StepSettings s = base;
    if (auto scene = MakeCatalogScene(name)) {
        const scenes::SceneInfo& info = scene->Info();
        s.hz = info.hz;
        s.velocityIterations = info.velocityIterations;
        s.positionIterations = info.positionIterations;
        s.sleep = info.allowSleep;
        if (const auto* file = dynamic_cast<const scenes::SceneFileScene*>(scene.get())) {
            s.warmStarting = file->FileWorld().warmStarting;
            s.continuous = file->FileWorld().continuousPhysics;
            s.subStepping = file->FileWorld().subStepping;
        }
    }
    return s;
}

bool Simulation::Load(std::string_view name, const StepSettings& settings) {
    auto game = std::make_unique<TestbedGame>(name, ToRunSettings(settings));
    if (!game->ok()) return false;
    DropRecorder();
    mouseJoint_ = nullptr;
    mouseJointId_ = -1;
    game_ = std::move(game);
    name_ = std::string(name);
    settings_ = settings;
    frame_ = 0;
    ApplySwitches();
    hash_ = World().Hash();
    return true;
}

void Simulation::Restart() {
    if (Loaded()) Load(std::string(name_), settings_);
}

void Simulation::ApplySwitches() {
    b2World& w = World();
    // SetAllowSleeping(false) wakes every body: call it only on a change.
    if (w.GetAllowSleeping() != settings_.sleep) w.SetAllowSleeping(settings_.sleep);
    w.SetWarmStarting(settings_.warmStarting);
    w.SetContinuousPhysics(settings_.continuous);
    w.SetSubStepping(settings_.subStepping);
    w.SetHeadroomTelemetry(settings_.headroom);
}

void Simulation::Step() {
    if (!Loaded()) return;
    ApplySwitches();
    if (recorder_) {
        // The recorder applies the frame (Apply with no inputs) and steps with its settings,
        // which are this simulation's: the panel locks them while recording.
        recorder_->Advance(noInputs_);
    } else {
        game_->Apply(World(), frame_, noInputs_);
        World().Step(Fixed::FromRatio(1, settings_.hz), settings_.velocityIterations, settings_.positionIterations);
    }
    ++frame_;
    hash_ = World().Hash();
}

b2MouseJoint* Simulation::Grabbed() {
    // A body leaving the world bounds takes its joints with it: check the joint still exists.
    if (mouseJoint_ && (!Loaded() || World().GetJoint(mouseJointId_) != mouseJoint_)) {
        mouseJoint_ = nullptr;
        mouseJointId_ = -1;
    }
    return mouseJoint_;
}

bool Simulation::Grab(const b2Vec2& p) {
    if (!Loaded() || Recording() || Grabbed()) return false;
    b2World& w = World();
    // A box of +-1/1024 m around the point: the broad phase narrows, TestPoint decides.
    const Fixed d = Fixed::FromRaw(64);
    b2AABB box;
    box.lowerBound = b2Vec2(p.x - d, p.y - d);
    box.upperBound = b2Vec2(p.x + d, p.y + d);
    PointQuery query(p);
    w.QueryAABB(&query, box);
    if (!query.found) return false;
    b2Body* body = query.found->GetBody();

    // bodyA is unused by the mouse joint; any static body serves (most scenes have a ground).
    b2Body* anchor = nullptr;
    for (b2Body* b = w.GetBodyList(); b && !anchor; b = b->GetNext())
        if (b->GetType() == b2_staticBody) anchor = b;
    if (!anchor) {
        b2BodyDef def;
        anchor = w.CreateBody(&def);
    }
    b2MouseJointDef def;
    def.bodyA = anchor;
    def.bodyB = body;
    def.target = p;
    // 1000 times the body's weight per m/s^2, as Box2D's testbed (Q32.32 holds it).
    def.maxForce = body->GetMass() * Wide(1000);
    mouseJoint_ = static_cast<b2MouseJoint*>(w.CreateJoint(&def));
    if (!mouseJoint_) return false;
    mouseJointId_ = mouseJoint_->GetId();
    body->SetAwake(true);
    return true;
}

void Simulation::DragTo(const b2Vec2& p) {
    if (b2MouseJoint* j = Grabbed()) j->SetTarget(p);
}

void Simulation::Release() {
    if (b2MouseJoint* j = Grabbed()) World().DestroyJoint(j);
    mouseJoint_ = nullptr;
    mouseJointId_ = -1;
}

bool Simulation::StartRecording(const std::string& path, std::string& message) {
    if (!Loaded()) return false;
    Restart();  // a replay starts from the scene's first frame (see docs/testbed.md)
    auto sink = std::make_unique<replay::FileSink>(path);
    if (!sink->ok()) {
        message = "cannot create " + path;
        return false;
    }
    replay::RecorderConfig config;
    config.gameName = game_->GameName();
    config.gameParams = game_->GameParams();
    config.tickRate = static_cast<uint16>(settings_.hz);
    config.velocityIterations = static_cast<uint16>(settings_.velocityIterations);
    config.positionIterations = static_cast<uint16>(settings_.positionIterations);
    config.playerCount = 1;
    config.inputBytes = static_cast<uint16>(replay::SceneInput::kBytes);
    // Dense keyframes make scrubbing quick; fencepost hashes let Bisect name the stage.
    config.keyframeInterval = 60;
    config.stageHashes = true;
    auto recorder = std::make_unique<replay::Recorder>(World(), *game_, *sink, config);
    if (replay::Error e = recorder->Begin(); !e.ok()) {
        message = "recording failed: " + e.Describe();
        return false;
    }
    sink_ = std::move(sink);
    recorder_ = std::move(recorder);
    recordingPath_ = path;
    message = "recording " + name_ + " to " + path;
    return true;
}

bool Simulation::StopRecording(std::string& message) {
    if (!recorder_) return false;
    const int32 frames = recorder_->Frames();
    replay::Error e = recorder_->Finish();
    const bool closed = sink_->Close();
    recorder_.reset();
    sink_.reset();
    if (!e.ok() || !closed) {
        message = "writing " + recordingPath_ + " failed" + (e.ok() ? std::string() : ": " + e.Describe());
        return false;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, " (%d frames)", frames);
    message = "wrote " + recordingPath_ + buf;
    return true;
}

int32 Simulation::RecordedFrames() const noexcept { return recorder_ ? recorder_->Frames() : 0; }

void Simulation::DropRecorder() {
    if (!recorder_) return;
    std::string ignored;
    StopRecording(ignored);
}

}  // namespace lockbox::testbed
