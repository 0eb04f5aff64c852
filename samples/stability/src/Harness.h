#pragma once
// Shared pieces of the stability cases: a world with headroom telemetry, a few builders, and
// display-only measurements (doubles read from the world, never written back).

#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/lockbox.h"
#include "lockbox/stability/Cases.h"

namespace lockbox::stability::detail {

using namespace lockbox::literals;

/// The suite's time step: 1/60 s rounded to Q16.16 (raw 1092), as the scene library uses.
inline constexpr Fixed kDt = Fixed::FromRaw(1092);
/// Steps per simulated second at kDt (display and loop counts).
inline constexpr int kHz = 60;

/// A world whose every step feeds the case's headroom and step count.
class Sim {
public:
    /// A world with the given gravity (m/s^2), telemetry on, reporting into r.
    Sim(CaseReport& r, const b2Vec2& gravity = b2Vec2(0, -10));
    Sim(const Sim&) = delete;
    Sim& operator=(const Sim&) = delete;

    /// The world (gravity as constructed, telemetry on).
    b2World& world() noexcept { return *world_; }
    /// One step of kDt with the given iterations.
    void Step(int velocityIterations = 8, int positionIterations = 3);

    /// A static body at the origin with a box of half-extents hx, hy centred at (cx, cy).
    b2Body* GroundBox(Fixed hx, Fixed hy, const b2Vec2& center = b2Vec2());
    /// A static body at the origin with one two-sided edge.
    b2Body* GroundEdge(const b2Vec2& a, const b2Vec2& b);
    /// A dynamic body at p with one box (half-extents hx, hy) of the given density.
    b2Body* Box(const b2Vec2& p, Fixed hx, Fixed hy, Fixed density, Fixed friction = Fixed::FromRaw(39322));
    /// A dynamic body at p with one circle of radius r and the given density.
    b2Body* Ball(const b2Vec2& p, Fixed r, Fixed density, Fixed friction = Fixed::FromRaw(39322),
                 Fixed restitution = Fixed());

private:
    CaseReport& report_;
    std::unique_ptr<b2World> world_;
};

/// Value as a double (display only).
inline double D(Fixed v) noexcept { return v.ToDouble(); }
inline double D(Wide v) noexcept { return v.ToDouble(); }

/// Largest linear speed over dynamic bodies, m/s.
double MaxSpeed(const b2World& w);
/// Largest penetration over touching enabled contacts, m (0 when none).
double MaxPenetration(b2World& w);
/// True when no dynamic body is awake.
bool AllAsleep(const b2World& w);
/// Total mechanical energy with gravity g (m/s^2, downward), J: kinetic + potential.
double Energy(const b2World& w, double g);

/// Appends a result "value <= limit" to r.
void Check(CaseReport& r, std::string_view metric, double value, double limit, bool limitation = false);

/// Step between the starts of a chaotic case's ensemble: start k moves one body sideways by
/// k * kEnsembleShift. 11 raw units (0.17 mm): 64 starts span 11 mm.
constexpr Fixed kEnsembleShift = Fixed::FromRaw(11);

/// Runs `run(shift)` for `starts` starts (shift = k * kEnsembleShift, k = 0 .. starts - 1) and
/// returns, per figure, the median over the starts. `run` returns its figures in a fixed
/// order. Used where one run's figure depends on sub-millimetre detail (a toppling stack, a
/// bouncing pile): a single start then judges the luck of one rounding, the median the engine.
std::vector<double> EnsembleMedians(int starts, const std::function<std::vector<double>(Fixed shift)>& run);

// ---- the cases (one function per case; each file documents its limits) ----
void TallStack(CaseReport& r, Budget b);
void Pyramids(CaseReport& r, Budget b);
void TinyBodies(CaseReport& r, Budget b);
void LargeBodies(CaseReport& r, Budget b);
void MassRatios(CaseReport& r, Budget b);
void WreckingBall(CaseReport& r, Budget b);
void Bullets(CaseReport& r, Budget b);
void OverlapRecovery(CaseReport& r, Budget b);
void FarFromOrigin(CaseReport& r, Budget b);
void LongRuns(CaseReport& r, Budget b);
void RestitutionPile(CaseReport& r, Budget b);
void DegenerateInput(CaseReport& r, Budget b);
void PulleyGear(CaseReport& r, Budget b);
void SoftJoints(CaseReport& r, Budget b);
void SleepThreshold(CaseReport& r, Budget b);

}  // namespace lockbox::stability::detail
