// The localhost operations endpoint (OpsHttp.h).
#include "OpsHttp.h"

#include <httplib.h>

#include <chrono>

namespace lockbox::server {

namespace {

uint64_t SteadyMillis() {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count());
}

// The main loop turns at least every few milliseconds; five seconds without a turn is a hang.
constexpr uint64_t kHealthyMillis = 5000;

}  // namespace

OpsHttp::OpsHttp() : m_server(std::make_unique<httplib::Server>()) {
    m_server->Get("/healthz", [this](const httplib::Request&, httplib::Response& res) {
        const uint64_t beat = m_heartbeat.load();
        const bool healthy = beat != 0 && SteadyMillis() - beat < kHealthyMillis;
        res.status = healthy ? 200 : 503;
        res.set_content(healthy ? "ok\n" : "main loop stalled\n", "text/plain");
    });
    m_server->Get("/readyz", [this](const httplib::Request&, httplib::Response& res) {
        const bool ready = m_ready.load();
        res.status = ready ? 200 : 503;
        res.set_content(ready ? "ready\n" : "not admitting\n", "text/plain");
    });
    m_server->Get("/metrics", [this](const httplib::Request&, httplib::Response& res) {
        std::lock_guard lock(m_mutex);
        res.set_content(m_metrics, "text/plain; version=0.0.4");
    });
}

OpsHttp::~OpsHttp() { Stop(); }

bool OpsHttp::Start(uint16_t port, std::string& error) {
    if (!m_server->bind_to_port("127.0.0.1", port)) {
        error = "cannot listen on 127.0.0.1:" + std::to_string(port);
        return false;
    }
    m_thread = std::thread([this] { m_server->listen_after_bind(); });
    return true;
}

void OpsHttp::Stop() {
    if (!m_thread.joinable()) return;
    m_server->stop();
    m_thread.join();
}

void OpsHttp::Publish(std::string metrics, bool ready) {
    {
        std::lock_guard lock(m_mutex);
        m_metrics = std::move(metrics);
    }
    m_ready.store(ready);
    m_heartbeat.store(SteadyMillis());
}

}  // namespace lockbox::server
