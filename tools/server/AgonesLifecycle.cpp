// Agones SDK REST calls on their own thread (AgonesLifecycle.h).
#include "AgonesLifecycle.h"

#include <httplib.h>

#include <chrono>
#include <cstdlib>
#include <string_view>

namespace lockbox::server {

namespace {
// The sidecar may start after the game server: /ready is retried this many times, 500 ms apart.
constexpr int kReadyAttempts = 20;
}  // namespace

uint16_t AgonesPortFromEnvironment() {
    const char* text = std::getenv("AGONES_SDK_HTTP_PORT");
    if (text == nullptr || *text == '\0') return 0;
    uint32_t port = 0;
    for (const char* c = text; *c != '\0'; ++c) {
        if (*c < '0' || *c > '9' || port > 65535) return 0;
        port = port * 10 + static_cast<uint32_t>(*c - '0');
    }
    return port <= 65535 ? static_cast<uint16_t>(port) : 0;
}

AgonesLifecycle::AgonesLifecycle(uint16_t port, uint32_t healthMillis, JsonLog& log)
    : m_port(port), m_healthMillis(healthMillis < 100 ? 100 : healthMillis), m_log(log) {
    m_thread = std::thread([this] { Run(); });
}

AgonesLifecycle::~AgonesLifecycle() { Finish(2000); }

void AgonesLifecycle::Enqueue(Call call) {
    {
        std::lock_guard lock(m_mutex);
        if (m_stop) return;
        m_calls.push_back(std::move(call));
    }
    m_wake.notify_all();
}

void AgonesLifecycle::Ready() { Enqueue({"POST", "/ready", "{}", kReadyAttempts}); }

void AgonesLifecycle::Counts(size_t matches, size_t players) {
    // Label values are Kubernetes label values: short decimal text is valid.
    if (matches != m_lastMatches)
        Enqueue({"PUT", "/metadata/label", "{\"key\":\"matches\",\"value\":\"" + std::to_string(matches) + "\"}"});
    if (players != m_lastPlayers)
        Enqueue({"PUT", "/metadata/label", "{\"key\":\"players\",\"value\":\"" + std::to_string(players) + "\"}"});
    m_lastMatches = matches;
    m_lastPlayers = players;
}

void AgonesLifecycle::Finish(uint32_t timeoutMillis) {
    if (!m_thread.joinable()) return;
    Enqueue({"POST", "/shutdown", "{}"});
    {
        std::unique_lock lock(m_mutex);
        m_wake.wait_for(lock, std::chrono::milliseconds(timeoutMillis), [this] { return m_calls.empty() && !m_busy; });
        m_stop = true;
    }
    m_wake.notify_all();
    m_thread.join();
}

void AgonesLifecycle::Run() {
    httplib::Client client("127.0.0.1", m_port);
    client.set_connection_timeout(1);
    client.set_read_timeout(2);
    auto nextHealth = std::chrono::steady_clock::now();
    std::unique_lock lock(m_mutex);
    while (!m_stop) {
        const bool healthDue = m_healthOn && std::chrono::steady_clock::now() >= nextHealth;
        if (m_calls.empty() && !healthDue) {
            if (m_healthOn)
                m_wake.wait_until(lock, nextHealth);
            else
                m_wake.wait(lock);
            continue;
        }
        Call call;
        if (!m_calls.empty()) {
            call = std::move(m_calls.front());
            m_calls.pop_front();
        } else {
            call = {"POST", "/health", "{}"};
            nextHealth = std::chrono::steady_clock::now() + std::chrono::milliseconds(m_healthMillis);
        }
        m_busy = true;
        lock.unlock();
        int status = 0;
        for (int attempt = 0; attempt < call.attempts && status != 200; ++attempt) {
            if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(500));
            const httplib::Result r = call.method == "PUT"
                                          ? client.Put(call.path.c_str(), call.body, "application/json")
                                          : client.Post(call.path.c_str(), call.body, "application/json");
            status = r ? r->status : 0;
        }
        // Health pings are logged only when they fail: one line every interval would drown the log.
        if (call.path != "/health" || status != 200)
            m_log.Event("agones").Str("call", call.method + " " + call.path).Int("status", status);
        lock.lock();
        m_busy = false;
        if (call.path == "/ready" && status == 200) {
            m_healthOn = true;
            nextHealth = std::chrono::steady_clock::now();
        }
        m_wake.notify_all();
    }
}

}  // namespace lockbox::server
