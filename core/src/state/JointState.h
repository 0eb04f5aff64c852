#pragma once
// Internal to the snapshot: a joint record's state fields (the joint's VisitState, after the
// head WriteJoint writes), read without a scratch joint. The parse checks them where they lie
// in the image and keeps only the record's offset and the gear references (JointStateCheck);
// the apply reads them again, straight into the world's joint (JointStateReader). A scratch
// copy of every joint, copied whole into the world, doubled the bytes a joint restore moved.
// Both run the joint's own VisitState, the one field list shared with the hash and the save.

#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "ByteCursor.h"
#include "SnapshotCheck.h"
#include "SnapshotImage.h"
#include "StateWalk.h"

namespace lockbox {

/// The joints' state fields where no world joint is at hand: their prototypes.
struct core_detail::Engine::JointState {
    /// A joint of class T to run VisitState on where no world joint is at hand (the parse, the
    /// record sizes): the visitors use the fields' types and places, never write them, and the
    /// size count's reads are defined (a static is zero-filled before its constructor runs).
    /// Restores in several threads only read it.
    template <class T>
    static T& Prototype() {
        static T prototype{b2RestoreTag{}};
        return prototype;
    }

    /// Runs the VisitState of the class of `type` on its prototype.
    template <class V>
    static void VisitFields(b2JointType type, V& v) {
        state_detail::WithJointClass(type, [&](auto cls) { Prototype<typename decltype(cls)::type>().VisitState(v); });
    }

    /// Runs a joint's own VisitState (T is its concrete class).
    template <class T, class V>
    static void VisitState(T& joint, V& v) {
        joint.VisitState(v);
    }
};

}  // namespace lockbox

namespace lockbox::state_detail {

/// The prototype joint of class T (Engine::JointState::Prototype).
template <class T>
T& JointPrototype() {
    return core_detail::Engine::JointState::Prototype<T>();
}

/// Runs the VisitState of the class of `type` on its prototype.
template <class V>
void VisitJointFields(b2JointType type, V& v) {
    core_detail::Engine::JointState::VisitFields(type, v);
}

/// A writer that only counts the bytes asked of it (the widths of ByteCursor's fields).
struct ByteCount {
    size_t bytes = 0;
    void U8(uint32) { bytes += 1; }
    void Bool(bool) { bytes += 1; }
    void I32(int32) { bytes += 4; }
    void F(Fixed) { bytes += 4; }
    void W(Wide) { bytes += 8; }
    void V(const b2Vec2&) { bytes += 8; }
};

/// Marks the 64-byte chunks of a joint object that hold its b2Joint part or a visited field
/// (bit c: bytes [64c, 64c + 64) from the object's start).
struct FieldChunks {
    const char* object;
    uint64 mask = 0;
    template <class... T>
    void operator()(const T&... fields) {
        (Mark(&fields, sizeof fields), ...);
    }
    template <class P>
    void BodyRef(const P& slot) {
        Mark(&slot, sizeof slot);
    }
    template <class P>
    void JointRef(const P& slot) {
        Mark(&slot, sizeof slot);
    }
    void Mark(const void* field, size_t bytes) {
        const size_t first = static_cast<size_t>(static_cast<const char*>(field) - object);
        for (size_t c = first / 64; c <= (first + bytes - 1) / 64; ++c) mask |= uint64{1} << c;
    }
};

/// The most bytes any joint type's state fields take (the save's own writer, JointFieldWriter,
/// counted, so the size cannot drift from the format) and, per type, the chunks of the object a
/// restore writes (found on the prototype, so they follow the class layout). Solver
/// temporaries lie in other chunks, about half of a revolute joint: a restore leaves them
/// alone and need not load them.
struct JointStateSizes {
    std::array<uint64, e_ropeJoint + 1> chunks{};
    uint32 largest = 0;
    /// Bytes of each type's VisitReactionState fields in the joint-reaction section.
    std::array<uint32, e_ropeJoint + 1> reaction{};
};

inline const JointStateSizes& JointStateBytes() {
    static const JointStateSizes sizes = [] {
        JointStateSizes s;
        for (int32 t = e_revoluteJoint; t <= e_ropeJoint; ++t) {
            ByteCount count;
            JointFieldWriter<ByteCount> writer{count};
            VisitJointFields(static_cast<b2JointType>(t), writer);
            if (count.bytes > s.largest) s.largest = static_cast<uint32>(count.bytes);
            WithJointClass(static_cast<b2JointType>(t), [&](auto cls) {
                using T = typename decltype(cls)::type;
                static_assert(sizeof(T) <= 64 * 64, "a joint's chunks fit in the 64-bit mask");
                T& prototype = JointPrototype<T>();
                FieldChunks chunks{reinterpret_cast<const char*>(&prototype)};
                chunks.Mark(&prototype, sizeof(b2Joint));
                core_detail::Engine::JointState::VisitState(prototype, chunks);
                StateWalk::VisitJointReaction(prototype, chunks);
                s.chunks[static_cast<size_t>(t)] = chunks.mask;
                ByteCount reactionCount;
                JointFieldWriter<ByteCount> reactionWriter{reactionCount};
                StateWalk::VisitJointReaction(prototype, reactionWriter);
                s.reaction[static_cast<size_t>(t)] = static_cast<uint32>(reactionCount.bytes);
            });
        }
        // WriteJoint's single room check must cover the largest record.
        if (kJointHeadBytes + s.largest > kJointRecordMaxBytes) std::abort();
        return s;
    }();
    return sizes;
}

/// Starts loading the parts of a joint that a restore writes (`chunks` from JointStateSizes).
/// Objects are not 64-byte aligned, so each chunk requests the lines of both its ends.
inline void PrefetchJointFields(const b2Joint* joint, uint64 chunks) noexcept {
    if (joint == nullptr) return;
    const uintptr_t at = reinterpret_cast<uintptr_t>(joint);
    for (; chunks != 0; chunks &= chunks - 1) {
        const uintptr_t first = at + 64 * static_cast<uintptr_t>(std::countr_zero(chunks));
        __builtin_prefetch(reinterpret_cast<const void*>(first));
        __builtin_prefetch(reinterpret_cast<const void*>(first + 63));
    }
}

/// Parse side: reads and checks a joint's state fields from R, keeping only the references
/// (gear joints) in `refs`, in VisitState order. R is a ReadCursor when the whole record is
/// known to be in the image, else the checked ImageReader, which then fails exactly where
/// a field runs past the end.
template <class R>
struct JointStateCheck {
    R& r;
    std::vector<RefImage>& refs;
    template <class... T>
    void operator()(const T&... fields) {
        (Take(fields), ...);
    }
    void Take(const Fixed&) { (void)r.F(); }
    void Take(const Wide&) { (void)r.W(); }
    void Take(const b2Vec2&) { (void)r.V(); }
    void Take(const b2WideVec2&) { Skip(2); }
    void Take(const b2WideVec3&) { Skip(3); }
    void Take(const bool&) { (void)ReadBool(r, "joint flag"); }
    void Take(const b2LimitState&) {
        const uint8 v = r.U8();
        Check(v <= e_equalLimits, "joint.limitState", "is not a limit state", v);
    }
    void Take(const b2JointType&) {
        const uint8 v = r.U8();
        Check(v == e_revoluteJoint || v == e_prismaticJoint, "gear.side.type", "is not revolute or prismatic", v);
    }
    template <class P>
    void BodyRef(const P&) {
        refs.push_back({false, r.I32()});
    }
    template <class P>
    void JointRef(const P&) {
        refs.push_back({true, r.I32()});
    }

private:
    void Skip(int wides) {
        for (int i = 0; i < wides; ++i) (void)r.W();
    }
};

/// Apply side: reads a joint's state fields from its checked record into a joint of the
/// record's type. References resolve to the world's objects by id: joint references (gear
/// joints) once every joint of the image is in the world's id table.
struct JointStateReader {
    ReadCursor r;
    core_detail::Engine::World& world;
    template <class... T>
    void operator()(T&... fields) {
        (Get(fields), ...);
    }
    void Get(Fixed& x) { x = r.F(); }
    void Get(Wide& x) { x = r.W(); }
    void Get(b2Vec2& x) { x = r.V(); }
    void Get(b2WideVec2& x) {
        x.x = r.W();
        x.y = r.W();
    }
    void Get(b2WideVec3& x) {
        x.x = r.W();
        x.y = r.W();
        x.z = r.W();
    }
    // The parse checked the ranges of these.
    void Get(bool& x) { x = r.U8() != 0; }
    void Get(b2LimitState& x) { x = static_cast<b2LimitState>(r.U8()); }
    void Get(b2JointType& x) { x = static_cast<b2JointType>(r.U8()); }
    void BodyRef(b2Body*& slot) { slot = world.m_bodies.Get(r.I32()); }
    void JointRef(b2Joint*& slot) { slot = world.m_joints[static_cast<size_t>(r.I32())]; }
};

}  // namespace lockbox::state_detail
