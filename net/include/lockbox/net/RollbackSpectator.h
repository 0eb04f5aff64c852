#pragma once
/// RollbackSpectator (issue 11): watches a rollback match. A host peer (a RollbackPeer with
/// this machine in RollbackPeerConfig::spectators) sends every player's confirmed inputs, the
/// same stream a replay stores; the spectator acknowledges them and hands them out frame by
/// frame. Confirmed inputs never change, so a spectator never rolls back: it applies each
/// frame once, RTT plus the slowest player's latency behind the players.

#include <cstdint>
#include <deque>
#include <vector>

#include "lockbox/net/RollbackProtocol.h"
#include "lockbox/net/Transport.h"

namespace lockbox::net {

/// Settings of a spectator.
struct RollbackSpectatorConfig {
    uint32_t matchId = 1;                   ///< the match's id (RollbackPeerConfig::matchId)
    uint32_t players = 2;                   ///< 1 .. kRollbackMaxPlayers
    uint32_t inputBytes = 8;                ///< 1 .. kRollbackMaxInputBytes
    PeerId host = kNoPeer;                  ///< the peer that sends the confirmed inputs
    uint64_t timeoutMicros = 2000000;       ///< silence after which HostAlive() turns false
    uint32_t maxBufferedFrames = 4096;      ///< frames kept before Next takes them (more are not acked)
};

class RollbackSpectator {
public:
    /// `transport` must outlive the spectator.
    RollbackSpectator(Transport& transport, RollbackSpectatorConfig config);

    /// Reads what arrived from the host; frames must arrive in order (the host resends).
    void Poll();
    /// Acknowledges the frames received so far (one datagram to the host).
    void Flush();
    /// The next frame's inputs (players * inputBytes bytes, player 0 first) and its number;
    /// false when it has not arrived yet.
    bool Next(int32_t& frame, std::vector<uint8_t>& inputs);

    /// Frames before this have arrived.
    int32_t ReceivedFrame() const noexcept { return received_; }
    /// Frames handed out by Next.
    int32_t ConsumedFrame() const noexcept { return consumed_; }
    bool HostAlive() const noexcept { return alive_; }
    /// Datagrams refused (malformed, another match, not from the host).
    uint64_t Refused() const noexcept { return refused_; }

private:
    Transport& transport_;
    RollbackSpectatorConfig config_;
    RollbackShape shape_;
    std::deque<std::vector<uint8_t>> frames_;  // frames [consumed_, received_)
    int32_t received_ = 0;
    int32_t consumed_ = 0;
    uint64_t lastHeard_ = 0;
    bool alive_ = true;
    uint64_t refused_ = 0;
    std::vector<Datagram> inbox_;
    std::vector<RollbackMessage> messages_;
    RollbackDatagramWriter writer_;
};

}  // namespace lockbox::net
