// RollbackMatchBuilder: every setting of a match checked in one place (RollbackMatch.h).
#include <algorithm>
#include <string>
#include <utility>

#include "lockbox/net/RollbackMatch.h"
#include "lockbox/net/UdpTransport.h"

namespace lockbox::net {

const char* MatchSettingName(MatchSetting setting) noexcept {
    switch (setting) {
        case MatchSetting::e_none: return "none";
        case MatchSetting::e_players: return "players";
        case MatchSetting::e_localPlayers: return "local players";
        case MatchSetting::e_remotePlayers: return "remote players";
        case MatchSetting::e_inputBytes: return "input bytes";
        case MatchSetting::e_inputDelay: return "input delay";
        case MatchSetting::e_predictionWindow: return "prediction window";
        case MatchSetting::e_startTimeout: return "start timeout";
        case MatchSetting::e_disconnectTimeout: return "disconnect timeout";
        case MatchSetting::e_world: return "world";
        case MatchSetting::e_transport: return "transport";
        case MatchSetting::e_latency: return "latency";
        case MatchSetting::e_address: return "remote address";
        case MatchSetting::e_port: return "port";
    }
    return "unknown";
}

RollbackMatchBuilder& RollbackMatchBuilder::Players(uint32_t players) {
    m_players = players;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::LocalPlayer(uint32_t player) {
    m_local.push_back(player);
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::RemotePlayer(uint32_t player, std::string host, uint16_t port) {
    m_remotes.push_back(Remote{player, std::move(host), port, kNoPeer});
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::RemotePlayer(uint32_t player, PeerId peer) {
    m_remotes.push_back(Remote{player, {}, 0, peer});
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::InputBytes(uint32_t bytes) {
    m_inputBytes = bytes;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::InputDelay(uint32_t frames) {
    m_inputDelay = frames;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::PredictionWindow(uint32_t frames) {
    m_window = frames;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::DesyncInterval(uint32_t frames) {
    m_desyncInterval = frames;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::StartTimeoutMicros(uint64_t micros) {
    m_startTimeout = micros;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::DisconnectTimeoutMicros(uint64_t micros) {
    m_disconnectTimeout = micros;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::MatchId(uint32_t id) {
    m_matchId = id;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::UseTransport(Transport& transport) {
    m_transport = &transport;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::UdpPort(uint16_t port, std::string bindHost) {
    m_udp = true;
    m_udpPort = port;
    m_bindHost = std::move(bindHost);
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::Latency(const LatencyProfile& profile, uint64_t seed) {
    m_latency = true;
    m_latencyProfile = profile;
    m_latencySeed = seed;
    return *this;
}
RollbackMatchBuilder& RollbackMatchBuilder::World(b2World& world, WorldGame& game, WorldStepSettings step) {
    m_world = &world;
    m_game = &game;
    m_step = step;
    return *this;
}

namespace {

RollbackMatchBuild Refuse(MatchSetting setting, std::string message) {
    RollbackMatchBuild out;
    out.error.setting = setting;
    out.error.message = std::string(MatchSettingName(setting)) + ": " + std::move(message);
    return out;
}

std::string Range(const char* what, uint32_t value, uint32_t lo, uint32_t hi) {
    return std::string(what) + " must be " + std::to_string(lo) + " .. " + std::to_string(hi) + ", not " +
           std::to_string(value);
}

}  // namespace

RollbackMatchBuild RollbackMatchBuilder::Build() const {
    using S = MatchSetting;
    if (m_players < 1 || m_players > kRollbackMaxPlayers)
        return Refuse(S::e_players, Range("the player count", m_players, 1, kRollbackMaxPlayers));
    if (m_local.empty()) return Refuse(S::e_localPlayers, "none given (call LocalPlayer)");
    std::vector<int> role(m_players, 0);  // 0: unassigned, 1: local, 2: remote
    for (uint32_t p : m_local) {
        if (p >= m_players)
            return Refuse(S::e_localPlayers, "player " + std::to_string(p) + " is not below the player count " +
                                                 std::to_string(m_players));
        if (role[p] != 0) return Refuse(S::e_localPlayers, "player " + std::to_string(p) + " is given twice");
        role[p] = 1;
    }
    for (const Remote& r : m_remotes) {
        const std::string who = "player " + std::to_string(r.player);
        if (r.player >= m_players)
            return Refuse(S::e_remotePlayers, who + " is not below the player count " + std::to_string(m_players));
        if (role[r.player] == 1) return Refuse(S::e_remotePlayers, who + " is local already");
        if (role[r.player] == 2) return Refuse(S::e_remotePlayers, who + " is given twice");
        role[r.player] = 2;
    }
    for (uint32_t p = 0; p < m_players; ++p)
        if (role[p] == 0)
            return Refuse(S::e_remotePlayers, "player " + std::to_string(p) + " is neither local nor remote");
    if (m_inputBytes < 1 || m_inputBytes > kRollbackMaxInputBytes)
        return Refuse(S::e_inputBytes, Range("bytes per input", m_inputBytes, 1, kRollbackMaxInputBytes));
    if (m_inputDelay > kRollbackMaxInputDelay)
        return Refuse(S::e_inputDelay, Range("frames", m_inputDelay, 0, kRollbackMaxInputDelay));
    if (m_window < 1 || m_window > kRollbackMaxWindow)
        return Refuse(S::e_predictionWindow, Range("frames", m_window, 1, kRollbackMaxWindow));
    if (m_startTimeout < 1) return Refuse(S::e_startTimeout, "must be at least 1 microsecond");
    if (m_disconnectTimeout < 2) return Refuse(S::e_disconnectTimeout, "must be at least 2 microseconds");
    if (m_world == nullptr || m_game == nullptr) return Refuse(S::e_world, "none given (call World)");
    if (m_step.tickRate < 1) return Refuse(S::e_world, "the tick rate must be at least 1");
    if ((m_transport != nullptr) == m_udp)
        return Refuse(S::e_transport, m_udp ? "both UseTransport and UdpPort given; choose one"
                                            : "none given (call UseTransport or UdpPort)");
    auto* givenUdp = dynamic_cast<UdpTransport*>(m_transport);
    for (const Remote& r : m_remotes) {
        const std::string who = "player " + std::to_string(r.player);
        if (r.peer == kNoPeer && !m_udp && givenUdp == nullptr)
            return Refuse(S::e_transport, who + " is given by address, which needs UdpPort or a UdpTransport");
        if (r.peer != kNoPeer && m_udp)
            return Refuse(S::e_transport, who + " is given by PeerId, which needs UseTransport");
        if (r.peer == kNoPeer && (r.host.empty() || r.port == 0))
            return Refuse(S::e_address, who + " needs a numeric host and a port in 1 .. 65535");
    }
    const LatencyProfile& lp = m_latencyProfile;
    for (uint32_t rate : {lp.lossPermille, lp.duplicatePermille, lp.reorderPermille})
        if (m_latency && rate > 1000) return Refuse(S::e_latency, Range("a rate in per mille", rate, 0, 1000));

    // Everything that can be checked is; now the socket and the addresses.
    std::unique_ptr<RollbackMatch> match(new RollbackMatch());
    RollbackMatch& m = *match;
    Transport* base = m_transport;
    UdpTransport* udp = givenUdp;
    if (m_udp) {
        std::string error;
        m.m_udp = UdpTransport::Open(m_bindHost, m_udpPort, &error);
        if (!m.m_udp)
            return Refuse(S::e_port, "cannot open UDP " + m_bindHost + ":" + std::to_string(m_udpPort) + ": " + error);
        base = m.m_udp.get();
        udp = m.m_udp.get();
    }
    RollbackPeerConfig peerConfig;
    peerConfig.matchId = m_matchId;
    peerConfig.tickRate = m_step.tickRate;
    peerConfig.startTimeoutMicros = m_startTimeout;
    peerConfig.disconnectTimeoutMicros = m_disconnectTimeout;
    peerConfig.interruptTimeoutMicros = std::min<uint64_t>(peerConfig.interruptTimeoutMicros, m_disconnectTimeout / 2);
    for (const Remote& r : m_remotes) {
        PeerId peer = r.peer;
        std::string name = "peer " + std::to_string(r.peer);
        if (peer == kNoPeer) {
            std::string error;
            peer = udp->AddPeer(r.host, r.port, &error);
            if (peer == kNoPeer)
                return Refuse(S::e_address, "player " + std::to_string(r.player) + " at " + r.host + ":" +
                                                std::to_string(r.port) + ": " + error);
            name = udp->PeerAddress(peer);
        }
        auto same = std::find_if(peerConfig.remotes.begin(), peerConfig.remotes.end(),
                                 [&](const RollbackRemote& x) { return x.peer == peer; });
        if (same != peerConfig.remotes.end()) {
            same->players.push_back(r.player);
        } else {
            peerConfig.remotes.push_back(RollbackRemote{peer, {r.player}});
            m.m_remoteNames.push_back(std::move(name));
        }
    }
    m.m_net = base;
    if (m_latency) {
        m.m_latency = std::make_unique<LatencyTransport>(*base, m_latencyProfile, m_latencySeed);
        m.m_net = m.m_latency.get();
    }
    RollbackSessionBuilder session;
    session.Players(m_players)
        .InputBytes(m_inputBytes)
        .InputDelay(m_inputDelay)
        .PredictionWindow(m_window)
        .DesyncInterval(m_desyncInterval);
    for (uint32_t p : m_local) session.LocalPlayer(p);
    m.m_session = session.Build();
    if (!m.m_session) return Refuse(S::e_players, std::string(session.Check()));  // checked above; never
    m.m_adapter = std::make_unique<WorldGameAdapter>(*m_world, *m_game, m_step);
    m.m_peer = std::make_unique<RollbackPeer>(*m.m_session, *m.m_net, peerConfig);
    m.m_world = m_world;
    m.m_game = m_game;
    m.m_tickRate = m_step.tickRate;
    m.m_local = m_local;
    std::sort(m.m_local.begin(), m.m_local.end());
    m.m_input.assign(m_inputBytes, 0);
    m.m_end.remotes.resize(peerConfig.remotes.size());
    RollbackMatchBuild out;
    out.match = std::move(match);
    return out;
}

}  // namespace lockbox::net
