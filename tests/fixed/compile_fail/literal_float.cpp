// Must compile: the control case for runtime_float.cpp (a literal converts at compile time).
#include "lockbox/fixed/Fixed.h"

lockbox::Fixed Convert() { return 0.25f; }
