// The C API of replay verification (the samples module only): plays a replay of a library
// scene from its seed and checks every stored hash, as `lockbox_replay verify` does; on a
// divergence it also names the stage (bisect) and the first differing body and field at the
// first keyframe after it.
#include <span>
#include <string>
#include <vector>

#include "Bindings.h"
#include "lockbox/replay/Bisect.h"
#include "lockbox/replay/Diff.h"
#include "lockbox/replay/Player.h"
#include "lockbox/replay/ReplayFile.h"
#include "lockbox/replay/SceneGame.h"

using namespace lockbox;
using namespace lockbox::replay;
using namespace lockbox::web;

namespace {

std::string& Report() {
    static std::string text;
    return text;
}

// The differing fields of the last divergence: "field\trecorded\tre-simulated" each.
std::vector<std::string>& Fields() {
    static std::vector<std::string> fields;
    return fields;
}

/// The first keyframe holding the state after frame `frame` or later, or nullptr.
const Keyframe* KeyframeAfter(const ReplayFile& file, int32_t frame) {
    for (const Keyframe& k : file.keyframes)
        if (k.frame > frame) return &k;
    return nullptr;
}

}  // namespace

/// Verifies a replay file of `size` bytes. Returns -1 when it cannot be played (unreadable,
/// or not a scene replay; lb_last_error says why), else 0 with out[0..17]: ok, frames played,
/// hashes checked, first divergent frame (-1: none), recorded hash there (2 words), re-
/// simulated hash (2 words), final hash (2 words), frame count, tick rate, stage (-1: unknown),
/// solve phase (-1), keyframe frame the body comparison used (-1: none), body id (-1: none),
/// hash category, differing field count. lb_replay_report holds the account for people.
LOCKBOX_WEB_API int32_t lb_replay_verify(const uint8_t* bytes, int32_t size, int32_t* out) {
    for (int i = 0; i < 18; ++i) out[i] = -1;
    Report().clear();
    Fields().clear();
    if (size < 0) return Fail("replay: negative size");
    ReplayFile file;
    if (Error e = ParseReplay(std::span<const uint8_t>(bytes, static_cast<size_t>(size)), file); !e.ok())
        return Fail(e.Describe());
    const std::string sceneName = SceneGame::SceneName(file.gameName);
    SceneGame game(sceneName);
    if (!game.ok()) return Fail("replay of game '" + file.gameName + "': not a library scene this build can play");
    Player player(file, game.world(), game);
    const VerifyResult r = player.Verify();
    if (!r.error.ok()) return Fail(r.message);
    out[0] = r.ok ? 1 : 0;
    out[1] = r.frames;
    out[2] = r.hashesChecked;
    out[3] = r.firstBadFrame;
    PutU64(out + 4, r.expected);
    PutU64(out + 6, r.actual);
    PutU64(out + 8, r.finalHash);
    out[10] = file.frameCount;
    out[11] = file.header.tickRate;
    Report() = r.message + "\n";
    if (r.ok || r.firstBadFrame < 0) return 0;

    // The stage inside the step where re-simulation and recording split (needs fencepost
    // hashes in the file), on a fresh game: Bisect leaves its player anywhere.
    {
        SceneGame g(sceneName);
        Player p(file, g.world(), g);
        const BisectResult b = Bisect(p);
        if (b.error.ok() && b.diverged) {
            out[12] = b.stage;
            out[13] = b.solvePhase;
            Report() += b.Describe();
        }
    }
    // The first differing body and field: re-simulate from the last good stored state to the
    // first keyframe after the divergence and compare with the state recorded there.
    const Keyframe* k = KeyframeAfter(file, r.firstBadFrame);
    if (!k) {
        Report() += "no keyframe after the divergence: record with keyframes to see the body and field\n";
        return 0;
    }
    SceneGame g(sceneName);
    Player p(file, g.world(), g);
    if (!p.Restore(file.NearestKeyframe(r.firstBadFrame)).ok()) return 0;
    while (p.Frame() < k->frame && p.Step()) {
    }
    b2World recorded(b2Vec2(0, 0));
    if (!recorded.Restore(k->world)) return 0;
    DiffResult d = DiffWorlds(recorded, g.world());
    d.frame = k->frame - 1;  // the keyframe holds the state after this frame
    for (const FieldDifference& f : d.fields) Fields().push_back(f.field + "\t" + f.a + "\t" + f.b);
    out[14] = k->frame;
    out[15] = d.where.bodyId;
    out[16] = static_cast<int32_t>(d.where.category);
    out[17] = static_cast<int32_t>(d.fields.size());
    Report() += "at the keyframe after it (A recorded, B re-simulated):\n" + d.Describe();
    return 0;
}

/// Differing field `index` (0 .. field count - 1) of the last divergence as "name\trecorded\t
/// re-simulated" (values as "decimal (raw 0x...)"), or "" out of range.
LOCKBOX_WEB_API const char* lb_replay_field(int32_t index) {
    if (index < 0 || static_cast<size_t>(index) >= Fields().size()) return "";
    return Fields()[static_cast<size_t>(index)].c_str();
}

/// The account of the last lb_replay_verify: its verdict line, then on a divergence the
/// stage and the first differing body and fields.
LOCKBOX_WEB_API const char* lb_replay_report() { return Report().c_str(); }
