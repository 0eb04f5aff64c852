// Admission tokens: the layout (lockbox::net), signing and every refusal of the verifier
// (tools/admission), and the client's envelope.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox/net/SimNet.h"
#include "lockbox/net/admission/AdmissionToken.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox_admission/TokenAuthority.h"

namespace lockbox::admission {
namespace LOCKBOX_TEST_FILE {

constexpr uint64_t kNow = 1'800'000'000;

TokenKey Key(uint8_t fill) {
    TokenKey k{};
    for (size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(fill + i);
    return k;
}

AdmissionToken Sample() {
    AdmissionToken t;
    t.matchId = 7;
    t.slot = 2;
    t.clientId = 0x1122334455667788ull;
    t.expiresAt = kNow + 30;
    t.nonce = 0xABCDEF;
    return t;
}

TEST(AdmissionToken, LayoutRoundTrip) {
    const TokenBytes bytes = TokenSigner(Key(1)).Sign(Sample());
    EXPECT_EQ(bytes[0], 'L');
    EXPECT_EQ(bytes[1], 'T');
    EXPECT_EQ(bytes[2], net::admission::kTokenVersion);
    EXPECT_EQ(bytes[3], 2);
    AdmissionToken parsed;
    ASSERT_EQ(net::admission::ParseToken(bytes, parsed), net::admission::TokenFormatError::e_ok);
    EXPECT_EQ(parsed, Sample());
}

TEST(AdmissionToken, FormatErrorsLeaveTheTargetUntouched) {
    TokenBytes bytes = TokenSigner(Key(1)).Sign(Sample());
    AdmissionToken out;
    out.matchId = 99;
    using net::admission::TokenFormatError;
    EXPECT_EQ(net::admission::ParseToken(std::span(bytes).first(63), out), TokenFormatError::e_wrongLength);
    TokenBytes bad = bytes;
    bad[1] = 'X';
    EXPECT_EQ(net::admission::ParseToken(bad, out), TokenFormatError::e_badMagic);
    bad = bytes;
    bad[2] = 9;
    EXPECT_EQ(net::admission::ParseToken(bad, out), TokenFormatError::e_badVersion);
    bad = bytes;
    bad[3] = 64;
    EXPECT_EQ(net::admission::ParseToken(bad, out), TokenFormatError::e_badSlot);
    EXPECT_EQ(out.matchId, 99u);
}

TEST(TokenVerifier, AcceptsASignedToken) {
    TokenVerifier v(Key(1));
    const TokenBytes bytes = TokenSigner(Key(1)).Sign(Sample());
    AdmissionToken out;
    ASSERT_EQ(v.Check(bytes, kNow, out), Refusal::e_none);
    EXPECT_EQ(out, Sample());
    EXPECT_EQ(v.Consume(out, 1, kNow), Refusal::e_none);
    // The same presenter again (its first datagrams are resent): still admitted.
    EXPECT_EQ(v.Consume(out, 1, kNow), Refusal::e_none);
}

TEST(TokenVerifier, RefusesMalformed) {
    TokenVerifier v(Key(1));
    AdmissionToken out;
    const std::vector<uint8_t> shortBytes(10, 0);
    EXPECT_EQ(v.Check(shortBytes, kNow, out), Refusal::e_malformed);
}

TEST(TokenVerifier, RefusesAnotherVersion) {
    TokenVerifier v(Key(1));
    TokenBytes bytes = TokenSigner(Key(1)).Sign(Sample());
    bytes[2] = 2;
    AdmissionToken out;
    EXPECT_EQ(v.Check(bytes, kNow, out), Refusal::e_badVersion);
}

TEST(TokenVerifier, RefusesUnsignedAlteredAndOtherKeys) {
    TokenVerifier v(Key(1));
    AdmissionToken out;
    // Unsigned: the fields with a zero signature.
    const auto body = net::admission::EncodeTokenBody(Sample());
    TokenBytes unsigned_{};
    for (size_t i = 0; i < body.size(); ++i) unsigned_[i] = body[i];
    EXPECT_EQ(v.Check(unsigned_, kNow, out), Refusal::e_forged);
    // Altered: another slot under the original signature.
    TokenBytes altered = TokenSigner(Key(1)).Sign(Sample());
    altered[3] = 3;
    EXPECT_EQ(v.Check(altered, kNow, out), Refusal::e_forged);
    // Signed with another key.
    EXPECT_EQ(v.Check(TokenSigner(Key(2)).Sign(Sample()), kNow, out), Refusal::e_forged);
}

TEST(TokenVerifier, RefusesExpiredAndTooLong) {
    TokenVerifier v(Key(1), 16, 600);
    AdmissionToken out;
    const TokenBytes bytes = TokenSigner(Key(1)).Sign(Sample());
    EXPECT_EQ(v.Check(bytes, Sample().expiresAt, out), Refusal::e_expired);
    EXPECT_EQ(v.Check(bytes, Sample().expiresAt + 100, out), Refusal::e_expired);
    AdmissionToken far = Sample();
    far.expiresAt = kNow + 601;
    EXPECT_EQ(v.Check(TokenSigner(Key(1)).Sign(far), kNow, out), Refusal::e_tooLong);
}

TEST(TokenVerifier, RefusesReuseFromAnotherPresenterUntilItExpires) {
    TokenVerifier v(Key(1));
    const AdmissionToken t = Sample();
    EXPECT_EQ(v.Consume(t, 1, kNow), Refusal::e_none);
    EXPECT_EQ(v.Consume(t, 2, kNow), Refusal::e_reused);
    EXPECT_EQ(v.Remembered(), 1u);
    // Past its deadline the nonce is forgotten (Check refuses the token itself by then).
    EXPECT_EQ(v.Consume(t, 2, t.expiresAt), Refusal::e_none);
}

TEST(TokenVerifier, ReplayCacheIsBoundedAndForgetsExpiredNonces) {
    TokenVerifier v(Key(1), 2);
    AdmissionToken a = Sample(), b = Sample(), c = Sample();
    b.nonce = 2;
    c.nonce = 3;
    a.expiresAt = kNow + 5;
    EXPECT_EQ(v.Consume(a, 1, kNow), Refusal::e_none);
    EXPECT_EQ(v.Consume(b, 1, kNow), Refusal::e_none);
    EXPECT_EQ(v.Consume(c, 1, kNow), Refusal::e_replayCacheFull);
    EXPECT_EQ(v.Remembered(), 2u);
    // Once `a` expired its room is reused.
    EXPECT_EQ(v.Consume(c, 1, kNow + 5), Refusal::e_none);
    EXPECT_EQ(v.Remembered(), 2u);
}

TEST(TokenVerifier, RefusalNamesAreDistinct) {
    for (int i = 0; i < static_cast<int>(Refusal::e_count); ++i)
        for (int j = i + 1; j < static_cast<int>(Refusal::e_count); ++j)
            EXPECT_NE(RefusalName(static_cast<Refusal>(i)), RefusalName(static_cast<Refusal>(j)));
    EXPECT_EQ(RefusalName(Refusal::e_wrongMatch), "wrong_match");
}

TEST(TokenHex, KeyAndBytesRoundTrip) {
    const TokenKey k = Key(5);
    EXPECT_EQ(ParseKeyHex(KeyHex(k) + "\n"), k);
    EXPECT_FALSE(ParseKeyHex("abc"));
    EXPECT_FALSE(ParseKeyHex(std::string(64, 'g')));
    std::vector<uint8_t> out{1};
    EXPECT_FALSE(FromHex("0", out));
    EXPECT_EQ(out.size(), 1u);
    ASSERT_TRUE(FromHex("00ff10", out));
    EXPECT_EQ(out, (std::vector<uint8_t>{0, 255, 16}));
}

TEST(AdmissionEnvelope, WhatArrivedBeforeTheFirstSendIsNoAnswer) {
    // A socket that got a departed client's port may receive what was on its way to it.
    net::SimNet simnet(1);
    auto& client = simnet.AddEndpoint();
    auto& server = simnet.AddEndpoint();
    const TokenBytes token = TokenSigner(Key(1)).Sign(Sample());
    net::admission::AdmissionTransport wrapped(client, server.Index(), token);
    const std::vector<uint8_t> stray{9, 9};
    ASSERT_TRUE(server.Send(client.Index(), stray));
    simnet.Advance(100'000);
    std::vector<net::Datagram> got;
    wrapped.Poll(got);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_FALSE(wrapped.Answered());
    ASSERT_TRUE(wrapped.Send(server.Index(), std::vector<uint8_t>{1, 2, 3}));
    simnet.Advance(100'000);
    got.clear();
    server.Poll(got);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_TRUE(net::admission::LooksLikeEnvelope(got[0].bytes)) << "the token still goes first";
}

TEST(AdmissionEnvelope, WrapsUntilTheServerAnswers) {
    net::SimNet simnet(1);
    auto& client = simnet.AddEndpoint();
    auto& server = simnet.AddEndpoint();
    const TokenBytes token = TokenSigner(Key(1)).Sign(Sample());
    net::admission::AdmissionTransport wrapped(client, server.Index(), token);
    const std::vector<uint8_t> hello{1, 2, 3};
    ASSERT_TRUE(wrapped.Send(server.Index(), hello));
    simnet.Advance(100'000);
    std::vector<net::Datagram> got;
    server.Poll(got);
    ASSERT_EQ(got.size(), 1u);
    net::admission::Envelope env;
    ASSERT_TRUE(net::admission::ParseEnvelope(got[0].bytes, env));
    EXPECT_TRUE(std::equal(env.token.begin(), env.token.end(), token.begin(), token.end()));
    EXPECT_EQ(std::vector<uint8_t>(env.payload.begin(), env.payload.end()), hello);
    // The server answers: from then on datagrams go as they are.
    ASSERT_TRUE(server.Send(client.Index(), hello));
    simnet.Advance(100'000);
    std::vector<net::Datagram> back;
    wrapped.Poll(back);
    EXPECT_TRUE(wrapped.Answered());
    ASSERT_TRUE(wrapped.Send(server.Index(), hello));
    simnet.Advance(100'000);
    got.clear();
    server.Poll(got);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].bytes, hello);
}

TEST(AdmissionEnvelope, RefusesWrongMagicVersionAndEmptyPayload) {
    std::vector<uint8_t> out;
    const TokenBytes token{};
    const std::vector<uint8_t> payload{9};
    net::admission::WriteEnvelope(out, token, payload);
    net::admission::Envelope env;
    EXPECT_TRUE(net::admission::ParseEnvelope(out, env));
    std::vector<uint8_t> bad = out;
    bad[2] = 2;
    EXPECT_FALSE(net::admission::ParseEnvelope(bad, env));
    bad = out;
    bad[0] = 'X';
    EXPECT_FALSE(net::admission::ParseEnvelope(bad, env));
    bad = out;
    bad.pop_back();
    EXPECT_FALSE(net::admission::ParseEnvelope(bad, env));
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::admission
