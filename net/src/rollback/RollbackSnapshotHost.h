#pragma once
// What a RollbackPeer keeps per spectator (RollbackPeer.cpp reads datagrams, and
// RollbackSnapshotHost.cpp feeds spectators: the confirmed input stream and late-join
// snapshots).

#include <cstdint>

#include "lockbox/net/RollbackPeer.h"
#include "session/SnapshotTransfer.h"

namespace lockbox::net {

struct RollbackPeer::Spectator {
    PeerId peer = kNoPeer;
    int32_t acked = 0;           // confirmed frames before this were acked
    bool lateJoin = false;       // asked for a snapshot: no input stream before it is acked
    bool wantsSnapshot = false;  // waits for OfferSnapshot
    uint32_t attempt = 0;        // the last join attempt served
    uint64_t checksum = 0;       // XXH3-64 of the snapshot being sent
    SnapshotSender sender;
    bool incompatible = false;  // its hello named another version or shape: not served
    bool late = false;          // joined by asking (maxLateSpectators), not listed
    uint64_t lastHeard = 0;     // when its latest datagram arrived
};

}  // namespace lockbox::net
