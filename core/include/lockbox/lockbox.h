#pragma once
/// lockbox umbrella header (Box2D's Box2D.h): everything a user of the manual's API needs.
/// `using namespace lockbox;` then makes the manual's code read as written.

#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Math.h"

#include "lockbox/collision/BroadPhase.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/Collision.h"
#include "lockbox/collision/Distance.h"
#include "lockbox/collision/DynamicTree.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/collision/Shape.h"
#include "lockbox/collision/TimeOfImpact.h"

#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/ContactManager.h"
#include "lockbox/dynamics/Draw.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/TimeStep.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/dynamics/joints/Joints.h"
