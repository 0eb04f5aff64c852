#pragma once
// What a RollbackPeer keeps per remote peer (RollbackPeer.cpp: inputs, acks, time sync,
// hashes; RollbackAgreement.cpp: views and the disconnect agreement).

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "lockbox/net/RollbackPeer.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

struct RollbackPeer::Remote {
    PeerId peer = kNoPeer;
    uint32_t index = 0;
    std::vector<uint32_t> players;
    bool alive = true;
    bool heard = false;         // a valid datagram arrived from it
    bool synchronized = false;  // and it echoed one of ours (RbQualityReply): the start phase's round trip
    uint64_t lastHeard = 0;
    std::array<int32_t, kRollbackMaxPlayers> acked{};  // per local player: frames before are received
    // Per player: the frame this remote announced it froze that player at, -1 when it has not.
    std::array<int32_t, kRollbackMaxPlayers> frozenHeard{};
    RttEstimator rtt;
    bool heardFrame = false;
    int32_t remoteFrame = 0;
    uint64_t remoteFrameAt = 0;
    bool echoPending = false;
    uint64_t echoTime = 0, echoReceivedAt = 0;
    std::deque<int32_t> localAdvantage, remoteAdvantage;
    std::map<int32_t, uint8_t> hashCopies;  // final hash frame -> datagrams that carried it
    int32_t finalHashFrame = -1;            // the newest final hash it sent us (-1: none yet)
    uint64_t finalHash = 0;
    bool interrupted = false;
    uint8_t delayWish = 0;  // the input delay it asked this peer for (RbDelayWish)
    RollbackIncompatibility incompatible = RollbackIncompatibility::e_none;
    // Traffic (RemoteStats): totals, and the bytes of the current one-second window.
    uint64_t datagramsSent = 0, datagramsReceived = 0, bytesSent = 0, bytesReceived = 0;
    uint64_t windowStart = 0, windowSent = 0, windowReceived = 0;
    uint64_t sendBps = 0, receiveBps = 0;  // of the latest whole window
    // Loss estimate from RbQuality's sequence byte: ours to it, and its to us unwrapped (the
    // first and highest seen) with the count of those that arrived.
    uint8_t sendSequence = 0;
    bool sequenceSeen = false;
    uint64_t sequenceFirst = 0, sequenceHighest = 0, sequenceArrived = 0;

    Remote() { frozenHeard.fill(-1); }
};

}  // namespace lockbox::net
