// One "joint" entry: the ten joint types of Box2D 2.2.1 with b2dJson's field names (local
// anchors "anchorA"/"anchorB", "refAngle", limits "lowerLimit"/"upperLimit", ...), absent
// values zero or false. Ranges the engine documents are checked here: non-negative forces and
// torques, spring frequencies within 0..30 Hz, a positive pulley ratio, a non-zero axis.
#include "Sections.h"

namespace lockbox::scenefile::detail {

namespace {

// Every field any joint type reads; the type picks its own.
enum Field : size_t {
    kType,
    kName,
    kPath,
    kBodyA,
    kBodyB,
    kCollide,
    kProps,
    kAnchorA,
    kAnchorB,
    kRefAngle,
    kEnableLimit,
    kLower,
    kUpper,
    kEnableMotor,
    kMotorSpeed,
    kMaxMotorTorque,
    kAxis,
    kAxisOld,
    kMaxMotorForce,
    kLength,
    kFrequency,
    kDamping,
    kGroundA,
    kGroundB,
    kLengthA,
    kLengthB,
    kRatio,
    kTarget,
    kMaxForce,
    kJoint1,
    kJoint2,
    kSpringFrequency,
    kSpringDamping,
    kMaxTorque,
    kMaxLength,
    kFieldCount
};

constexpr std::array<std::string_view, kFieldCount> kNames{"type",
                                                           "name",
                                                           "path",
                                                           "bodyA",
                                                           "bodyB",
                                                           "collideConnected",
                                                           "customProperties",
                                                           "anchorA",
                                                           "anchorB",
                                                           "refAngle",
                                                           "enableLimit",
                                                           "lowerLimit",
                                                           "upperLimit",
                                                           "enableMotor",
                                                           "motorSpeed",
                                                           "maxMotorTorque",
                                                           "localAxisA",
                                                           "localAxis1",
                                                           "maxMotorForce",
                                                           "length",
                                                           "frequency",
                                                           "dampingRatio",
                                                           "groundAnchorA",
                                                           "groundAnchorB",
                                                           "lengthA",
                                                           "lengthB",
                                                           "ratio",
                                                           "target",
                                                           "maxForce",
                                                           "joint1",
                                                           "joint2",
                                                           "springFrequency",
                                                           "springDampingRatio",
                                                           "maxTorque",
                                                           "maxLength"};

constexpr Fixed kMaxFrequency = 30;  // Hz: the range docs/joints.md gives the soft constraints

// Reads the fields of one joint entry with their paths.
class JointFields {
public:
    JointFields(SceneReader& reader, const Path& at, const std::array<const JsonNode*, kFieldCount>& members)
        : r(reader), path(at), m(members) {}

    Path At(Field f) const { return path.Member(kNames[f]); }
    bool Fixed_(Field f, Fixed& v) { return r.ReadFixed(m[f], At(f), v); }
    bool NonNegative(Field f, Fixed& v) { return Fixed_(f, v) && r.NonNegative(v, m[f], At(f)); }
    bool Vec(Field f, b2Vec2& v) { return r.ReadVec(m[f], At(f), v); }
    /// A point in a body's frame (an anchor): within the shapes' coordinate range.
    bool Local(Field f, b2Vec2& v) { return Vec(f, v) && r.WithinVec(v, b2_maxShapeCoordinate, At(f), "m", kLocalWhy); }
    /// A reference angle, rad.
    bool Angle(Field f, Fixed& v) { return Fixed_(f, v) && r.Within(v, kMaxFileAngle, m[f], At(f), "rad", kAngleWhy); }
    /// A revolute limit, rad (RevoluteJoint.h: |value| <= 16000).
    bool AngleLimit(Field f, Fixed& v) {
        return Fixed_(f, v) && r.Within(v, Fixed(16000), m[f], At(f), "rad", "the revolute joint's limit range");
    }
    bool Bool(Field f, bool& v) { return r.ReadBool(m[f], At(f), v); }
    bool Frequency(Field f, Fixed& v, bool positive) {
        if (!Fixed_(f, v)) return false;
        if (v > kMaxFrequency || v < Fixed() || (positive && v == Fixed())) {
            return r.Fail(At(f), SceneError::e_range,
                          (m[f] ? r.Quote(*m[f]) : std::string("0")) + " Hz is outside the engine's range " +
                              (positive ? "(0, 30]" : "[0, 30]"));
        }
        return true;
    }
    bool Limits(bool enabled, Fixed lower, Fixed upper) {
        if (!enabled || lower <= upper) return true;
        return r.Fail(At(kLower), SceneError::e_range, "the lower limit is above the upper limit");
    }
    bool Axis(b2Vec2& axis) {
        // Older files call the prismatic axis "localAxis1".
        const Field f = SceneReader::Absent(m[kAxis]) && !SceneReader::Absent(m[kAxisOld]) ? kAxisOld : kAxis;
        if (!Vec(f, axis)) return false;
        if (axis.x != Fixed() || axis.y != Fixed()) return true;
        return r.Fail(At(f), SceneError::e_range, "the axis is the zero vector");
    }

    SceneReader& r;
    const Path& path;
    const std::array<const JsonNode*, kFieldCount>& m;
};

bool LoadTyped(JointFields& f, std::string_view type, JointDesc& out) {
    if (type == "revolute") {
        b2RevoluteJointDef d;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.Angle(kRefAngle, d.referenceAngle) || !f.Bool(kEnableLimit, d.enableLimit) ||
            !f.AngleLimit(kLower, d.lowerAngle) || !f.AngleLimit(kUpper, d.upperAngle) ||
            !f.Bool(kEnableMotor, d.enableMotor) || !f.Fixed_(kMotorSpeed, d.motorSpeed) ||
            !f.NonNegative(kMaxMotorTorque, d.maxMotorTorque) || !f.Limits(d.enableLimit, d.lowerAngle, d.upperAngle)) {
            return false;
        }
        out.def = d;
    } else if (type == "prismatic") {
        b2PrismaticJointDef d;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) || !f.Axis(d.localAxisA) ||
            !f.Angle(kRefAngle, d.referenceAngle) || !f.Bool(kEnableLimit, d.enableLimit) ||
            !f.Fixed_(kLower, d.lowerTranslation) || !f.Fixed_(kUpper, d.upperTranslation) ||
            !f.Bool(kEnableMotor, d.enableMotor) || !f.Fixed_(kMotorSpeed, d.motorSpeed) ||
            !f.NonNegative(kMaxMotorForce, d.maxMotorForce) ||
            !f.Limits(d.enableLimit, d.lowerTranslation, d.upperTranslation)) {
            return false;
        }
        out.def = d;
    } else if (type == "distance") {
        b2DistanceJointDef d;
        d.length = 0;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.NonNegative(kLength, d.length) || !f.Frequency(kFrequency, d.frequencyHz, false) ||
            !f.NonNegative(kDamping, d.dampingRatio)) {
            return false;
        }
        out.def = d;
    } else if (type == "pulley") {
        b2PulleyJointDef d;
        d.collideConnected = false;
        d.ratio = 0;
        if (!f.Vec(kGroundA, d.groundAnchorA) || !f.Vec(kGroundB, d.groundAnchorB) ||
            !f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.NonNegative(kLengthA, d.lengthA) || !f.NonNegative(kLengthB, d.lengthB) || !f.Fixed_(kRatio, d.ratio)) {
            return false;
        }
        if (d.ratio <= Fixed()) return f.r.Fail(f.At(kRatio), SceneError::e_range, "a pulley ratio must be positive");
        // The joint keeps lengthA + ratio * lengthB as one Q16.16 value: it must fit.
        const int64_t total = int64_t{d.lengthA.Raw()} +
                              ((int64_t{d.ratio.Raw()} * d.lengthB.Raw() + (int64_t{1} << 15)) >> Fixed::kFractionBits);
        if (total > Fixed::kMaxRaw) {
            return f.r.Fail(f.path, SceneError::e_range,
                            "lengthA + ratio * lengthB does not fit Q16.16 (32767.99998 m)");
        }
        out.def = d;
    } else if (type == "mouse") {
        b2MouseJointDef d;
        d.frequencyHz = 0;
        d.dampingRatio = 0;
        // b2dJson: "anchorB" is the grab point (world), "target" where it is pulled to.
        if (!f.Vec(kTarget, out.mouseTarget) || !f.Vec(kAnchorB, d.target) ||
            !f.r.ReadWide(f.m[kMaxForce], f.At(kMaxForce), d.maxForce) ||
            !f.Frequency(kFrequency, d.frequencyHz, true) || !f.NonNegative(kDamping, d.dampingRatio)) {
            return false;
        }
        if (d.maxForce < Wide()) return f.r.Fail(f.At(kMaxForce), SceneError::e_range, "the force is negative");
        out.def = d;
    } else if (type == "gear") {
        b2GearJointDef d;
        d.ratio = 0;
        if (!f.r.ReadInt(f.m[kJoint1], f.At(kJoint1), INT32_MIN, INT32_MAX, out.joint1) ||
            !f.r.ReadInt(f.m[kJoint2], f.At(kJoint2), INT32_MIN, INT32_MAX, out.joint2) || !f.Fixed_(kRatio, d.ratio)) {
            return false;
        }
        out.def = d;
    } else if (type == "wheel") {
        b2WheelJointDef d;
        d.frequencyHz = 0;
        d.dampingRatio = 0;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) || !f.Axis(d.localAxisA) ||
            !f.Bool(kEnableMotor, d.enableMotor) || !f.Fixed_(kMotorSpeed, d.motorSpeed) ||
            !f.NonNegative(kMaxMotorTorque, d.maxMotorTorque) || !f.Frequency(kSpringFrequency, d.frequencyHz, false) ||
            !f.NonNegative(kSpringDamping, d.dampingRatio)) {
            return false;
        }
        out.def = d;
    } else if (type == "weld") {
        b2WeldJointDef d;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.Angle(kRefAngle, d.referenceAngle) || !f.Frequency(kFrequency, d.frequencyHz, false) ||
            !f.NonNegative(kDamping, d.dampingRatio)) {
            return false;
        }
        out.def = d;
    } else if (type == "friction") {
        b2FrictionJointDef d;
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.NonNegative(kMaxForce, d.maxForce) || !f.NonNegative(kMaxTorque, d.maxTorque)) {
            return false;
        }
        out.def = d;
    } else if (type == "rope") {
        b2RopeJointDef d;
        d.localAnchorA.SetZero();
        d.localAnchorB.SetZero();
        if (!f.Local(kAnchorA, d.localAnchorA) || !f.Local(kAnchorB, d.localAnchorB) ||
            !f.NonNegative(kMaxLength, d.maxLength)) {
            return false;
        }
        out.def = d;
    } else if (type == "motor") {
        return f.r.Fail(f.At(kType), SceneError::e_type,
                        "\"motor\" joints came with Box2D 2.3; lockbox has the joints of 2.2.1");
    } else {
        return f.r.Fail(f.At(kType), SceneError::e_type,
                        "unknown joint type \"" + std::string(type.substr(0, 40)) +
                            "\" (revolute, prismatic, distance, pulley, mouse, gear, wheel, weld, friction, rope)");
    }
    return true;
}

}  // namespace

bool LoadJoint(SceneReader& r, const JsonNode& n, const Path& path, int32 bodyCount, JointDesc& out) {
    std::array<const JsonNode*, kFieldCount> m;
    if (!r.Members(n, path, kNames, m)) return false;
    out = JointDesc();
    std::string type;
    if (!r.ReadString(m[kType], path.Member("type"), type)) return false;
    if (type.empty()) return r.Fail(path, SceneError::e_type, "a joint needs a \"type\"");
    out.bodyA = 0;
    out.bodyB = 0;
    bool collide = false;
    if (!r.ReadInfo(m[kName], m[kPath], m[kProps], path, out.info) ||
        !r.ReadInt(m[kBodyA], path.Member("bodyA"), INT32_MIN, INT32_MAX, out.bodyA) ||
        !r.ReadInt(m[kBodyB], path.Member("bodyB"), INT32_MIN, INT32_MAX, out.bodyB) ||
        !r.ReadBool(m[kCollide], path.Member("collideConnected"), collide)) {
        return false;
    }
    JointFields fields(r, path, m);
    if (!LoadTyped(fields, type, out)) return false;
    // b2dJson checks both body indices of every joint, gears included.
    if (out.bodyA < 0 || out.bodyA >= bodyCount) {
        return r.Fail(path.Member("bodyA"), SceneError::e_reference, IndexMessage(out.bodyA, bodyCount, "bodies"));
    }
    if (out.bodyB < 0 || out.bodyB >= bodyCount) {
        return r.Fail(path.Member("bodyB"), SceneError::e_reference, IndexMessage(out.bodyB, bodyCount, "bodies"));
    }
    const bool gear = std::holds_alternative<b2GearJointDef>(out.def);
    if (!gear && out.bodyA == out.bodyB) {
        return r.Fail(path.Member("bodyB"), SceneError::e_reference,
                      "bodyA and bodyB are both body " + std::to_string(out.bodyA) + "; a joint joins two bodies");
    }
    std::visit([&](auto& d) { d.collideConnected = collide; }, out.def);
    return true;
}

bool CheckGearJoints(SceneReader& r, const Path& jointsPath, const std::vector<JointDesc>& joints) {
    const auto count = static_cast<int32>(joints.size());
    for (int32 i = 0; i < count; ++i) {
        const JointDesc& j = joints[static_cast<size_t>(i)];
        if (!std::holds_alternative<b2GearJointDef>(j.def)) continue;
        const Path p = jointsPath.Index(i);
        for (int k = 0; k < 2; ++k) {
            const int32 ref = k == 0 ? j.joint1 : j.joint2;
            const Path rp = p.Member(k == 0 ? "joint1" : "joint2");
            if (ref < 0 || ref >= count) return r.Fail(rp, SceneError::e_reference, IndexMessage(ref, count, "joints"));
            const b2JointType t = JointDescType(joints[static_cast<size_t>(ref)].def);
            if (t != e_revoluteJoint && t != e_prismaticJoint) {
                return r.Fail(rp, SceneError::e_reference,
                              "joint " + std::to_string(ref) + " is a " + JointTypeName(t) +
                                  " joint; a gear couples revolute and prismatic joints");
            }
        }
    }
    return true;
}

}  // namespace lockbox::scenefile::detail
