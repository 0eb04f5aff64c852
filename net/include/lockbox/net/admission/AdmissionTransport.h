#pragma once
/// @file
/// How a client presents its admission token (AdmissionToken.h) to a match server: every
/// datagram it sends before the server first answers is wrapped in an admission envelope that
/// carries the token in front of the session's own bytes. Only what arrives from the server
/// after the first wrapped datagram went out counts as an answer: a socket whose port a
/// departed client of the same server held may receive what was still on its way to that
/// client, and must present its token all the same. The session (a LockstepClient, say)
/// is unchanged: AdmissionTransport wraps the transport it runs on.
///
/// The envelope, little-endian:
///   0  u8 'L'   1 u8 'A'   magic
///   2  u8 version (kEnvelopeVersion)
///   3  kTokenBytes bytes: the token, as the matchmaker handed it out
///   67 the session's datagram (at least one byte)
///
/// The server answers nothing to a datagram it did not admit, and before the handshake
/// completes it never sends more bytes than it received (docs/deploy.md).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/net/Transport.h"
#include "lockbox/net/admission/AdmissionToken.h"

namespace lockbox::net::admission {

/// Layout version of the envelope.
inline constexpr uint8_t kEnvelopeVersion = 1;
/// Bytes in front of the session's datagram.
inline constexpr size_t kEnvelopeBytes = 3 + kTokenBytes;

/// The parts of an envelope; both view the input bytes.
struct Envelope {
    std::span<const uint8_t> token;    ///< kTokenBytes bytes (not checked here)
    std::span<const uint8_t> payload;  ///< the session's datagram, never empty
};

/// True when `bytes` starts with the envelope's magic (whatever follows).
LOCKBOX_API bool LooksLikeEnvelope(std::span<const uint8_t> bytes) noexcept;
/// Splits an envelope; false for a wrong magic or version, or no payload.
LOCKBOX_API bool ParseEnvelope(std::span<const uint8_t> bytes, Envelope& out) noexcept;
/// Writes the envelope of `token` and `payload` into `out` (replacing its contents).
LOCKBOX_API void WriteEnvelope(std::vector<uint8_t>& out, std::span<const uint8_t> token,
                               std::span<const uint8_t> payload);

/// A client's transport decorator: wraps every datagram to `server` in an envelope with the
/// token until a datagram from `server` arrives, then sends datagrams as they are.
class LOCKBOX_API AdmissionTransport final : public Transport {
public:
    /// `inner` must outlive this transport; `token` is the matchmaker's token (kTokenBytes bytes,
    /// copied; its contents are not checked: the server does).
    AdmissionTransport(Transport& inner, PeerId server, std::span<const uint8_t> token);

    bool Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery = Delivery::e_unreliable) override;
    size_t Poll(std::vector<Datagram>& out) override;
    uint64_t NowMicros() const override { return m_inner.NowMicros(); }
    /// The inner transport's limit less the envelope, so a wrapped datagram always fits.
    size_t MaxDatagram() const noexcept override;
    const TransportStats& Stats() const noexcept override { return m_inner.Stats(); }
    void Disconnect(PeerId peer) override { m_inner.Disconnect(peer); }

    /// True once the server has answered, i.e. sent anything after our first datagram to it
    /// (the token is no longer sent).
    bool Answered() const noexcept { return m_answered; }

private:
    Transport& m_inner;
    PeerId m_server;
    std::vector<uint8_t> m_token;
    std::vector<uint8_t> m_buffer;
    bool m_sent = false;  // a wrapped datagram went to the server
    bool m_answered = false;
};

}  // namespace lockbox::net::admission
