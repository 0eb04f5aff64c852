#pragma once
/// @file
/// All ten joint types of the manual (one include for applications and tests).

#include "lockbox/dynamics/joints/DistanceJoint.h"
#include "lockbox/dynamics/joints/FrictionJoint.h"
#include "lockbox/dynamics/joints/GearJoint.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/dynamics/joints/MouseJoint.h"
#include "lockbox/dynamics/joints/PrismaticJoint.h"
#include "lockbox/dynamics/joints/PulleyJoint.h"
#include "lockbox/dynamics/joints/RevoluteJoint.h"
#include "lockbox/dynamics/joints/RopeJoint.h"
#include "lockbox/dynamics/joints/WeldJoint.h"
#include "lockbox/dynamics/joints/WheelJoint.h"
