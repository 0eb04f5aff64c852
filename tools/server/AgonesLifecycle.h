#pragma once
// The Agones game-server lifecycle over the SDK sidecar's REST gateway (on localhost, port
// AGONES_SDK_HTTP_PORT): POST /ready once the server listens, POST /health at an interval,
// PUT /metadata/label with the match and player counts when they change, POST /shutdown after
// the last match ended. Calls run on a thread of their own, so a slow or absent sidecar never
// stalls the game loop; each call's outcome is logged.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "JsonLog.h"

namespace lockbox::server {

class AgonesLifecycle {
public:
    /// Calls the sidecar at 127.0.0.1:`port`, with a health ping every `healthMillis`.
    AgonesLifecycle(uint16_t port, uint32_t healthMillis, JsonLog& log);
    /// Finish(2000) if not done yet.
    ~AgonesLifecycle();
    AgonesLifecycle(const AgonesLifecycle&) = delete;
    AgonesLifecycle& operator=(const AgonesLifecycle&) = delete;

    /// The server listens: POST /ready (retried while the sidecar is not up yet), then health pings.
    void Ready();
    /// The counts changed: PUT /metadata/label for "matches" and "players".
    void Counts(size_t matches, size_t players);
    /// The last match ended: POST /shutdown, then waits up to `timeoutMillis` for every queued
    /// call to be made and stops the thread.
    void Finish(uint32_t timeoutMillis);

private:
    struct Call {
        std::string method, path, body;
        int attempts = 1;
    };
    void Enqueue(Call call);
    void Run();

    uint16_t m_port;
    uint32_t m_healthMillis;
    JsonLog& m_log;
    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<Call> m_calls;
    bool m_healthOn = false;
    bool m_stop = false;
    bool m_busy = false;
    size_t m_lastMatches = SIZE_MAX, m_lastPlayers = SIZE_MAX;
    std::thread m_thread;
};

/// The port in AGONES_SDK_HTTP_PORT, or 0 when it is not set or not a port.
uint16_t AgonesPortFromEnvironment();

}  // namespace lockbox::server
