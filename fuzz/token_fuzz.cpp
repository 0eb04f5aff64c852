// Admission tokens and their envelope, as a match server reads them from any sender: the layout
// parser, the signature and deadline check, and the envelope split. Nothing may crash, and a
// token that parses must encode back to the same signed bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "lockbox/net/admission/AdmissionToken.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox_admission/TokenAuthority.h"

namespace {

void Require(bool ok) {
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace lockbox;
    const std::span<const uint8_t> bytes(data, size);
    static const admission::TokenKey kKey{};
    static admission::TokenVerifier verifier(kKey, 64, 3600);

    net::admission::AdmissionToken token;
    if (net::admission::ParseToken(bytes, token) == net::admission::TokenFormatError::e_ok) {
        const auto body = net::admission::EncodeTokenBody(token);
        for (size_t i = 0; i < body.size(); ++i) Require(body[i] == bytes[i]);
    }
    net::admission::AdmissionToken checked;
    const uint64_t now = size > 0 ? data[0] : 0;
    if (verifier.Check(bytes, now, checked) == admission::Refusal::e_none) (void)verifier.Consume(checked, 1, now);

    net::admission::Envelope env;
    if (net::admission::ParseEnvelope(bytes, env)) {
        Require(env.token.size() == net::admission::kTokenBytes && !env.payload.empty());
        Require(verifier.Check(env.token, now, checked) != admission::Refusal::e_count);
    }
    // A valid token for the fuzzer to build on: the same bytes, signed.
    if (size >= net::admission::kTokenBodyBytes) {
        net::admission::AdmissionToken t;
        if (net::admission::ParseToken(admission::TokenSigner(kKey).Sign(token), t) ==
            net::admission::TokenFormatError::e_ok)
            Require(t == token);
    }
    return 0;
}
