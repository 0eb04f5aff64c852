// WorldGameAdapter: rollback requests on a lockbox world and a WorldGame.

#include "lockbox/net/RollbackWorldAdapter.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <variant>

#include "lockbox/lockbox.h"
#include "lockbox/net/StateHash.h"
#include "lockbox/replay/Recorder.h"
#include "lockbox/state/WorldGame.h"
#include "lockbox/state/WorldHash.h"
#include "session/SessionCommon.h"

namespace lockbox::net {

WorldGameAdapter::WorldGameAdapter(b2World& world, WorldGame& game, WorldStepSettings settings, uint32_t slots)
    : m_world(world), m_game(game), m_settings(settings), m_slots(slots < 3 ? 3 : slots) {
    if (m_settings.tickRate == 0) m_settings.tickRate = 1;
}

uint64_t WorldGameAdapter::StateHash() const { return FoldedStateHash(m_world, m_game); }

bool WorldGameAdapter::Visit(const Slot& s, std::vector<uint8_t>* image, uint64_t* hash) const {
    // Slots hold rollback frames, which only their world can read: the world visits the slot
    // and comes back (restore then step gives the same bits as step).
    m_world.SaveFrame(m_scratch);
    if (!m_world.RestoreFrame(s.state).ok()) return false;
    if (image != nullptr) m_world.Save(*image);
    if (hash != nullptr) *hash = b2WorldHash(m_world);
    return m_world.RestoreFrame(m_scratch).ok();
}

bool WorldGameAdapter::ConfirmedSnapshot(const RollbackSession& session, int32_t& frame,
                                         std::vector<uint8_t>& out) const {
    const int32_t f = std::min(session.ConfirmedFrame(), session.CurrentFrame());
    if (f < 0) return false;
    const Slot& s = m_slots[static_cast<size_t>(f) % m_slots.size()];
    if (s.frame != f || s.user.size() > UINT32_MAX) return false;
    std::vector<uint8_t> image;
    if (!Visit(s, &image, nullptr) || image.size() > UINT32_MAX) return false;
    frame = f;
    PackStateBlob(image, s.user, out);
    return true;
}

bool WorldGameAdapter::Record(replay::Recorder& recorder, int32_t frames) {
    if (m_lastAdvanced >= 0 || frames < 0 || m_recorder != nullptr) return false;
    m_recorder = &recorder;
    m_recordEnd = frames == 0 ? INT32_MAX : frames;
    m_recorded = 0;
    m_recordFinished = m_recordFailed = false;
    return true;
}

bool WorldGameAdapter::RecordWantsHash(int32_t frame) const noexcept {
    // The state at `frame` is the one after frame - 1: its hash is stored on the interval, and
    // the last one recorded ends the file.
    if (m_recorder == nullptr || m_recordFinished || frame <= m_recorded || frame > m_recordEnd) return false;
    return frame % static_cast<int32_t>(m_recorder->Config().hashInterval) == 0 || frame == m_recordEnd;
}

void WorldGameAdapter::RecordFinal(const RollbackSession& session) {
    // Right after a batch is executed every frame the session calls final was simulated with
    // its final inputs (a pending rollback is part of the batch), so its saved state is final.
    const int32_t limit = std::min({session.ConfirmedFrame(), session.CurrentFrame(), m_recordEnd});
    replay::Keyframe state;
    while (m_recorded < limit) {
        const int32_t f = m_recorded;
        const Slot& in = SlotOf(f);
        const Slot& after = SlotOf(f + 1);
        if (in.inputFrame != f || after.frame != f + 1) {
            m_recordFailed = true;
            return;
        }
        uint64_t hash = after.worldHash;
        const bool wantHash =
            (f + 1) % static_cast<int32_t>(m_recorder->Config().hashInterval) == 0 || f + 1 == m_recordEnd;
        const bool keyframe = m_recorder->KeyframeDue();
        if (keyframe) {
            state.user = after.user;
            if (!Visit(after, &state.world, &state.hash)) {
                m_recordFailed = true;
                return;
            }
            hash = state.hash;
        } else if (wantHash && !after.hashed && !Visit(after, nullptr, &hash)) {
            m_recordFailed = true;
            return;
        }
        m_recorder->AppendFinal(in.inputs, wantHash ? hash : 0, keyframe ? &state : nullptr);
        ++m_recorded;
        if (m_recorded == m_recordEnd) {
            m_recordFinished = true;
            if (!m_recorder->Finish(hash).ok()) m_recordFailed = true;
            return;
        }
    }
}

bool WorldGameAdapter::FinishRecording(const RollbackSession& session) {
    if (m_recorder == nullptr || m_recordFailed) return false;
    if (m_recordFinished) return true;
    RecordFinal(session);
    if (m_recordFailed) return false;
    if (m_recordFinished) return true;
    m_recordFinished = true;
    if (!m_recorder->Begun() && !m_recorder->Begin().ok()) return false;
    // The state after the last recorded frame (the seed's when none was).
    const Slot& last = SlotOf(m_recorded);
    uint64_t hash = last.worldHash;
    if (last.frame != m_recorded || (!last.hashed && !Visit(last, nullptr, &hash))) {
        m_recordFailed = true;
        return false;
    }
    return m_recorder->Finish(hash).ok();
}

bool WorldGameAdapter::RestoreSnapshot(b2World& world, WorldGame& game, std::span<const uint8_t> snapshot) {
    return LoadStateBlob(snapshot, world, game);
}

bool WorldGameAdapter::Execute(RollbackSession& session, std::span<const RollbackRequest> requests) {
    const bool ok = Execute(requests, [&session](int32_t frame, uint64_t hash) { session.ReportHash(frame, hash); });
    if (ok && m_recorder != nullptr && !m_recordFinished && !m_recordFailed) RecordFinal(session);
    return ok;
}

bool WorldGameAdapter::Execute(std::span<const RollbackRequest> requests, const RollbackHashReport& reportHash) {
    bool rollingBack = false;
    for (const RollbackRequest& r : requests) {
        if (const auto* save = std::get_if<SaveState>(&r)) {
            if (save->frame < 0) return false;
            if (save->frame == 0 && m_recorder != nullptr && !m_recorder->Begun() && !m_recorder->Begin().ok())
                m_recordFailed = true;
            Slot& s = SlotOf(save->frame);
            s.frame = save->frame;
            m_world.SaveFrame(s.state);
            m_game.SaveUserState(s.user);
            // The session asks for hashes of the frames it compares (every desyncInterval-th),
            // a recording for those it stores: a walk of the world, a few percent of a step.
            s.hashed = save->wantHash || RecordWantsHash(save->frame);
            if (s.hashed) s.worldHash = b2WorldHash(m_world);
            if (save->wantHash && reportHash) reportHash(save->frame, FoldUserState(s.worldHash, s.user));
        } else if (const auto* load = std::get_if<LoadState>(&r)) {
            if (load->frame < 0) return false;
            Slot& s = SlotOf(load->frame);
            if (s.frame != load->frame) return false;
            if (!m_world.RestoreFrame(s.state).ok()) return false;
            m_game.LoadUserState(s.user);
            rollingBack = true;
        } else if (const auto* adv = std::get_if<AdvanceRequest>(&r)) {
            AdvanceWorldFrame(m_world, m_game, adv->frame, adv->inputs, m_settings);
            m_lastAdvanced = adv->frame;
            if (rollingBack) ++m_resimulated;
            if (m_recorder != nullptr && adv->frame >= m_recorded) {
                Slot& s = SlotOf(adv->frame);
                s.inputFrame = adv->frame;
                s.inputs = adv->inputs;
            }
        }
    }
    return true;
}

}  // namespace lockbox::net
