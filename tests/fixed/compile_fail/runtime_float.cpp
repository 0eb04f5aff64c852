// Must NOT compile: a run-time float may never convert to Fixed implicitly.
#include "lockbox/fixed/Fixed.h"

lockbox::Fixed Convert(float runtimeValue) { return runtimeValue; }
