#pragma once
/// The lockbox engine adapter for the scene templates (see Scene.h for the contract).
///
/// lockbox has every joint type, so each `kHas...` flag is true; the flags exist for the
/// adapter contract (Scene.h), which lets a scene skip a joint type an engine lacks.

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <type_traits>

#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/lockbox.h"

namespace lockbox::scenes {

/// Scene adapter over a lockbox b2World (gravity (0, -10)).
class LockboxEngine {
public:
    using Num = Fixed;
    using Vec = b2Vec2;
    using World = b2World;
    using Body = b2Body;
    using BodyDef = b2BodyDef;
    using Fixture = b2Fixture;
    using FixtureDef = b2FixtureDef;
    using PolygonShape = b2PolygonShape;
    using CircleShape = b2CircleShape;
    using EdgeShape = b2EdgeShape;
    using ChainShape = b2ChainShape;
    using Contact = b2Contact;
    using Manifold = b2Manifold;
    using WorldManifold = b2WorldManifold;
    using Joint = b2Joint;
    static constexpr b2BodyType kStatic = b2_staticBody;
    static constexpr b2BodyType kDynamic = b2_dynamicBody;
    static constexpr b2BodyType kKinematic = b2_kinematicBody;
    static constexpr const char* kName = "lockbox";

    // Joint availability (see the file comment).
    static constexpr bool kHasJoints = true;
    static constexpr bool kHasRevolute = true;
    static constexpr bool kHasPrismatic = true;
    static constexpr bool kHasWheel = true;
    static constexpr bool kHasPulley = true;
    static constexpr bool kHasGear = true;
    using RevoluteJointDef = b2RevoluteJointDef;
    using PrismaticJointDef = b2PrismaticJointDef;
    using WheelJointDef = b2WheelJointDef;
    using PulleyJointDef = b2PulleyJointDef;
    using GearJointDef = b2GearJointDef;

    /// num/den rounded once to Q16.16 (to nearest, ties away from zero).
    static Num R(int64_t num, int64_t den = 1) noexcept { return Fixed::FromRatio(num, den); }
    /// For display and metrics only.
    static double D(Num v) noexcept { return v.ToDouble(); }
    /// A vector from two numbers.
    static Vec V(Num x, Num y) noexcept { return Vec(x, y); }
    /// num/den degrees in radians, rounded once: num * pi / (180 den), with pi carried as
    /// round(pi * 2^32) = 13493037705 (so the ratio is num * pi * 2^32 / (180 den 2^32) and
    /// the only rounding is FromRatio's). Valid for |num| <= 3 * 10^8 (the numerator stays
    /// below 2^62).
    static Num Deg(int64_t num, int64_t den = 1) noexcept {
        constexpr int64_t kPi32 = 13493037705;  // pi * 2^32, rounded
        constexpr int64_t kTwo32 = int64_t{1} << 32;
        return Fixed::FromRatio(num * kPi32, 180 * den * kTwo32);
    }
    /// A two-sided edge v1-v2 (2.2.1 `Set`).
    static void SetEdge(EdgeShape& edge, const Vec& v1, const Vec& v2) { edge.Set(v1, v2); }
    /// An open chain through count vertices (2.2.1 `CreateChain`, no ghost vertices).
    static void CreateChain(ChainShape& chain, const Vec* vertices, int count) { chain.CreateChain(vertices, count); }
    /// The wheel suspension spring: frequency (Hz) and damping ratio (2.2.1 fields).
    static void SetWheelSpring(WheelJointDef& def, Num hz, Num dampingRatio) {
        def.frequencyHz = hz;
        def.dampingRatio = dampingRatio;
    }

    /// Sets a joint's maxMotorTorque (N m) from an integer; a Q16.16 field saturates at its
    /// largest value (32767.99998 N m), a Q32.32 field takes it exactly.
    template <class Def>
    static void SetMaxMotorTorque(Def& def, int64_t newtonMetres) {
        using T = std::remove_cvref_t<decltype(def.maxMotorTorque)>;
        if constexpr (std::is_same_v<T, Fixed>) {
            def.maxMotorTorque = newtonMetres > 32767 ? Fixed::FromRaw(std::numeric_limits<int32_t>::max())
                                                      : Fixed(static_cast<int32_t>(newtonMetres));
        } else {
            def.maxMotorTorque = T(newtonMetres);
        }
    }

    /// A fresh world with gravity (0, -10) m/s^2.
    LockboxEngine() : world_(std::make_unique<b2World>(b2Vec2(0, -10))) {}
    LockboxEngine(const LockboxEngine&) = delete;
    LockboxEngine& operator=(const LockboxEngine&) = delete;

    /// The world.
    World& world() noexcept { return *world_; }
    /// The time step for a frequency: round(65536 / hz) / 65536 s (1/60 s is raw 1092).
    static Num TimeStep(int hz) noexcept { return Fixed::FromRatio(1, hz); }
    /// One world step at hz steps per second.
    void Step(int hz, int velocityIterations, int positionIterations) {
        world_->Step(TimeStep(hz), velocityIterations, positionIterations);
    }
    /// Creates a joint from a definition (engines differ only in the return type).
    /// (W is a dependent alias of b2World, so this compiles before the world has joints.)
    template <class Def, class W = b2World>
    Joint* CreateJoint(const Def& def) {
        W& w = *world_;
        return w.CreateJoint(&def);
    }

    /// Called on BeginContact when set (install with InstallListener).
    std::function<void(Contact*)> onBeginContact;
    /// Called on PreSolve when set (install with InstallListener).
    std::function<void(Contact*, const Manifold*)> onPreSolve;
    /// Registers the forwarding listener with the world (only scenes with hooks call this,
    /// so other scenes run without callback overhead).
    void InstallListener() { world_->SetContactListener(&listener_); }

private:
    class Forwarder : public b2ContactListener {
    public:
        explicit Forwarder(LockboxEngine* owner) : owner_(owner) {}
        void BeginContact(b2Contact* c) override {
            if (owner_->onBeginContact) owner_->onBeginContact(c);
        }
        void PreSolve(b2Contact* c, const b2Manifold* old) override {
            if (owner_->onPreSolve) owner_->onPreSolve(c, old);
        }

    private:
        LockboxEngine* owner_;
    };
    std::unique_ptr<b2World> world_;
    Forwarder listener_{this};
};

/// The world's stage timers (b2World::SetProfileTimers) for a run.
inline void SetProfileTimers(LockboxEngine& e, bool on) { e.world().SetProfileTimers(on); }

}  // namespace lockbox::scenes
