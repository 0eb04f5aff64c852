// Joint type names of the b2dJson format.
#include "lockbox/scenefile/SceneDocument.h"

namespace lockbox::scenefile {

const char* JointTypeName(b2JointType type) noexcept {
    switch (type) {
        case e_revoluteJoint: return "revolute";
        case e_prismaticJoint: return "prismatic";
        case e_distanceJoint: return "distance";
        case e_pulleyJoint: return "pulley";
        case e_mouseJoint: return "mouse";
        case e_gearJoint: return "gear";
        case e_wheelJoint: return "wheel";
        case e_weldJoint: return "weld";
        case e_frictionJoint: return "friction";
        case e_ropeJoint: return "rope";
        case e_unknownJoint: break;
    }
    return nullptr;
}

b2JointType JointDescType(const JointDefDesc& def) noexcept {
    return std::visit([](const auto& d) { return d.type; }, def);
}

}  // namespace lockbox::scenefile
