// b2WorldHash: the canonical state walk (StateWalk.h) streamed into XXH3-64, one stream per
// category, each opened by a tag. The field list is in docs/determinism.md ("State hash",
// version b2_hashVersion).

#include "lockbox/state/WorldHash.h"

#include <iterator>

#include "HashWriter.h"
#include "StateWalk.h"

namespace lockbox {

using state_detail::HashWriter;

namespace {

/// Contacts hashed per body in the interleaved walk (a pace, not a count: only speed depends
/// on it).
constexpr int kContactsPerBody = 3;

/// The six category hashes into out[]; with `bodies`, also every body's sub-hash.
void HashAll(const b2World& world, uint64 out[], std::vector<b2BodyHashEntry>* bodies) {
    using namespace state_detail;
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_settings);
        WriteSettings(w, world);
        out[0] = w.Digest();
    }
    {
        // Bodies, fixtures and contacts in one interleaved pass (the bytes of each stream are
        // those of WriteBodies, WriteFixtures and WriteContacts): each list node is a cache
        // miss that the next node's address waits for, and two independent chains (the body
        // list, the contact list) let the processor wait for both at once. One body walk
        // also serves both the body and the fixture streams.
        HashWriter bodyStream, fixtureStream, contactStream;
        Tag(bodyStream, b2HashCategory::e_bodies);
        Tag(fixtureStream, b2HashCategory::e_fixtures);
        Tag(contactStream, b2HashCategory::e_contacts);
        const core_detail::Engine::World& in = core_detail::Engine::Of(world);
        WritePool(bodyStream, in.m_bodies);
        WritePool(fixtureStream, in.m_fixtures);
        WritePool(contactStream, in.m_contactManager.GetPool());
        const b2Body* b = world.GetBodyList();
        const b2Contact* c = world.GetContactList();
        while (b != nullptr || c != nullptr) {
            // Each lane requests its next node, writes the current one, then (the next node's
            // first line having had the write's time to arrive) requests what the next
            // record reads through a pointer: a body's first fixture. (A contact's record
            // reads only the contact: its fixture ids are cached in it.)
            if (b != nullptr) {
                const b2Body* next = b->GetNext();
                if (next != nullptr) PrefetchObject(next);
                StateWalk::WriteBody(bodyStream, *b);
                for (const b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
                    StateWalk::WriteFixture(fixtureStream, *f);
                }
                if (next != nullptr && next->GetFixtureList() != nullptr) PrefetchObject(next->GetFixtureList());
                b = next;
            }
            // About three contacts per body in stacked scenes; any ratio gives the same bytes.
            for (int k = 0; k < kContactsPerBody && c != nullptr; ++k) {
                const b2Contact* next = c->GetNext();
                if (next != nullptr) PrefetchObject(next);
                StateWalk::WriteContact(contactStream, *c);
                c = next;
            }
        }
        out[1] = bodyStream.Digest();
        out[2] = fixtureStream.Digest();
        out[3] = contactStream.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_joints);
        WriteJoints(w, world);
        out[4] = w.Digest();
    }
    {
        HashWriter w;
        Tag(w, b2HashCategory::e_broadphase);
        WriteBroadPhase(w, world);
        out[5] = w.Digest();
    }
    if (bodies != nullptr) {
        for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext())
            bodies->push_back({b->GetId(), b2BodyStateHash(*b)});
    }
}

}  // namespace

std::string_view b2HashCategoryName(b2HashCategory category) noexcept {
    switch (category) {
        case b2HashCategory::e_settings: return "settings";
        case b2HashCategory::e_bodies: return "bodies";
        case b2HashCategory::e_fixtures: return "fixtures";
        case b2HashCategory::e_contacts: return "contacts";
        case b2HashCategory::e_joints: return "joints";
        case b2HashCategory::e_broadphase: return "broadphase";
        default: return "none";
    }
}

uint64 b2BodyStateHash(const b2Body& body) {
    HashWriter w;
    w.U32(b2_hashVersion);
    state_detail::StateWalk::WriteBody(w, body);
    for (const b2Fixture* f = body.GetFixtureList(); f; f = f->GetNext()) state_detail::StateWalk::WriteFixture(w, *f);
    return w.Digest();
}

namespace {

/// Records the fields of one walk record, in order, with their formats.
class FieldRecorder {
public:
    class Cursor {
    public:
        explicit Cursor(std::vector<b2BodyField>& out) : out_(&out) {}
        void U8(uint32 v) { Int(v); }
        void U16(uint32 v) { Int(v); }
        void U32(uint32 v) { Int(v); }
        void U64(uint64 v) { Int(static_cast<int64_t>(v)); }
        void I32(int32 v) { Int(v); }
        void Bool(bool v) { Int(v ? 1 : 0); }
        void F(Fixed v) { out_->push_back({"", b2FieldFormat::e_fixed, v.Raw()}); }
        void W(Wide v) { out_->push_back({"", b2FieldFormat::e_wide, v.Raw()}); }
        void V(const b2Vec2& v) {
            F(v.x);
            F(v.y);
        }

    private:
        void Int(int64_t v) { out_->push_back({"", b2FieldFormat::e_integer, v}); }
        std::vector<b2BodyField>* out_;
    };

    Cursor Begin(size_t) { return Cursor(fields); }
    void End(const Cursor&) {}

    std::vector<b2BodyField> fields;
};

/// The names of a body record's fields, in the order StateWalk::WriteBody writes them (vectors
/// as two fields). A test checks that the walk writes exactly this many.
constexpr const char* kBodyFieldNames[] = {
    "id",
    "type",
    "flags",
    "position.x",
    "position.y",
    "rotation.s",
    "rotation.c",
    "sweep.localCenter.x",
    "sweep.localCenter.y",
    "sweep.c0.x",
    "sweep.c0.y",
    "sweep.c.x",
    "sweep.c.y",
    "sweep.a0",
    "sweep.a",
    "sweep.alpha0",
    "linearVelocity.x",
    "linearVelocity.y",
    "angularVelocity",
    "velocityRemainder.x",
    "velocityRemainder.y",
    "velocityRemainder.w",
    "positionRemainder.x",
    "positionRemainder.y",
    "positionRemainder.w",
    "force.x",
    "force.y",
    "torque",
    "sleepSteps",
    "mass",
    "invMass",
    "I",
    "invI",
    "linearDamping",
    "angularDamping",
    "gravityScale",
    "minExtent",
    "maxExtent",
    "userData",
    "fixtureCount",
};

}  // namespace

std::vector<b2BodyField> b2BodyStateFields(const b2Body& body) {
    FieldRecorder recorder;
    recorder.fields.reserve(std::size(kBodyFieldNames));
    state_detail::StateWalk::WriteBody(recorder, body);
    // A walk changed without this table falls back to positions, never to wrong names.
    const bool named = recorder.fields.size() == std::size(kBodyFieldNames);
    for (size_t i = 0; i < recorder.fields.size(); ++i) recorder.fields[i].name = named ? kBodyFieldNames[i] : "field";
    return recorder.fields;
}

uint64 b2WorldHash(const b2World& world) {
    uint64 categories[static_cast<uint32>(b2HashCategory::e_count)];
    HashAll(world, categories, nullptr);
    return state_detail::CombineCategories(categories);
}

b2WorldHashReport b2WorldHashDetailed(const b2World& world) {
    b2WorldHashReport report;
    report.bodies.reserve(static_cast<size_t>(world.GetBodyCount()));
    HashAll(world, report.categories, &report.bodies);
    report.total = state_detail::CombineCategories(report.categories);
    return report;
}

b2HashMismatch b2CompareHashReports(const b2WorldHashReport& a, const b2WorldHashReport& b) noexcept {
    b2HashMismatch result;
    for (uint32 i = 0; i < static_cast<uint32>(b2HashCategory::e_count); ++i) {
        if (a.categories[i] != b.categories[i]) {
            result.category = static_cast<b2HashCategory>(i);
            break;
        }
    }
    const size_t n = a.bodies.size() < b.bodies.size() ? a.bodies.size() : b.bodies.size();
    for (size_t i = 0; i < n; ++i) {
        if (a.bodies[i].bodyId != b.bodies[i].bodyId || a.bodies[i].hash != b.bodies[i].hash) {
            result.bodyId = a.bodies[i].bodyId;
            return result;
        }
    }
    if (a.bodies.size() != b.bodies.size()) {
        const auto& longer = a.bodies.size() > b.bodies.size() ? a.bodies : b.bodies;
        result.bodyId = longer[n].bodyId;
    }
    return result;
}

}  // namespace lockbox
