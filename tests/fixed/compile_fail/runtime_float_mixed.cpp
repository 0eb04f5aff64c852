// Must NOT compile, for each FORM: a run-time float next to a Fixed, a Wide or a vector does
// not convert either (only a literal does, as in mixed_arithmetic_test.cpp).
#include "lockbox/fixed/WideVec.h"

#if FORM == 1
lockbox::Fixed Mixed(float runtimeValue, lockbox::Fixed x) { return runtimeValue * x; }
#elif FORM == 2
lockbox::Wide Mixed(double runtimeValue, lockbox::Wide w) { return w * runtimeValue; }
#elif FORM == 3
lockbox::b2Vec2 Mixed(float runtimeValue, const lockbox::b2Vec2& v) { return runtimeValue * v; }
#elif FORM == 4
bool Mixed(float runtimeValue, lockbox::Fixed x) { return x < runtimeValue; }
#else
#error "FORM must be 1..4"
#endif
