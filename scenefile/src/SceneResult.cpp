// SceneResult: error names and the one-line description.
#include "lockbox/scenefile/SceneResult.h"

namespace lockbox::scenefile {

const char* SceneErrorName(SceneError error) noexcept {
    switch (error) {
        case SceneError::e_ok: return "ok";
        case SceneError::e_io: return "io";
        case SceneError::e_syntax: return "syntax";
        case SceneError::e_limit: return "limit";
        case SceneError::e_type: return "type";
        case SceneError::e_number: return "number";
        case SceneError::e_range: return "range";
        case SceneError::e_shape: return "shape";
        case SceneError::e_reference: return "reference";
        case SceneError::e_locked: return "locked";
    }
    return "unknown";
}

std::string SceneResult::Describe() const {
    if (ok()) return "ok";
    return path.empty() ? message : path + ": " + message;
}

}  // namespace lockbox::scenefile
