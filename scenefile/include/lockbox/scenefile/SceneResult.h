#pragma once
/// @file
/// The result of loading or saving a scene file: ok, or an error that names the JSON path of
/// the value at fault and what is wrong with it, in one line:
///   `body[3].fixture[1].polygon.vertices: 9 vertices, at most 8`
///   `joint[7].bodyB: index 40, the file has 12 bodies`
/// A scene file is untrusted input: every refusal comes back as a SceneResult, never as an
/// assert, and a refused load leaves the target world as it was.

#include <string>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"

namespace lockbox::scenefile {

/// What kind of problem a scene file has.
enum class SceneError : uint8 {
    e_ok = 0,
    e_io,         ///< the file could not be opened, read or written
    e_syntax,     ///< not JSON (the message gives the byte offset)
    e_limit,      ///< a bound of SceneLimits is exceeded (size, nesting, counts)
    e_type,       ///< a value has the wrong JSON type (a string where a number belongs, ...)
    e_number,     ///< a number's text is malformed, not finite, or does not fit its format
    e_range,      ///< a value is outside what the engine accepts (negative density, bounds, ...)
    e_shape,      ///< the engine's shape validation refused the geometry
    e_reference,  ///< an index names no body or joint, or the wrong kind of joint
    e_locked,     ///< the world is inside Step (a load must not change it)
};

/// Short name of an error kind ("syntax", "range", ...).
LOCKBOX_API const char* SceneErrorName(SceneError error) noexcept;

/// Outcome of a scene-file operation.
struct LOCKBOX_API SceneResult {
    /// e_ok, or the kind of problem.
    SceneError error = SceneError::e_ok;
    std::string path;     ///< JSON path of the value at fault ("body[3].angle"); empty for the document
    std::string message;  ///< what is wrong; empty when ok
    /// True when the operation succeeded.
    bool ok() const noexcept { return error == SceneError::e_ok; }
    /// True on success, as ok().
    explicit operator bool() const noexcept { return ok(); }
    /// "path: message", or the message alone when the path is empty; "ok" on success.
    std::string Describe() const;
};

}  // namespace lockbox::scenefile
