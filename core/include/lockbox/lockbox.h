#pragma once
/// @file
/// lockbox umbrella header (Box2D's Box2D.h): everything a user of the manual's API needs.
/// `using namespace lockbox;` then makes the manual's code read as written.

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
#include "lockbox/common/Settings.h"
#include "lockbox/dynamics/Body.h"
#include "lockbox/dynamics/Draw.h"
#include "lockbox/dynamics/Fixture.h"
#include "lockbox/dynamics/Profile.h"
#include "lockbox/dynamics/StepObserver.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/WorldCallbacks.h"
#include "lockbox/dynamics/contacts/Contact.h"
#include "lockbox/dynamics/joints/Joint.h"
#include "lockbox/dynamics/joints/Joints.h"
#include "lockbox/fixed/Math.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/SyncTest.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"

/// @namespace lockbox
/// Everything of lockbox: the manual's b2 names (b2World, b2Body, b2Vec2...), the number types
/// Fixed (Q16.16) and Wide (Q32.32), and the state functions (hash, snapshot, frames, sync
/// test). The modules beside the engine have their own namespaces: lockbox::replay,
/// lockbox::net and lockbox::scenefile; scalar helpers live in lockbox::math.
