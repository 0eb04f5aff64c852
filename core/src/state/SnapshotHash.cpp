// b2SnapshotHash: the world hash of a saved image, from its bytes. Each image section is the
// state walk of one hash category (StateWalk.h), so a category's hash is XXH3-64 of its tag
// (version, category index) followed by the section's contents, and the world hash combines
// the six as b2WorldHash does (WorldHash.cpp). The joint-reaction section (format 2 on) is
// not a hash category and is left out.

#include "HashWriter.h"
#include "SnapshotCheck.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox {

b2SnapshotHashResult b2SnapshotHash(std::span<const uint8> image) {
    using namespace state_detail;
    b2SnapshotHashResult result;
    SectionSpans sections;
    try {
        sections = FrameSections(image, ReadHeader(image).format);
    } catch (const SnapshotFailure& failure) {
        result.error = failure.error;
        result.message = failure.message;
        return result;
    }
    for (uint32 i = 0; i < static_cast<uint32>(b2HashCategory::e_count); ++i) {
        HashWriter w;
        Tag(w, static_cast<b2HashCategory>(i));
        w.Bytes(sections[i].data(), sections[i].size());
        result.categories[i] = w.Digest();
    }
    result.total = CombineCategories(result.categories);
    return result;
}

}  // namespace lockbox
