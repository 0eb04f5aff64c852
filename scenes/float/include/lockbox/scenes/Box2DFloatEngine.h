#pragma once
/// The float Box2D 2.4.1 adapter for the scene templates (see lockbox/scenes/Scene.h for the
/// contract). It runs the same scene definitions as lockbox, at the same time step: 1/hz is
/// rounded to Q16.16 first (1/60 s is 1092/65536 s) and that exact value is the float dt.
/// Box2D's names here are global (::b2World, ...); lockbox's live in namespace lockbox.

// Box2D 2.4.1 defines b2_pi, b2_linearSlop, ... as macros, which would break any lockbox
// header parsed after it: the lockbox side (with every joint header it uses) comes first.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "Box2DFloat.h"  // float Box2D without its constant macros
#include "lockbox/scenes/LockboxScenes.h"

namespace lockbox::scenes {

/// Scene adapter over a float Box2D 2.4.1 b2World (gravity (0, -10)).
class Box2DFloatEngine {
public:
    using Num = float;
    using Vec = ::b2Vec2;
    using World = ::b2World;
    using Body = ::b2Body;
    using BodyDef = ::b2BodyDef;
    using Fixture = ::b2Fixture;
    using FixtureDef = ::b2FixtureDef;
    using PolygonShape = ::b2PolygonShape;
    using CircleShape = ::b2CircleShape;
    using EdgeShape = ::b2EdgeShape;
    using ChainShape = ::b2ChainShape;
    using Contact = ::b2Contact;
    using Manifold = ::b2Manifold;
    using WorldManifold = ::b2WorldManifold;
    using Joint = ::b2Joint;
    using RevoluteJointDef = ::b2RevoluteJointDef;
    using PrismaticJointDef = ::b2PrismaticJointDef;
    using WheelJointDef = ::b2WheelJointDef;
    using PulleyJointDef = ::b2PulleyJointDef;
    using GearJointDef = ::b2GearJointDef;
    static constexpr ::b2BodyType kStatic = ::b2_staticBody;
    static constexpr ::b2BodyType kDynamic = ::b2_dynamicBody;
    static constexpr ::b2BodyType kKinematic = ::b2_kinematicBody;
    static constexpr const char* kName = "box2d-float";
    static constexpr bool kHasJoints = true;
    static constexpr bool kHasRevolute = true;
    static constexpr bool kHasPrismatic = true;
    static constexpr bool kHasWheel = true;
    static constexpr bool kHasPulley = true;
    static constexpr bool kHasGear = true;

    /// num/den as the nearest float (through double).
    static Num R(int64_t num, int64_t den = 1) noexcept {
        return static_cast<float>(static_cast<double>(num) / static_cast<double>(den));
    }
    /// For display and metrics.
    static double D(Num v) noexcept { return v; }
    /// A vector from two numbers.
    static Vec V(Num x, Num y) noexcept { return Vec(x, y); }
    /// num/den degrees in radians.
    static Num Deg(int64_t num, int64_t den = 1) noexcept {
        return static_cast<float>(static_cast<double>(num) / static_cast<double>(den) * 3.14159265358979323846 / 180.0);
    }
    /// A two-sided edge v1-v2 (2.4.1 `SetTwoSided`).
    static void SetEdge(EdgeShape& edge, const Vec& v1, const Vec& v2) { edge.SetTwoSided(v1, v2); }
    /// An open chain. 2.2.1 chains are two-sided; 2.4.1 chains are one-sided and collide only
    /// on the right of their direction. Scenes give terrain left to right with the solid side
    /// below, so the adapter reverses the vertices (solid side down, open side up) and adds
    /// ghost vertices continuing the end segments.
    static void CreateChain(ChainShape& chain, const Vec* vertices, int count) {
        std::vector<Vec> v(vertices, vertices + count);
        std::reverse(v.begin(), v.end());
        const Vec prev = v[0] + (v[0] - v[1]);
        const Vec next = v[count - 1] + (v[count - 1] - v[count - 2]);
        chain.CreateChain(v.data(), count, prev, next);
    }
    /// The wheel suspension spring from frequency (Hz) and damping ratio (2.4.1 stiffness and
    /// damping; call after Initialize so the bodies are set).
    static void SetWheelSpring(WheelJointDef& def, Num hz, Num dampingRatio) {
        ::b2LinearStiffness(def.stiffness, def.damping, hz, dampingRatio, def.bodyA, def.bodyB);
    }
    /// Sets a joint's maxMotorTorque (N m).
    template <class Def>
    static void SetMaxMotorTorque(Def& def, int64_t newtonMetres) {
        def.maxMotorTorque = static_cast<float>(newtonMetres);
    }

    /// A fresh world with gravity (0, -10) m/s^2.
    Box2DFloatEngine() : world_(std::make_unique<::b2World>(::b2Vec2(0, -10))) {}
    Box2DFloatEngine(const Box2DFloatEngine&) = delete;
    Box2DFloatEngine& operator=(const Box2DFloatEngine&) = delete;

    /// The world.
    World& world() noexcept { return *world_; }
    /// The time step for a frequency: lockbox's Q16.16 step, round(65536 / hz) / 65536 s.
    static float TimeStep(int hz) noexcept { return static_cast<float>((65536 + hz / 2) / hz) / 65536.0f; }
    /// One world step at hz steps per second.
    void Step(int hz, int velocityIterations, int positionIterations) {
        world_->Step(TimeStep(hz), velocityIterations, positionIterations);
    }
    /// Creates a joint from a definition.
    template <class Def>
    Joint* CreateJoint(const Def& def) {
        return world_->CreateJoint(&def);
    }

    /// Called on BeginContact when set (install with InstallListener).
    std::function<void(Contact*)> onBeginContact;
    /// Called on PreSolve when set (install with InstallListener).
    std::function<void(Contact*, const Manifold*)> onPreSolve;
    /// Registers the forwarding listener with the world.
    void InstallListener() { world_->SetContactListener(&listener_); }

private:
    class Forwarder : public ::b2ContactListener {
    public:
        explicit Forwarder(Box2DFloatEngine* owner) : owner_(owner) {}
        void BeginContact(::b2Contact* c) override {
            if (owner_->onBeginContact) owner_->onBeginContact(c);
        }
        void PreSolve(::b2Contact* c, const ::b2Manifold* old) override {
            if (owner_->onPreSolve) owner_->onPreSolve(c, old);
        }

    private:
        Box2DFloatEngine* owner_;
    };
    std::unique_ptr<::b2World> world_;
    Forwarder listener_{this};
};

/// Float Box2D 2.4.1 always times its stages: the switch has nothing to turn off.
inline void SetProfileTimers(Box2DFloatEngine&, bool) {}

}  // namespace lockbox::scenes
