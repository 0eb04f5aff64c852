#pragma once
/// @file
/// The manual's Math module on Q16.16: b2Vec2, b2Vec3, b2Mat22, b2Mat33, b2Rot, b2Transform,
/// b2Sweep and the free functions, plus Fixed, Wide and the scalar functions.

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Functions.h"
#include "lockbox/fixed/Mat22.h"
#include "lockbox/fixed/Mat33.h"
#include "lockbox/fixed/Rot.h"
#include "lockbox/fixed/Sweep.h"
#include "lockbox/fixed/Transform.h"
#include "lockbox/fixed/Vec2.h"
#include "lockbox/fixed/Vec3.h"
#include "lockbox/fixed/Wide.h"
