// lockbox_server as a real process: two clients in this process play a match through it over
// loopback UDP, /healthz /readyz /metrics answer, and SIGTERM drains: the server stops admitting
// (/readyz 503), lets the match finish (the clients leave), writes its replay and exits 0; the
// replay verifies with lockbox_replay verify-dir; the Agones lifecycle calls reach a recording
// stand-in for the SDK sidecar.

#include <httplib.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>

#include "server_harness.h"

namespace lockbox::server {
namespace LOCKBOX_TEST_FILE {

namespace fs = std::filesystem;
using testing::TestClient;

uint64_t UnixNow() {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

// A TCP port free a moment ago (the server binds it right after).
uint16_t FreeTcpPort() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    socklen_t len = sizeof a;
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
        ::close(fd);
        return 0;
    }
    ::close(fd);
    return ntohs(a.sin_port);
}

std::string ReadFile(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The child process; killed if the test ends while it still runs.
struct Child {
    pid_t pid = -1;
    ~Child() {
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
    }
    // Waits up to `limit` for the exit while `pump` runs; the exit status, or -1.
    int WaitExit(std::chrono::seconds limit, const std::function<void()>& pump) {
        const auto start = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - start < limit) {
            int status = 0;
            if (::waitpid(pid, &status, WNOHANG) == pid) {
                pid = -1;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            pump();
            std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
        return -1;
    }
};

// Records the calls an Agones SDK sidecar would get ("METHOD PATH BODY"), answering 200.
struct AgonesRecorder {
    httplib::Server server;
    std::thread thread;
    uint16_t port = 0;
    std::mutex mutex;
    std::vector<std::string> calls;

    bool Start() {
        auto record = [this](const httplib::Request& req, httplib::Response& res) {
            std::lock_guard lock(mutex);
            calls.push_back(req.method + " " + req.path + " " + req.body);
            res.set_content("{}", "application/json");
        };
        server.Post(R"(/.*)", record);
        server.Put(R"(/.*)", record);
        const int bound = server.bind_to_any_port("127.0.0.1");
        if (bound <= 0) return false;
        port = static_cast<uint16_t>(bound);
        thread = std::thread([this] { server.listen_after_bind(); });
        return true;
    }
    std::vector<std::string> Calls() {
        std::lock_guard lock(mutex);
        return calls;
    }
    ~AgonesRecorder() {
        server.stop();
        if (thread.joinable()) thread.join();
    }
};

TEST(ServerProcess, PlaysServesMetricsAndDrainsOnSigterm) {
    const fs::path dir = fs::temp_directory_path() / ("lockbox_server_process_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "replays");
    {
        std::ofstream key(dir / "key");
        key << admission::KeyHex(testing::TestKey()) << "\n";
    }
    const uint16_t httpPort = FreeTcpPort();
    ASSERT_NE(httpPort, 0);
    // A stand-in for the Agones SDK sidecar that records every call.
    AgonesRecorder agones;
    ASSERT_TRUE(agones.Start());
    const std::vector<std::string> args = {LOCKBOX_SERVER_PROGRAM,
                                           "--token-key-file",
                                           (dir / "key").string(),
                                           "--port-file",
                                           (dir / "port").string(),
                                           "--http-port",
                                           std::to_string(httpPort),
                                           "--log",
                                           (dir / "log.jsonl").string(),
                                           "--tick-rate",
                                           "240",
                                           "--hash-interval",
                                           "20",
                                           "--scene",
                                           "vertical_stack",
                                           "--replay-dir",
                                           (dir / "replays").string(),
                                           "--drain-seconds",
                                           "20",
                                           "--agones-health-seconds",
                                           "1"};
    Child child;
    child.pid = ::fork();
    ASSERT_GE(child.pid, 0);
    if (child.pid == 0) {
        std::vector<char*> argv;
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::setenv("AGONES_SDK_HTTP_PORT", std::to_string(agones.port).c_str(), 1);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    // The port file appears once the server listens.
    uint16_t port = 0;
    for (int i = 0; i < 200 && port == 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (fs::exists(dir / "port")) port = static_cast<uint16_t>(std::stoi(ReadFile(dir / "port")));
    }
    ASSERT_NE(port, 0) << "the server did not start";

    httplib::Client http("127.0.0.1", httpPort);
    http.set_connection_timeout(2);
    // /healthz answers once the main loop published.
    int healthz = 0;
    for (int i = 0; i < 100 && healthz != 200; ++i) {
        if (auto r = http.Get("/healthz")) healthz = r->status;
        if (healthz != 200) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_EQ(healthz, 200);
    auto ready = http.Get("/readyz");
    ASSERT_TRUE(ready);
    EXPECT_EQ(ready->status, 200);

    constexpr int32_t kFrames = 120;
    std::vector<std::unique_ptr<TestClient>> clients;
    const uint64_t now = UnixNow();
    for (uint8_t slot = 0; slot < 2; ++slot)
        clients.push_back(
            std::make_unique<TestClient>(port, testing::Mint(5, slot, 50 + slot, now + 60), 300 + slot, kFrames - 1));
    testing::Pump([] {}, clients,
                  [&] { return clients[0]->client->Frame() >= kFrames && clients[1]->client->Frame() >= kFrames; });
    ASSERT_GE(clients[0]->client->Frame(), kFrames);
    ASSERT_GE(clients[1]->client->Frame(), kFrames);
    EXPECT_EQ(clients[0]->worldHash, clients[1]->worldHash);

    // Published every 200 ms.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    auto metrics = http.Get("/metrics");
    ASSERT_TRUE(metrics);
    EXPECT_EQ(metrics->status, 200);
    EXPECT_NE(metrics->body.find("lockbox_server_matches 1\n"), std::string::npos) << metrics->body;
    EXPECT_NE(metrics->body.find("lockbox_server_admitted_total 2\n"), std::string::npos) << metrics->body;

    // SIGTERM: the server stops admitting but the match plays on.
    ASSERT_EQ(::kill(child.pid, SIGTERM), 0);
    const int32_t frameAtSignal = clients[0]->client->Frame();
    testing::Pump([] {}, clients, [&] { return clients[0]->client->Frame() >= frameAtSignal + 60; },
                  std::chrono::seconds(10));
    EXPECT_GE(clients[0]->client->Frame(), frameAtSignal + 60) << "the match stopped at the signal";
    ready = http.Get("/readyz");
    ASSERT_TRUE(ready);
    EXPECT_EQ(ready->status, 503);
    // The players leave: the match ends, its replay is written, the server exits 0.
    for (auto& c : clients) c->client->Leave();
    EXPECT_EQ(child.WaitExit(std::chrono::seconds(15), [] {}), 0);

    const std::string log = ReadFile(dir / "log.jsonl");
    EXPECT_NE(log.find("\"event\":\"draining\""), std::string::npos) << log;
    EXPECT_NE(log.find("\"event\":\"replay_written\""), std::string::npos) << log;
    EXPECT_NE(log.find("\"event\":\"stopped\""), std::string::npos) << log;
    // The fleet lifecycle: ready first, health pings, the match count as a label, shutdown last.
    const std::vector<std::string> calls = agones.Calls();
    ASSERT_FALSE(calls.empty());
    EXPECT_EQ(calls.front(), "POST /ready {}");
    EXPECT_EQ(calls.back(), "POST /shutdown {}");
    const auto has = [&](const std::string& c) { return std::find(calls.begin(), calls.end(), c) != calls.end(); };
    EXPECT_TRUE(has("POST /health {}"));
    EXPECT_TRUE(has("PUT /metadata/label {\"key\":\"matches\",\"value\":\"1\"}"));
    EXPECT_TRUE(has("PUT /metadata/label {\"key\":\"players\",\"value\":\"2\"}"));
    EXPECT_TRUE(has("PUT /metadata/label {\"key\":\"matches\",\"value\":\"0\"}"));

    // Every replay written verifies with lockbox_replay verify-dir.
    const std::string command =
        std::string(LOCKBOX_REPLAY_PROGRAM) + " verify-dir " + (dir / "replays").string() + " 2>&1";
    std::FILE* pipe = ::popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string printed;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) printed += buffer;
    EXPECT_EQ(::pclose(pipe), 0) << printed;
    EXPECT_NE(printed.find("match-5.lbr: verified"), std::string::npos) << printed;
    EXPECT_NE(printed.find("1 replays: 1 verified, 0 diverged, 0 corrupt"), std::string::npos) << printed;
    fs::remove_all(dir);
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox::server
