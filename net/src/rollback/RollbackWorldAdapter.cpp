// WorldGameAdapter: rollback requests on a lockbox world and a replay::Game.

#include "lockbox/net/RollbackWorldAdapter.h"

#include <algorithm>
#include <cstdint>
#include <variant>

#include "lockbox/lockbox.h"
#include "lockbox/net/StateHash.h"
#include "lockbox/replay/Game.h"
#include "lockbox/state/WorldHash.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

WorldGameAdapter::WorldGameAdapter(b2World& world, replay::Game& game, WorldStepSettings settings, uint32_t slots)
    : m_world(world), m_game(game), m_settings(settings), m_slots(slots < 3 ? 3 : slots) {
    if (m_settings.tickRate == 0) m_settings.tickRate = 1;
}

uint64_t WorldGameAdapter::StateHash() const { return FoldedStateHash(m_world, m_game); }

bool WorldGameAdapter::ConfirmedSnapshot(const RollbackSession& session, int32_t& frame,
                                         std::vector<uint8_t>& out) const {
    const int32_t f = std::min(session.ConfirmedFrame(), session.CurrentFrame());
    if (f < 0) return false;
    const Slot& s = m_slots[static_cast<size_t>(f) % m_slots.size()];
    if (s.frame != f || s.user.size() > UINT32_MAX) return false;
    // Slots hold rollback frames, which only their world can read: the world visits frame F
    // for a portable image and comes back (restore then step gives the same bits as step).
    m_world.SaveFrame(m_scratch);
    if (!m_world.RestoreFrame(s.state).ok()) return false;
    std::vector<uint8_t> image;
    m_world.Save(image);
    const bool back = m_world.RestoreFrame(m_scratch).ok();
    if (!back || image.size() > UINT32_MAX) return false;
    frame = f;
    PackStateBlob(image, s.user, out);
    return true;
}

bool WorldGameAdapter::RestoreSnapshot(b2World& world, replay::Game& game, std::span<const uint8_t> snapshot) {
    return LoadStateBlob(snapshot, world, game);
}

bool WorldGameAdapter::Execute(RollbackSession& session, std::span<const RollbackRequest> requests) {
    bool rollingBack = false;
    for (const RollbackRequest& r : requests) {
        if (const auto* save = std::get_if<SaveState>(&r)) {
            if (save->frame < 0) return false;
            Slot& s = m_slots[static_cast<size_t>(save->frame) % m_slots.size()];
            s.frame = save->frame;
            m_world.SaveFrame(s.state);
            m_game.SaveUserState(s.user);
            // The session asks for hashes of the frames it compares (every desyncInterval-th):
            // a walk of the world, a few percent of a step, on those frames only.
            if (save->wantHash) session.ReportHash(save->frame, FoldUserState(b2WorldHash(m_world), s.user));
        } else if (const auto* load = std::get_if<LoadState>(&r)) {
            if (load->frame < 0) return false;
            Slot& s = m_slots[static_cast<size_t>(load->frame) % m_slots.size()];
            if (s.frame != load->frame) return false;
            if (!m_world.RestoreFrame(s.state).ok()) return false;
            m_game.LoadUserState(s.user);
            rollingBack = true;
        } else if (const auto* adv = std::get_if<AdvanceRequest>(&r)) {
            StepConfirmedFrame(m_world, m_game, adv->frame, adv->inputs, m_settings.tickRate,
                               m_settings.velocityIterations, m_settings.positionIterations);
            m_lastAdvanced = adv->frame;
            if (rollingBack) ++m_resimulated;
        }
    }
    return true;
}

}  // namespace lockbox::net
