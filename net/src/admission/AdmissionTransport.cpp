// The admission envelope and the client's decorator (AdmissionTransport.h).
#include "lockbox/net/admission/AdmissionTransport.h"

#include "lockbox/common/Bytes.h"

namespace lockbox::net::admission {

bool LooksLikeEnvelope(std::span<const uint8_t> bytes) noexcept {
    return bytes.size() >= 2 && bytes[0] == 'L' && bytes[1] == 'A';
}

bool ParseEnvelope(std::span<const uint8_t> bytes, Envelope& out) noexcept {
    bytes::Reader r(bytes);
    const uint8_t l = r.U8(), a = r.U8(), version = r.U8();
    const std::span<const uint8_t> token = r.Bytes(kTokenBytes);
    if (!r.Ok() || l != 'L' || a != 'A' || version != kEnvelopeVersion || r.AtEnd()) return false;
    out.token = token;
    out.payload = r.Bytes(r.Remaining());
    return true;
}

void WriteEnvelope(std::vector<uint8_t>& out, std::span<const uint8_t> token, std::span<const uint8_t> payload) {
    out.clear();
    bytes::Writer w(out);
    w.U8('L');
    w.U8('A');
    w.U8(kEnvelopeVersion);
    w.Bytes(token);
    w.Bytes(payload);
}

AdmissionTransport::AdmissionTransport(Transport& inner, PeerId server, std::span<const uint8_t> token)
    : m_inner(inner), m_server(server), m_token(token.begin(), token.end()) {}

bool AdmissionTransport::Send(PeerId peer, std::span<const uint8_t> bytes, Delivery delivery) {
    if (m_answered || peer != m_server) return m_inner.Send(peer, bytes, delivery);
    if (bytes.empty() || bytes.size() > MaxDatagram()) return m_inner.Send(peer, {}, delivery);  // counted there
    WriteEnvelope(m_buffer, m_token, bytes);
    m_sent = true;
    return m_inner.Send(peer, m_buffer, delivery);
}

size_t AdmissionTransport::Poll(std::vector<Datagram>& out) {
    const size_t first = out.size();
    const size_t n = m_inner.Poll(out);
    // Before our first datagram nothing from the server is an answer (see the file comment).
    for (size_t i = first; i < out.size(); ++i) m_answered = m_answered || (m_sent && out[i].peer == m_server);
    return n;
}

size_t AdmissionTransport::MaxDatagram() const noexcept {
    const size_t inner = m_inner.MaxDatagram();
    return inner > kEnvelopeBytes ? inner - kEnvelopeBytes : 0;
}

}  // namespace lockbox::net::admission
