// Names and error descriptions of the replay format.
#include "lockbox/replay/Format.h"

namespace lockbox::replay {

const char* StageName(uint32 stage) noexcept {
    static const char* const kNames[kStagesPerFrame] = {"inputs", "collide", "solve", "broadphase", "toi"};
    return stage < kStagesPerFrame ? kNames[stage] : "none";
}

const char* SolvePhaseName(uint32 phase) noexcept {
    static const char* const kNames[kSolvePhasesPerFrame] = {"velocity solve", "position solve"};
    return phase < kSolvePhasesPerFrame ? kNames[phase] : "none";
}

const char* ErrorCodeName(ErrorCode code) noexcept {
    switch (code) {
        case ErrorCode::e_ok: return "ok";
        case ErrorCode::e_io: return "i/o error";
        case ErrorCode::e_truncated: return "truncated";
        case ErrorCode::e_badMagic: return "bad magic";
        case ErrorCode::e_badVersion: return "bad format version";
        case ErrorCode::e_badEngine: return "incompatible engine";
        case ErrorCode::e_badChecksum: return "bad checksum";
        case ErrorCode::e_badChunk: return "bad chunk";
        case ErrorCode::e_badSnapshot: return "bad snapshot";
        case ErrorCode::e_missing: return "missing chunk";
        case ErrorCode::e_usage: return "usage";
    }
    return "unknown";
}

std::string ChunkTagName(uint32 tag) {
    std::string s(4, '?');
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>((tag >> (8 * i)) & 0xFFu);
        if (c >= 0x20 && c < 0x7F) s[static_cast<size_t>(i)] = c;
    }
    return s;
}

std::string Error::Describe() const {
    if (ok()) return "ok";
    std::string s = std::string(ErrorCodeName(code)) + " at offset " + std::to_string(offset);
    if (chunkIndex < 0) {
        s += " (header";
    } else {
        s += " (chunk " + std::to_string(chunkIndex);
        if (chunkType != 0) s += " '" + ChunkTagName(chunkType) + "'";
    }
    if (frame >= 0) s += ", frame " + std::to_string(frame);
    s += "): " + message;
    return s;
}

}  // namespace lockbox::replay
