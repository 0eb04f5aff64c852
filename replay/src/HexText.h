#pragma once
// A hash as the replay library writes it in its messages and reports (private): the player's
// verdicts, the bisect report and the diff all print hashes in this one form.

#include <cstdio>
#include <string>

#include "lockbox/common/Settings.h"

namespace lockbox::replay::detail {

/// `v` as "0x" and 16 lower-case hex digits.
inline std::string Hex(uint64 v) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

}  // namespace lockbox::replay::detail
