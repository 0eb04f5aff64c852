#pragma once
/// Shared pieces of the C bindings (the functions JavaScript calls): the export macro, the
/// world handle, and the last error message.
///
/// Why a thin C API rather than embind: every value that crosses is an integer (raw Q16.16,
/// the two 32-bit halves of a Q32.32 or of a 64-bit hash, ids, flags), so the one documented
/// number conversion (NumberConversion.h) is the only way a JavaScript number becomes a
/// `Fixed`, and no binding layer converts numbers behind its back. Bodies, fixtures and joints
/// are named by their ids, which survive a snapshot restore, so JavaScript never holds a C++
/// pointer that a restore or a destroy could leave dangling. And the module stays small: no
/// RTTI, no binding registry.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/lockbox.h"

#if defined(__EMSCRIPTEN__)
#include <emscripten/em_macros.h>
/// A function of the C API: C linkage, kept and exported by the linker.
#define LOCKBOX_WEB_API extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define LOCKBOX_WEB_API extern "C"
#endif

namespace lockbox::web {

/// What the contact listener records: one event per call, read and cleared by JavaScript.
struct ContactEvent {
    int32_t begin = 0;  ///< 1 BeginContact, 0 EndContact
    int32_t fixtureA = -1, fixtureB = -1;
    int32_t childA = 0, childB = 0;
    int32_t bodyA = -1, bodyB = -1;
};

/// Collects BeginContact and EndContact as events (never changes the simulation).
class EventListener : public b2ContactListener {
public:
    void BeginContact(b2Contact* contact) override { Record(contact, 1); }
    void EndContact(b2Contact* contact) override { Record(contact, 0); }
    std::vector<ContactEvent> events;

private:
    void Record(b2Contact* contact, int32_t begin);
};

/// A world as JavaScript holds it: an owned world, or a scene's world (not owned), with the
/// buffers the bindings hand back to JavaScript.
struct WebWorld {
    std::unique_ptr<b2World> owned;  ///< set for worlds created through the API
    b2World* world = nullptr;        ///< the world itself
    EventListener listener;          ///< installed on owned worlds
    std::vector<int32_t> results;    ///< ids, hits, draw data of the last query
    std::vector<uint8_t> bytes;      ///< the last snapshot saved
};

/// Records `message` as the last error (read by lb_last_error) and returns -1.
int32_t Fail(std::string message);

/// Raw Q16.16 as a Fixed.
inline Fixed Fx(int32_t raw) noexcept { return Fixed::FromRaw(raw); }

/// The body with `id`, or nullptr after Fail naming `what`.
b2Body* FindBody(WebWorld& w, int32_t id, const char* what);
/// The fixture with `id`, or nullptr after Fail naming `what`.
b2Fixture* FindFixture(WebWorld& w, int32_t id, const char* what);
/// The joint with `id`, or nullptr after Fail naming `what`.
b2Joint* FindJoint(WebWorld& w, int32_t id, const char* what);

/// Writes a 64-bit value as two int32 words, low half first.
inline void PutU64(int32_t* out, uint64_t v) noexcept {
    out[0] = static_cast<int32_t>(static_cast<uint32_t>(v));
    out[1] = static_cast<int32_t>(static_cast<uint32_t>(v >> 32));
}

/// A 64-bit value from two int32 words, low half first.
inline uint64_t GetU64(int32_t lo, int32_t hi) noexcept {
    return static_cast<uint64_t>(static_cast<uint32_t>(lo)) | (static_cast<uint64_t>(static_cast<uint32_t>(hi)) << 32);
}

}  // namespace lockbox::web
