#pragma once
// Clients of a lockbox_server match over real loopback UDP: a LockstepClient on a UdpTransport,
// wrapped in an AdmissionTransport that presents the client's token.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "JsonLog.h"
#include "MatchHost.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox/replay/SceneGame.h"
#include "lockbox_admission/TokenAuthority.h"

namespace lockbox::server::testing {

inline constexpr uint64_t kNow = 1'800'000'000;  // the tests' Unix time

inline admission::TokenKey TestKey() {
    admission::TokenKey k{};
    for (size_t i = 0; i < k.size(); ++i) k[i] = static_cast<uint8_t>(3 * i + 1);
    return k;
}

inline admission::TokenBytes Mint(uint32_t match, uint8_t slot, uint64_t nonce, uint64_t expiresAt = kNow + 60,
                                  const admission::TokenKey& key = TestKey()) {
    admission::AdmissionToken t;
    t.matchId = match;
    t.slot = slot;
    t.clientId = 1000 + nonce;
    t.expiresAt = expiresAt;
    t.nonce = nonce;
    return admission::TokenSigner(key).Sign(t);
}

struct TestClient {
    std::unique_ptr<net::UdpTransport> udp;
    net::PeerId server = net::kNoPeer;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    std::unique_ptr<replay::SceneGame> game;
    std::unique_ptr<replay::ScriptedInputs> inputs;
    std::unique_ptr<net::LockstepClient> client;
    int32_t hashFrame = -1;  // frame whose resulting world hash is kept
    uint64_t worldHash = 0;  // b2World::Hash after frame hashFrame

    /// A client of the server at 127.0.0.1:`port` presenting `token`.
    TestClient(uint16_t port, const admission::TokenBytes& token, uint64_t seed, int32_t keepHashOf) {
        std::string error;
        udp = net::UdpTransport::Open("127.0.0.1", 0, &error);
        EXPECT_TRUE(udp) << error;
        server = udp->AddPeer("127.0.0.1", port, &error);
        admission = std::make_unique<net::admission::AdmissionTransport>(*udp, server, token);
        game = std::make_unique<replay::SceneGame>("vertical_stack");
        inputs = std::make_unique<replay::ScriptedInputs>(seed, 1);
        client = std::make_unique<net::LockstepClient>(*admission, server, net::ClientConfig{}, game->world(), *game);
        hashFrame = keepHashOf;
        client->SetConfirmedFrameHook([this](int32_t f, std::span<const uint8_t>, uint64_t, const b2World& w) {
            if (f == hashFrame) worldHash = w.Hash();
        });
    }

    void Step() {
        client->Update();
        std::vector<uint8_t> input;
        while (client->WantsInput()) {
            inputs->Next(input);
            if (!client->SubmitLocalInput(input)) break;
        }
    }
};

/// Runs `tick` (the server side) and every client until `done` or the wall limit.
inline void Pump(const std::function<void()>& tick, std::vector<std::unique_ptr<TestClient>>& clients,
                 const std::function<bool()>& done, std::chrono::seconds limit = std::chrono::seconds(20)) {
    const auto start = std::chrono::steady_clock::now();
    while (!done() && std::chrono::steady_clock::now() - start < limit) {
        tick();
        for (auto& c : clients) c->Step();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
}

/// A MatchHost on a fresh loopback socket, with the tests' key and clock and no log output.
struct TestHost {
    JsonLog log{nullptr};
    std::unique_ptr<MatchHost> host;
    uint16_t port = 0;

    explicit TestHost(HostConfig config) {
        std::string error;
        auto socket = net::UdpTransport::Open("127.0.0.1", 0, &error, 4096);
        EXPECT_TRUE(socket) << error;
        port = socket->LocalPort();
        config.key = TestKey();
        config.unixNow = [] { return kNow; };
        host = std::make_unique<MatchHost>(std::move(socket), std::move(config), log);
    }
};

/// Datagrams the host dropped for `drop`.
inline uint64_t Dropped(const MatchHost& h, Drop drop) { return h.Stats().dropped[static_cast<size_t>(drop)]; }

}  // namespace lockbox::server::testing
