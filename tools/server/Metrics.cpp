// Prometheus text of a MatchHost (Metrics.h).
#include "Metrics.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>

#include "MatchHost.h"

namespace lockbox::server {

namespace {

void Metric(std::string& out, const char* name, const char* type, const char* help, uint64_t value) {
    out += std::string("# HELP ") + name + " " + help + "\n# TYPE " + name + " " + type + "\n";
    out += std::string(name) + " " + std::to_string(value) + "\n";
}

// Microseconds as seconds with six decimals, written with integers only.
std::string Seconds(uint32_t micros) {
    std::string frac = std::to_string(micros % 1'000'000);
    return std::to_string(micros / 1'000'000) + "." + std::string(6 - frac.size(), '0') + frac;
}

// Resident memory of this process (Linux /proc/self/statm: pages; 0 when unreadable).
uint64_t ResidentBytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return 0;
    return resident * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
}

}  // namespace

uint32_t Quantile(std::vector<uint32_t> samples, uint32_t perMille) {
    if (samples.empty()) return 0;
    std::sort(samples.begin(), samples.end());
    // Nearest rank: the smallest sample with at least perMille/1000 of the samples at or below it.
    size_t rank = (samples.size() * std::min<uint32_t>(perMille, 1000) + 999) / 1000;
    rank = std::max<size_t>(rank, 1);
    return samples[rank - 1];
}

std::string RenderMetrics(const MatchHost& host) {
    const HostStats& s = host.Stats();
    std::string out;
    Metric(out, "lockbox_server_matches", "gauge", "Matches running now.", host.MatchCount());
    Metric(out, "lockbox_server_players", "gauge", "Clients admitted now.", host.PlayerCount());
    Metric(out, "lockbox_server_resident_bytes", "gauge", "Resident memory of the process (RSS).", ResidentBytes());
    Metric(out, "lockbox_server_draining", "gauge", "1 once SIGTERM started the drain.", host.Draining() ? 1 : 0);
    Metric(out, "lockbox_server_datagrams_in_total", "counter", "Datagrams received.", s.datagramsIn);
    Metric(out, "lockbox_server_datagrams_out_total", "counter", "Datagrams sent.", s.datagramsOut);
    Metric(out, "lockbox_server_bytes_in_total", "counter", "Payload bytes received.", s.bytesIn);
    Metric(out, "lockbox_server_bytes_out_total", "counter", "Payload bytes sent.", s.bytesOut);
    Metric(out, "lockbox_server_admitted_total", "counter", "Clients admitted with a valid token.", s.admitted);
    Metric(out, "lockbox_server_matches_created_total", "counter", "Matches created.", s.matchesCreated);
    Metric(out, "lockbox_server_matches_ended_total", "counter", "Matches ended.", s.matchesEnded);
    Metric(out, "lockbox_server_desyncs_total", "counter", "Matches whose clients' hashes diverged.", s.desyncs);
    Metric(out, "lockbox_server_late_joins_total", "counter", "Late joiners admitted into a running match.",
           s.lateJoins);
    Metric(out, "lockbox_server_replays_written_total", "counter", "Replays written.", s.replaysWritten);
    Metric(out, "lockbox_server_replay_failures_total", "counter", "Replays that could not be written.",
           s.replayFailures);
    Metric(out, "lockbox_server_rebound_total", "counter",
           "Admitted addresses taken over by a new client's fresh token (a departed client's port reused).", s.rebound);
    Metric(out, "lockbox_server_held_before_handshake_total", "counter",
           "Sends held back so that a client is never sent more than it sent before its handshake.",
           s.heldBeforeHandshake);
    out +=
        "# HELP lockbox_server_refused_tokens_total Admission tokens refused, by reason.\n"
        "# TYPE lockbox_server_refused_tokens_total counter\n";
    for (size_t i = 1; i < s.refusedTokens.size(); ++i)
        out += "lockbox_server_refused_tokens_total{reason=\"" +
               std::string(admission::RefusalName(static_cast<admission::Refusal>(i))) + "\"} " +
               std::to_string(s.refusedTokens[i]) + "\n";
    out +=
        "# HELP lockbox_server_dropped_datagrams_total Datagrams dropped unread (senders not admitted, admitted ones "
        "over "
        "their bandwidth or claiming another slot), "
        "by reason.\n# TYPE lockbox_server_dropped_datagrams_total counter\n";
    for (size_t i = 0; i < s.dropped.size(); ++i)
        out += std::string("lockbox_server_dropped_datagrams_total{reason=\"") + DropName(static_cast<Drop>(i)) +
               "\"} " + std::to_string(s.dropped[i]) + "\n";
    out +=
        "# HELP lockbox_server_tick_seconds Time of one server update (read, route, update every match), "
        "over the latest 4096 updates.\n# TYPE lockbox_server_tick_seconds gauge\n";
    out += "lockbox_server_tick_seconds{quantile=\"0.5\"} " + Seconds(Quantile(host.UpdateMicros(), 500)) + "\n";
    out += "lockbox_server_tick_seconds{quantile=\"0.99\"} " + Seconds(Quantile(host.UpdateMicros(), 990)) + "\n";
    return out;
}

}  // namespace lockbox::server
