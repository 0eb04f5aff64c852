#pragma once
// What the two socket transports (UdpTransport, EnetTransport) do alike when they open: the
// socket buffers they ask for, and the error text their callers may ask for.

#include <string>
#include <utility>

namespace lockbox::net::transport_detail {

inline constexpr int kSocketBufferBytes = 4 << 20;  // room for bursts on loopback; the kernel may cap it

/// Hands `message` to the caller when it asked for the error text (`error` not null).
inline void SetError(std::string* error, std::string message) {
    if (error != nullptr) *error = std::move(message);
}

}  // namespace lockbox::net::transport_detail
