// lockbox_server_load: drives lockstep matches against a running lockbox_server from another
// process, for the capacity figures of docs/deploy.md. Each client has its own UDP socket and a
// one-body world that its inputs push (so the state hash depends on every input, at almost no
// simulation cost: the server's relay work is what is measured). At the end it reports the
// frames reached and whether every match's clients agree on their state hash.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "lockbox/lockbox.h"
#include "lockbox/net/LockstepClient.h"
#include "lockbox/net/UdpTransport.h"
#include "lockbox/net/admission/AdmissionTransport.h"
#include "lockbox/replay/Game.h"
#include "lockbox_admission/TokenAuthority.h"
#include "lockbox_cli/OptionReader.h"

namespace {

using namespace lockbox;

constexpr const char* kUsage =
    "usage: lockbox_server_load --port N --key-file FILE [options]\n"
    "  --host HOST         the server's numeric address (default 127.0.0.1)\n"
    "  --port N            the server's UDP port (required)\n"
    "  --key-file FILE     the server's token key (required)\n"
    "  --matches M         matches to play, 1 .. 10000 (default 10)\n"
    "  --players P         clients per match, 1 .. 64 (must match the server's; default 4)\n"
    "  --first-match ID    id of the first match (default 1)\n"
    "  --seconds S         how long to play, 1 .. 3600 (default 10)\n";

// One body pushed by every player's input byte.
class PushGame : public replay::Game {
public:
    void Apply(b2World& world, int32 frame, std::span<const uint8> inputs) override {
        (void)frame;
        b2Body* body = world.GetBodyList();
        if (body == nullptr) return;
        int32 push = 0;
        for (uint8 b : inputs) push += b & 3;
        body->ApplyLinearImpulse(b2Vec2(Fixed(push - 3), Fixed(0)), body->GetWorldCenter());
    }
};

struct Client {
    std::unique_ptr<net::UdpTransport> udp;
    std::unique_ptr<net::admission::AdmissionTransport> admission;
    std::unique_ptr<b2World> world;
    PushGame game;
    std::unique_ptr<net::LockstepClient> session;
    uint32_t counter = 0;
};

}  // namespace

int main(int argc, char** argv) {
    cli::OptionReader args("lockbox_server_load", argc, argv);
    std::string host = "127.0.0.1", keyFile;
    uint16_t port = 0;
    uint32_t matches = 10, players = 4, firstMatch = 1, seconds = 10;
    while (args.Next()) {
        if (args.Is("--host"))
            args.Text(host);
        else if (args.Is("--port"))
            args.Int(1, 65535, port);
        else if (args.Is("--key-file"))
            args.Text(keyFile);
        else if (args.Is("--matches"))
            args.Int(1, 10000, matches);
        else if (args.Is("--players"))
            args.Int(1, 64, players);
        else if (args.Is("--first-match"))
            args.Int(0, 4000000000LL, firstMatch);
        else if (args.Is("--seconds"))
            args.Int(1, 3600, seconds);
        else
            args.Unknown();
    }
    if (!args.Failed() && (port == 0 || keyFile.empty())) args.Refuse("--port and --key-file are required");
    if (args.Failed()) return args.Fail(kUsage);
    std::ifstream in(keyFile);
    std::stringstream text;
    text << in.rdbuf();
    const auto key = admission::ParseKeyHex(text.str());
    if (!key) {
        std::fprintf(stderr, "lockbox_server_load: %s does not hold a key\n", keyFile.c_str());
        return 2;
    }
    const uint64_t now = static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count());
    const admission::TokenSigner signer(*key);
    std::vector<std::unique_ptr<Client>> clients;
    for (uint32_t m = 0; m < matches; ++m) {
        for (uint32_t s = 0; s < players; ++s) {
            auto c = std::make_unique<Client>();
            std::string error;
            c->udp = net::UdpTransport::Open(host.find(':') == std::string::npos ? "0.0.0.0" : "::", 0, &error);
            if (!c->udp) {
                std::fprintf(stderr, "lockbox_server_load: %s\n", error.c_str());
                return 1;
            }
            const net::PeerId server = c->udp->AddPeer(host, port, &error);
            admission::AdmissionToken t;
            t.matchId = firstMatch + m;
            t.slot = static_cast<uint8_t>(s);
            t.clientId = m * 100 + s;
            t.expiresAt = now + 600;
            t.nonce = admission::NewNonce();
            const auto token = signer.Sign(t);
            c->admission = std::make_unique<net::admission::AdmissionTransport>(*c->udp, server, token);
            c->world = std::make_unique<b2World>(b2Vec2(Fixed(0), Fixed(0)));
            b2BodyDef bd;
            bd.type = b2_dynamicBody;
            b2CircleShape circle;
            circle.m_radius = Fixed(1);
            c->world->CreateBody(&bd)->CreateFixture(&circle, Fixed(1));
            c->session =
                std::make_unique<net::LockstepClient>(*c->admission, server, net::ClientConfig{}, *c->world, c->game);
            c->counter = m * 7919 + s * 104729;
            clients.push_back(std::move(c));
        }
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<uint8_t> input(8);
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds)) {
        for (auto& c : clients) {
            c->session->Update();
            while (c->session->WantsInput()) {
                c->counter = c->counter * 1664525u + 1013904223u;
                for (size_t i = 0; i < input.size(); ++i) input[i] = static_cast<uint8_t>(c->counter >> (i * 3));
                if (!c->session->SubmitLocalInput(input)) break;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    // No more inputs: the frames already confirmed reach every client, which then all stand at
    // the same frame, where their hashes must agree.
    const auto settle = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - settle < std::chrono::seconds(2)) {
        for (auto& c : clients) c->session->Update();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    int32_t minFrame = INT32_MAX, maxFrame = 0;
    uint32_t agreed = 0, unequalFrames = 0, disagreed = 0;
    for (uint32_t m = 0; m < matches; ++m) {
        bool sameFrame = true, sameHash = true;
        const auto& first = clients[m * players]->session;
        for (uint32_t s = 0; s < players; ++s) {
            const auto& c = clients[m * players + s]->session;
            minFrame = std::min(minFrame, c->Frame());
            maxFrame = std::max(maxFrame, c->Frame());
            sameFrame = sameFrame && c->Frame() == first->Frame();
            sameHash = sameHash && c->LastHash() == first->LastHash();
        }
        if (!sameFrame || first->Frame() <= 0)
            ++unequalFrames;
        else if (sameHash)
            ++agreed;
        else
            ++disagreed;
    }
    for (auto& c : clients) c->session->Leave();
    std::printf(
        "{\"matches\":%u,\"players\":%u,\"seconds\":%u,\"min_frame\":%d,\"max_frame\":%d,\"agreed\":%u,"
        "\"disagreed\":%u,\"not_comparable_or_not_started\":%u}\n",
        matches, players, seconds, minFrame, maxFrame, agreed, disagreed, unequalFrames);
    return disagreed == 0 && minFrame > 0 ? 0 : 1;
}
