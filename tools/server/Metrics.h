#pragma once
// lockbox_server's metrics in the Prometheus text format (version 0.0.4), as /metrics serves
// them.

#include <cstdint>
#include <string>
#include <vector>

namespace lockbox::server {

class MatchHost;

/// The `q` quantile (per mille, 0 .. 1000) of `samples` by the nearest-rank rule; 0 when empty.
uint32_t Quantile(std::vector<uint32_t> samples, uint32_t perMille);

/// Every metric of `host`: matches, players, datagrams and bytes in and out, admissions,
/// refused tokens and dropped datagrams by reason, desyncs, late joins, replays, and the
/// p50/p99 of the host's update time (its tick).
std::string RenderMetrics(const MatchHost& host);

}  // namespace lockbox::server
