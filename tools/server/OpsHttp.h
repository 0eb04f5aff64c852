#pragma once
// lockbox_server's operations endpoint on localhost (cpp-httplib): /healthz (the main loop is
// turning), /readyz (listening and admitting: not draining) and /metrics (Prometheus text). The
// main loop publishes; the HTTP thread only reads what was published.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace httplib {
class Server;
}

namespace lockbox::server {

class OpsHttp {
public:
    OpsHttp();
    ~OpsHttp();
    OpsHttp(const OpsHttp&) = delete;
    OpsHttp& operator=(const OpsHttp&) = delete;

    /// Serves on 127.0.0.1:`port` from a thread of its own; false (and `error`) when the port
    /// cannot be bound.
    bool Start(uint16_t port, std::string& error);
    /// Stops serving and joins the thread (also done by the destructor).
    void Stop();

    /// Main loop: the metrics text and the readiness; also the loop's heartbeat for /healthz.
    void Publish(std::string metrics, bool ready);

private:
    std::unique_ptr<httplib::Server> m_server;
    std::thread m_thread;
    std::mutex m_mutex;
    std::string m_metrics;
    std::atomic<bool> m_ready{false};
    std::atomic<uint64_t> m_heartbeat{0};
};

}  // namespace lockbox::server
