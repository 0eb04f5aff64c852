// WorldGameAdapter: rollback requests on a lockbox world and a replay::Game.

#include "lockbox/net/RollbackWorldAdapter.h"

#include <algorithm>
#include <cstdint>
#include <variant>

#include "SessionCommon.h"
#include "lockbox/lockbox.h"
#include "lockbox/state/WorldHash.h"
#include "lockbox/replay/Game.h"

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
    if (s.frame != f || s.image.size() > UINT32_MAX || s.user.size() > UINT32_MAX) return false;
    frame = f;
    PackStateBlob(s.image, s.user, out);
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
            world_.Save(s.image);
            game_.SaveUserState(s.user);
            // A hash of every kept state makes a later desync report name the first bad frame
            // the session compares. Read from the image just written, it equals StateHash()
            // at a fifth of a walk's cost (under 1 % of a step for 1,000 bodies).
            if (save->wantHash) {
                const b2SnapshotHashResult h = b2SnapshotHash(s.image);
                session.ReportHash(save->frame, h.ok() ? FoldUserState(h.total, s.user) : StateHash());
            }
        } else if (const auto* load = std::get_if<LoadState>(&r)) {
            if (load->frame < 0) return false;
            Slot& s = slots_[static_cast<size_t>(load->frame) % slots_.size()];
            if (s.frame != load->frame) return false;
            if (!world_.Restore(s.image).ok()) return false;
            game_.LoadUserState(s.user);
            rollingBack = true;
        } else if (const auto* adv = std::get_if<AdvanceRequest>(&r)) {
            StepConfirmedFrame(world_, game_, adv->frame, adv->inputs, settings_.tickRate,
                               settings_.velocityIterations, settings_.positionIterations);
            lastAdvanced_ = adv->frame;
            if (rollingBack) ++resimulated_;
        }
    }
    return true;
}

}  // namespace lockbox::net
