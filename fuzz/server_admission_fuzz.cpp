// lockbox_server's front door (MatchHost) as any sender meets it, before a handshake: each input
// is one datagram sent over loopback UDP from one sender. Half of the inputs are turned into an
// envelope around a token signed with the server's key (fields from the input) so the fuzzer
// reaches admission, match creation and the match's Hello handling; the rest arrive as they are.
// Another bit of the first byte picks the host: lockstep relay matches, or rollback-relay
// matches with spectator slots whose inputs are recorded (relay joins, slot checks, the input
// runs read for the replay, and an admitted address taken over: every token comes from the
// one sender). Nothing may crash or leak. (The no-amplification rule is a test: tests/server.)
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "MatchHost.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/net/admission/AdmissionTransport.h"

namespace {

using namespace lockbox;

struct Rig {
    server::JsonLog log{nullptr};
    std::unique_ptr<server::MatchHost> host;
    std::unique_ptr<net::UdpTransport> sender;
    net::PeerId server = net::kNoPeer;

    explicit Rig(bool rollback) {
        std::string error;
        auto socket = net::UdpTransport::Open("127.0.0.1", 0, &error, 4096);
        if (!socket) std::abort();
        const uint16_t port = socket->LocalPort();
        server::HostConfig config;
        config.key = admission::TokenKey{};
        config.maxMatches = 8;
        config.maxPlayers = 32;
        config.match.playerCount = 2;
        if (rollback) {
            config.kind = server::MatchKind::e_rollbackRelay;
            config.spectatorsPerMatch = 2;
            config.scene = "vertical_stack";
            const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lockbox_server_fuzz_replays";
            std::filesystem::create_directories(dir);
            config.replayDir = dir.string();
        }
        config.rateLimitPerSecond = 1'000'000;  // one sender: the fuzzer's inputs must get through
        config.rateLimitBurst = 1'000'000;
        config.unixNow = [] { return uint64_t{1'800'000'000}; };
        host = std::make_unique<server::MatchHost>(std::move(socket), std::move(config), log);
        sender = net::UdpTransport::Open("127.0.0.1", 0, &error);
        if (!sender) std::abort();
        server = sender->AddPeer("127.0.0.1", port, &error);
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static Rig lockstepRig(false);
    static Rig rollbackRig(true);
    if (size < 1 || size > net::Transport::kMaxDatagram - net::admission::kEnvelopeBytes) return 0;
    std::vector<uint8_t> datagram;
    if ((data[0] & 1) != 0 && size > 16) {
        // A signed token from the input's next 15 bytes, around the rest as the payload.
        bytes::Reader r(std::span<const uint8_t>(data + 1, 15));
        admission::AdmissionToken t;
        t.matchId = r.U8() % 16;
        t.slot = static_cast<uint8_t>(r.U8() % 5);
        t.clientId = r.U8();
        t.expiresAt = 1'800'000'000 + r.U8() % 8;
        t.nonce = r.U64();
        const auto token = admission::TokenSigner(admission::TokenKey{}).Sign(t);
        net::admission::WriteEnvelope(datagram, token, std::span<const uint8_t>(data + 16, size - 16));
    } else {
        datagram.assign(data + 1, data + size);
        if (datagram.empty()) return 0;
    }
    Rig& rig = (data[0] & 2) != 0 ? rollbackRig : lockstepRig;
    const uint64_t before = rig.host->Stats().datagramsIn;
    if (!rig.sender->Send(rig.server, datagram)) return 0;
    for (int spin = 0; spin < 1000 && rig.host->Stats().datagramsIn == before; ++spin) rig.host->Update();
    rig.host->Update();
    std::vector<net::Datagram> answers;
    rig.sender->Poll(answers);
    return 0;
}
