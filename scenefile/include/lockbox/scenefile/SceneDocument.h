#pragma once
/// @file
/// The scene-file document: everything a b2dJson world file says, as lockbox values. Loading
/// reads and validates the whole file into a SceneDocument before it touches a world (so a bad
/// file changes nothing), then builds the world from it; saving describes a world as a
/// SceneDocument, then writes it as JSON. Numbers are Fixed (Q16.16), or Wide (Q32.32) for mass
/// and rotational inertia, converted from the file's text with integer arithmetic only.
///
/// Order is part of the meaning: bodies, each body's fixtures and joints are listed in creation
/// order (oldest first), and a world built from a document creates them in that order, so ids,
/// list orders and the state hash follow the file.

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/scenefile/CustomProperties.h"

namespace lockbox::scenefile {

/// Name, path and custom properties of one object. b2dJson keeps a name and a path for bodies,
/// fixtures, joints and images; the world has custom properties only.
struct ObjectInfo {
    std::string name;  ///< "" when unnamed
    std::string path;  ///< b2dJson's object path; "" when none
    /// The object's custom properties (see CustomProperties).
    CustomProperties properties;
    /// True when the object carries no name, path or property.
    bool Empty() const noexcept { return name.empty() && path.empty() && properties.Empty(); }
    /// Equal name, path and properties.
    friend bool operator==(const ObjectInfo&, const ObjectInfo&) = default;
};

/// R.U.B.E.'s simulation settings, stored at the top of the file but not world state (the
/// caller passes them to b2World::Step). Zero means the file does not give them.
struct StepSettings {
    Fixed stepsPerSecond;          ///< "stepsPerSecond", Hz
    int32 velocityIterations = 0;  ///< "velocityIterations"
    int32 positionIterations = 0;  ///< "positionIterations"
    /// Equal rate and iteration counts.
    friend bool operator==(const StepSettings&, const StepSettings&) = default;

    /// The step length for b2World::Step, s: 1 / stepsPerSecond rounded to Q16.16 (1/60 s is
    /// raw 1092, as Fixed::FromRatio(1, 60)), or 1/60 s when the file gives no rate.
    Fixed TimeStep() const noexcept {
        return stepsPerSecond > Fixed() ? Fixed(1) / stepsPerSecond : Fixed::FromRatio(1, 60);
    }
    /// The file's iteration counts, or the manual's 8 and 3 when not given.
    int32 VelocityIterationsOr(int32 fallback = 8) const noexcept {
        return velocityIterations > 0 ? velocityIterations : fallback;
    }
    /// The file's position iteration count, or `fallback` (the manual's 3) when not given.
    int32 PositionIterationsOr(int32 fallback = 3) const noexcept {
        return positionIterations > 0 ? positionIterations : fallback;
    }
};

/// The world's own settings. An absent switch is false, as R.U.B.E. defines it.
struct WorldDesc {
    b2Vec2 gravity;  ///< m/s^2
    /// "allowSleep": bodies may fall asleep (b2World::SetAllowSleeping).
    bool allowSleep = false;
    /// "autoClearForces": each Step clears the applied forces (b2World::SetAutoClearForces).
    bool autoClearForces = false;
    /// "warmStarting": the solver starts from the previous step's impulses
    /// (b2World::SetWarmStarting).
    bool warmStarting = false;
    /// "continuousPhysics": time of impact against fast bodies (b2World::SetContinuousPhysics).
    bool continuousPhysics = false;
    /// "subStepping": time-of-impact sub-stepping (b2World::SetSubStepping).
    bool subStepping = false;
    /// R.U.B.E.'s step settings (not world state: the caller passes them to b2World::Step).
    StepSettings step;
    ObjectInfo info;  ///< the world's custom properties (name and path unused)
};

/// A fixture's shape: one of the four concrete shapes, already validated by the engine's own
/// setters (b2PolygonShape::Set and friends).
using ShapeDesc = std::variant<b2CircleShape, b2PolygonShape, b2EdgeShape, b2ChainShape>;

/// One fixture. `def.shape` is left null: the shape is `shape`, bound when the world is built.
struct FixtureDesc {
    /// The fixture's material, filter and sensor flag (friction, restitution, density in kg/m^2);
    /// shape null.
    b2FixtureDef def;
    /// The fixture's shape, in the body's frame (m).
    ShapeDesc shape;
    /// The fixture's name, path and custom properties.
    ObjectInfo info;
};

/// One body with its fixtures (creation order).
struct BodyDesc {
    b2BodyDef def;  ///< linearVelocity is the velocity the built body reports (see docs/scene-files.md)
    /// The body's fixtures, in creation order (oldest first).
    std::vector<FixtureDesc> fixtures;
    /// The mass-data override ("massData-mass", "-center", "-I"), applied after the fixtures
    /// with b2Body::SetMassData; absent: the mass the fixtures give.
    std::optional<b2MassData> massData;
    /// The body's name, path and custom properties.
    ObjectInfo info;
};

/// The joint definitions of Box2D 2.2.1, one alternative per joint type.
using JointDefDesc =
    std::variant<b2RevoluteJointDef, b2PrismaticJointDef, b2DistanceJointDef, b2PulleyJointDef, b2MouseJointDef,
                 b2GearJointDef, b2WheelJointDef, b2WeldJointDef, b2FrictionJointDef, b2RopeJointDef>;

/// One joint. The definition's body and joint pointers stay null in the document: bodies and
/// geared joints are named by their index in the document's lists.
struct JointDesc {
    /// The joint's definition (the alternative tells the type); body and joint pointers stay null.
    JointDefDesc def;
    int32 bodyA = -1;    ///< index into SceneDocument::bodies
    int32 bodyB = -1;    ///< index into SceneDocument::bodies
    int32 joint1 = -1;   ///< gear joints: index into SceneDocument::joints of a revolute or prismatic joint
    int32 joint2 = -1;   ///< gear joints: the second geared joint
    b2Vec2 mouseTarget;  ///< mouse joints: the target (def.target holds the grab point, b2dJson's "anchorB")
    /// The joint's name, path and custom properties.
    ObjectInfo info;
};

/// An image entry (R.U.B.E.'s "image"): data for the game's renderer, ignored by physics.
struct ImageDesc {
    int32 body = -1;  ///< document: index into bodies; SceneMetadata: the body's id; -1: none
    /// The image file the renderer loads (as written in the scene file; lockbox never opens it).
    std::string file;
    b2Vec2 center;  ///< m, in the body's frame (the world's when no body)
    Fixed angle;    ///< rad
    Fixed scale;    ///< height, m
    /// Multiplier of the image file's own width-to-height ratio (1 keeps its proportions).
    Fixed aspectScale = 1;
    /// Mirrors the image horizontally.
    bool flip = false;
    /// Opacity, 0 (transparent) to 1 (opaque).
    Fixed opacity;
    int32 filter = 1;  ///< 0 nearest, 1 linear (b2dJson's default)
    /// Drawing order: higher values are drawn on top.
    Fixed renderOrder;
    std::array<int32, 4> colorTint{255, 255, 255, 255};  ///< RGBA, 0..255
    std::vector<b2Vec2> corners;                         ///< the four corners, m
    std::vector<Fixed> glVertexPointer;                  ///< x, y pairs, m
    std::vector<Fixed> glTexCoordPointer;                ///< u, v pairs
    std::vector<int32> glDrawElements;                   ///< triangle indices, 0..65535
    /// The image's name, path and custom properties.
    ObjectInfo info;
    /// Field-wise equality.
    friend bool operator==(const ImageDesc&, const ImageDesc&) = default;
};

/// A whole scene file.
struct SceneDocument {
    /// The world's gravity, switches, step settings and custom properties.
    WorldDesc world;
    /// Every body with its fixtures, in creation order (oldest first).
    std::vector<BodyDesc> bodies;
    /// Every joint, in creation order; a gear joint naming a joint later in the list is built after
    /// all the others.
    std::vector<JointDesc> joints;
    /// The images, in file order.
    std::vector<ImageDesc> images;
};

/// b2dJson's name of a joint type ("revolute", "gear", ...); nullptr for e_unknownJoint.
LOCKBOX_API const char* JointTypeName(b2JointType type) noexcept;

/// The joint type a JointDefDesc holds.
LOCKBOX_API b2JointType JointDescType(const JointDefDesc& def) noexcept;

}  // namespace lockbox::scenefile
