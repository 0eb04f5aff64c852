#pragma once
// GoogleTest printers that show a fixed-point value and its raw hex, so a failure reads
// "1.5 (raw 0x00018000)".
#include <cstdio>
#include <ostream>

#include "lockbox/fixed/Fixed.h"
#include "lockbox/fixed/Wide.h"

namespace lockbox {
inline void PrintTo(Fixed v, std::ostream* os) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g (raw 0x%08x)", v.ToDouble(), static_cast<unsigned>(v.Raw()));
    *os << buf;
}
inline void PrintTo(Wide v, std::ostream* os) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%.12g (raw 0x%016llx)", v.ToDouble(), static_cast<unsigned long long>(v.Raw()));
    *os << buf;
}
}  // namespace lockbox
