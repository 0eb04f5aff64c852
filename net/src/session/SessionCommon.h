#pragma once
// Pieces shared by LockstepServer and LockstepClient: integer RTT smoothing, frame timing and
// the step of one confirmed frame.

#include <cstdint>
#include <span>
#include <vector>

#include "lockbox/net/Protocol.h"
#include "lockbox/net/StateHash.h"  // the hash fold, used by every session

namespace lockbox {
class b2World;
class WorldGame;
}  // namespace lockbox

namespace lockbox::net {

/// RFC 6298-style smoothing in integer microseconds: srtt += (sample - srtt) / 8,
/// rttvar += (|sample - srtt| - rttvar) / 4.
class RttEstimator {
public:
    void Sample(uint64_t micros) noexcept {
        if (m_samples == 0) {
            m_srtt = micros;
            m_var = micros / 2;
        } else {
            const uint64_t dev = micros > m_srtt ? micros - m_srtt : m_srtt - micros;
            m_var = m_var - m_var / 4 + dev / 4;
            m_srtt = m_srtt - m_srtt / 8 + micros / 8;
        }
        ++m_samples;
    }
    uint64_t Srtt() const noexcept { return m_srtt; }
    uint64_t Var() const noexcept { return m_var; }
    uint32_t Samples() const noexcept { return m_samples; }

private:
    uint64_t m_srtt = 0, m_var = 0;
    uint32_t m_samples = 0;
};

/// Microseconds per frame, rounded down (tickRate >= 1).
inline uint64_t TickMicros(uint32_t tickRate) noexcept { return 1'000'000u / (tickRate == 0 ? 1u : tickRate); }

/// The late-join state blob of lockstep and rollback sessions, from a b2World::Save image and
/// the game's user state: u32 image size, the image, u32 user size, the user state (sizes
/// little-endian). Replaces `out`.
void PackStateBlob(std::span<const uint8_t> image, std::span<const uint8_t> user, std::vector<uint8_t>& out);
/// Restores a PackStateBlob into `world` and `game`; false when the sizes do not add up or the
/// world refuses the image (the game is then untouched).
bool LoadStateBlob(std::span<const uint8_t> blob, b2World& world, WorldGame& game);

}  // namespace lockbox::net
