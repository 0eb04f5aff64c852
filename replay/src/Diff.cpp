// Diff: lockstep play of two replays, then category, body and field of the first difference.
#include "lockbox/replay/Diff.h"

#include <algorithm>
#include <cstdio>

#include "HexText.h"

namespace lockbox::replay {

using detail::Hex;

namespace {

// Integer-only decimal text of raw / 2^bits with 6 truncated fraction digits.
std::string Decimal(int64_t raw, int bits) {
    const bool negative = raw < 0;
    // The magnitude of INT64_MIN does not fit int64: work in uint64.
    const uint64 mag = negative ? uint64{0} - static_cast<uint64>(raw) : static_cast<uint64>(raw);
    const uint64 whole = mag >> bits;
    const uint64 frac = mag & ((uint64{1} << bits) - 1);
    // frac < 2^32 and 10^6 < 2^20: the product stays below 2^52.
    const uint64 digits = (frac * 1000000u) >> bits;
    char buf[48];
    std::snprintf(buf, sizeof buf, "%s%llu.%06llu", negative ? "-" : "", static_cast<unsigned long long>(whole),
                  static_cast<unsigned long long>(digits));
    return buf;
}

const b2Body* FindBody(const b2World& w, int32 id) {
    for (const b2Body* b = w.GetBodyList(); b; b = b->GetNext())
        if (b->GetId() == id) return b;
    return nullptr;
}

}  // namespace

std::string FormatFixed(Fixed v) {
    char raw[24];
    std::snprintf(raw, sizeof raw, "0x%08x", static_cast<unsigned>(static_cast<uint32>(v.Raw())));
    return Decimal(v.Raw(), 16) + " (raw " + raw + ")";
}

std::string FormatWide(Wide v) {
    char raw[32];
    std::snprintf(raw, sizeof raw, "0x%016llx", static_cast<unsigned long long>(static_cast<uint64>(v.Raw())));
    return Decimal(v.Raw(), 32) + " (raw " + raw + ")";
}

std::vector<FieldDifference> CompareBodies(const b2Body& a, const b2Body& b) {
    // The body records of the canonical state walk (b2BodyStateFields): the fields the hash
    // reads, in its order, so the diff cannot miss one the hash sees.
    std::vector<FieldDifference> out;
    const std::vector<b2BodyField> fa = b2BodyStateFields(a);
    const std::vector<b2BodyField> fb = b2BodyStateFields(b);
    auto format = [](const b2BodyField& f) {
        switch (f.format) {
            case b2FieldFormat::e_fixed: return FormatFixed(Fixed::FromRaw(static_cast<int32>(f.raw)));
            case b2FieldFormat::e_wide: return FormatWide(Wide::FromRaw(f.raw));
            case b2FieldFormat::e_integer: break;
        }
        return std::to_string(f.raw);
    };
    for (size_t i = 0; i < fa.size() && i < fb.size(); ++i) {
        if (fa[i].raw != fb[i].raw) out.push_back({fa[i].name, format(fa[i]), format(fb[i])});
    }
    if (out.empty() && b2BodyStateHash(a) != b2BodyStateHash(b))
        out.push_back(
            {"fixtures", "(sub-hash " + Hex(b2BodyStateHash(a)) + ")", "(sub-hash " + Hex(b2BodyStateHash(b)) + ")"});
    return out;
}

DiffResult DiffWorlds(const b2World& a, const b2World& b) {
    DiffResult r;
    const b2WorldHashReport ra = b2WorldHashDetailed(a);
    const b2WorldHashReport rb = b2WorldHashDetailed(b);
    r.hashA = ra.total;
    r.hashB = rb.total;
    if (ra.total == rb.total) return r;
    r.same = false;
    r.where = b2CompareHashReports(ra, rb);
    if (r.where.bodyId >= 0) {
        const b2Body* ba = FindBody(a, r.where.bodyId);
        const b2Body* bb = FindBody(b, r.where.bodyId);
        if (ba != nullptr && bb != nullptr) {
            r.fields = CompareBodies(*ba, *bb);
        } else {
            r.note = "body " + std::to_string(r.where.bodyId) + " exists only in " + (ba != nullptr ? "A" : "B");
        }
    }
    if (r.where.category != b2HashCategory::e_bodies && r.where.category != b2HashCategory::e_fixtures) {
        if (a.GetContactCount() != b.GetContactCount())
            r.fields.push_back(
                {"world.contactCount", std::to_string(a.GetContactCount()), std::to_string(b.GetContactCount())});
        if (a.GetBodyCount() != b.GetBodyCount())
            r.fields.push_back({"world.bodyCount", std::to_string(a.GetBodyCount()), std::to_string(b.GetBodyCount())});
    }
    return r;
}

DiffResult DiffReplays(Player& a, Player& b, const ReplayFile& fileA, const ReplayFile& fileB) {
    DiffResult r;
    const size_t na = fileA.FrameInputBytes(), nb = fileB.FrameInputBytes();
    const int32 common = fileA.frameCount < fileB.frameCount ? fileA.frameCount : fileB.frameCount;
    for (int32 f = 0; f < common && r.firstInputFrame < 0; ++f) {
        const auto ia = fileA.Inputs(f), ib = fileB.Inputs(f);
        if (na != nb || !std::equal(ia.begin(), ia.end(), ib.begin())) r.firstInputFrame = f;
    }
    if (Error e = a.Reset(); !e.ok()) {
        r.error = e;
        r.same = false;
        return r;
    }
    if (Error e = b.Reset(); !e.ok()) {
        r.error = e;
        r.same = false;
        return r;
    }
    auto compare = [&](int32 frame) {
        DiffResult d = DiffWorlds(a.world(), b.world());
        if (d.same) return false;
        d.frame = frame;
        d.firstInputFrame = r.firstInputFrame;
        r = std::move(d);
        return true;
    };
    if (compare(-1)) return r;
    while (!a.AtEnd() && !b.AtEnd()) {
        const int32 frame = a.Frame();
        a.Step();
        b.Step();
        if (compare(frame)) return r;
    }
    if (fileA.frameCount != fileB.frameCount)
        r.note = "the runs agree on their " + std::to_string(common) + " common frames; A has " +
                 std::to_string(fileA.frameCount) + ", B has " + std::to_string(fileB.frameCount);
    return r;
}

std::string DiffResult::Describe() const {
    if (!error.ok()) return "error: " + error.Describe() + "\n";
    std::string s;
    if (firstInputFrame >= 0) s += "inputs first differ at frame " + std::to_string(firstInputFrame) + "\n";
    if (same) {
        s += "SAME: no state difference" + (note.empty() ? std::string() : " (" + note + ")") + "\n";
        return s;
    }
    s += frame < 0 ? std::string("DIFFER at the seed (before frame 0)\n")
                   : "DIFFER after frame " + std::to_string(frame) + "\n";
    s += "  hash      A " + Hex(hashA) + "  B " + Hex(hashB) + "\n";
    s += "  category  " + std::string(b2HashCategoryName(where.category)) + "\n";
    if (where.bodyId >= 0) s += "  body      " + std::to_string(where.bodyId) + "\n";
    for (const FieldDifference& f : fields) s += "  field     " + f.field + ": A " + f.a + "  B " + f.b + "\n";
    if (!note.empty()) s += "  note      " + note + "\n";
    return s;
}

}  // namespace lockbox::replay
