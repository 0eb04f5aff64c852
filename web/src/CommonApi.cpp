// The C API's shared functions: memory for JavaScript's arguments, the last error, number
// conversion, and the lookups every other file uses.
#include <cstdlib>
#include <string>
#include <string_view>

#include "Bindings.h"
#include "NumberConversion.h"

namespace lockbox::web {

namespace {
std::string& LastError() {
    static std::string message;
    return message;
}
}  // namespace

int32_t Fail(std::string message) {
    LastError() = std::move(message);
    return -1;
}

b2Body* FindBody(WebWorld& w, int32_t id, const char* what) {
    b2Body* b = w.world->GetBody(id);
    if (!b) Fail(std::string(what) + ": no body with id " + std::to_string(id));
    return b;
}

b2Fixture* FindFixture(WebWorld& w, int32_t id, const char* what) {
    b2Fixture* f = w.world->GetFixture(id);
    if (!f) Fail(std::string(what) + ": no fixture with id " + std::to_string(id));
    return f;
}

b2Joint* FindJoint(WebWorld& w, int32_t id, const char* what) {
    b2Joint* j = w.world->GetJoint(id);
    if (!j) Fail(std::string(what) + ": no joint with id " + std::to_string(id));
    return j;
}

void EventListener::Record(b2Contact* contact, int32_t begin) {
    ContactEvent e;
    e.begin = begin;
    const b2Fixture* a = contact->GetFixtureA();
    const b2Fixture* b = contact->GetFixtureB();
    e.fixtureA = a->GetId();
    e.fixtureB = b->GetId();
    e.childA = contact->GetChildIndexA();
    e.childB = contact->GetChildIndexB();
    e.bodyA = a->GetBody()->GetId();
    e.bodyB = b->GetBody()->GetId();
    events.push_back(e);
}

}  // namespace lockbox::web

using namespace lockbox;
using namespace lockbox::web;

/// Bytes for JavaScript's arguments and results; lb_free releases them.
LOCKBOX_WEB_API void* lb_alloc(int32_t bytes) { return bytes > 0 ? std::malloc(static_cast<size_t>(bytes)) : nullptr; }
LOCKBOX_WEB_API void lb_free(void* p) { std::free(p); }

/// The message of the last call that returned -1 (NUL-terminated, valid until the next call).
LOCKBOX_WEB_API const char* lb_last_error() { return LastError().c_str(); }

/// The binary64 number with bits (hi:lo) as raw Q16.16 into *out: 0 when converted, else a
/// NumberError code (*out untouched).
LOCKBOX_WEB_API int32_t lb_number_to_fixed(uint32_t lo, uint32_t hi, int32_t* out) {
    const RawNumber r = DoubleBitsToFixedRaw((uint64_t{hi} << 32) | lo);
    if (r.error == NumberError::none) *out = static_cast<int32_t>(r.raw);
    return static_cast<int32_t>(r.error);
}

/// The same for raw Q32.32, written as two words into out[0..1] (low half first).
LOCKBOX_WEB_API int32_t lb_number_to_wide(uint32_t lo, uint32_t hi, int32_t* out) {
    const RawNumber r = DoubleBitsToWideRaw((uint64_t{hi} << 32) | lo);
    if (r.error == NumberError::none) PutU64(out, static_cast<uint64_t>(r.raw));
    return static_cast<int32_t>(r.error);
}

/// num/den as raw Q16.16 (Fixed::FromRatio: nearest, ties away from zero) into *out; -1 when
/// den is 0 or the value is out of range.
LOCKBOX_WEB_API int32_t lb_fixed_ratio(int32_t num, int32_t den, int32_t* out) {
    if (den == 0) return Fail("ratio: zero denominator");
    // The magnitude as FromRatio rounds it, exactly in 64 bits (|num| * 2^17 < 2^49), so that an
    // out-of-range ratio is refused instead of saturated.
    const int64_t n = num < 0 ? -int64_t{num} : num;
    const int64_t d = den < 0 ? -int64_t{den} : den;
    const int64_t magnitude = (n * 131072 + d) / (2 * d);
    if (magnitude > 2147483647)
        return Fail("ratio: " + std::to_string(num) + "/" + std::to_string(den) + " out of range");
    *out = Fixed::FromRatio(num, den).Raw();
    return 0;
}

/// Decimal text (NUL-terminated) as raw Q16.16 with Fixed::Parse into *out; -1 when refused.
LOCKBOX_WEB_API int32_t lb_fixed_parse(const char* text, int32_t* out) {
    const char* why = nullptr;
    Fixed v;
    if (!Fixed::Parse(std::string_view(text), v, &why)) return Fail(std::string("'") + text + "': " + why);
    *out = v.Raw();
    return 0;
}

/// The message of a NumberError code.
LOCKBOX_WEB_API const char* lb_number_error(int32_t code) { return NumberErrorMessage(static_cast<NumberError>(code)); }
