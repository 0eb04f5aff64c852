// WorldGameAdapter: rollback requests on a lockbox world and a replay::Game.

#include "lockbox/net/RollbackWorldAdapter.h"

#include <algorithm>
#include <cstdint>
#include <variant>

#include "lockbox/lockbox.h"
#include "lockbox/replay/Game.h"
#include "lockbox/state/WorldHash.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

WorldGameAdapter::WorldGameAdapter(b2World& world, replay::Game& game, WorldStepSettings settings, uint32_t slots)
    : world_(world), game_(game), settings_(settings), slots_(slots < 3 ? 3 : slots) {
    if (settings_.tickRate == 0) settings_.tickRate = 1;
}

uint64_t WorldGameAdapter::StateHash() const { return FoldedStateHash(world_, game_); }

bool WorldGameAdapter::ConfirmedSnapshot(const RollbackSession& session, int32_t& frame,
                                         std::vector<uint8_t>& out) const {
    const int32_t f = std::min(session.ConfirmedFrame(), session.CurrentFrame());
    if (f < 0) return false;
    const Slot& s = slots_[static_cast<size_t>(f) % slots_.size()];
    if (s.frame != f || s.user.size() > UINT32_MAX) return false;
    // Slots hold rollback frames, which only their world can read: the world visits frame F
    // for a portable image and comes back (restore then step gives the same bits as step).
    world_.SaveFrame(scratch_);
    if (!world_.RestoreFrame(s.state).ok()) return false;
    std::vector<uint8_t> image;
    world_.Save(image);
    const bool back = world_.RestoreFrame(scratch_).ok();
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
            Slot& s = slots_[static_cast<size_t>(save->frame) % slots_.size()];
            s.frame = save->frame;
            world_.SaveFrame(s.state);
            game_.SaveUserState(s.user);
            // The session asks for hashes of the frames it compares (every desyncInterval-th):
            // a walk of the world, a few percent of a step, on those frames only.
            if (save->wantHash) session.ReportHash(save->frame, FoldUserState(b2WorldHash(world_), s.user));
        } else if (const auto* load = std::get_if<LoadState>(&r)) {
            if (load->frame < 0) return false;
            Slot& s = slots_[static_cast<size_t>(load->frame) % slots_.size()];
            if (s.frame != load->frame) return false;
            if (!world_.RestoreFrame(s.state).ok()) return false;
            game_.LoadUserState(s.user);
            rollingBack = true;
        } else if (const auto* adv = std::get_if<AdvanceRequest>(&r)) {
            StepConfirmedFrame(world_, game_, adv->frame, adv->inputs, settings_.tickRate, settings_.velocityIterations,
                               settings_.positionIterations);
            lastAdvanced_ = adv->frame;
            if (rollingBack) ++resimulated_;
        }
    }
    return true;
}

}  // namespace lockbox::net
