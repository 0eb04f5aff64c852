// b2SnapshotHash: the hash read from a saved image equals the hash of the world that saved it
// (total and every category), on every light scene and at several frames; an image with bad
// framing is refused with the error and a message, like Restore would refuse it.

#include <gtest/gtest.h>

#include "SceneSyncGame.h"
#include "StateTestUtil.h"

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

using testing_state::SceneRun;
using testing_state::SectionBytes;

class SnapshotHashScenes : public ::testing::TestWithParam<std::string_view> {};

TEST_P(SnapshotHashScenes, EqualsTheWorldHashAtEveryFrame) {
    SceneRun run(GetParam());
    ASSERT_TRUE(run.scene) << GetParam();
    std::vector<uint8> image;
    for (int frame = 0; frame <= 60; ++frame) {
        if (frame % 15 == 0 || frame < 3) {
            run.world().Save(image);
            const b2SnapshotHashResult fromImage = b2SnapshotHash(image);
            ASSERT_TRUE(fromImage.ok()) << fromImage.message;
            const b2WorldHashReport fromWorld = b2WorldHashDetailed(run.world());
            ASSERT_EQ(fromImage.total, run.world().Hash()) << "frame " << frame;
            ASSERT_EQ(fromImage.total, fromWorld.total) << "frame " << frame;
            for (uint32 c = 0; c < static_cast<uint32>(b2HashCategory::e_count); ++c) {
                ASSERT_EQ(fromImage.categories[c], fromWorld.categories[c])
                    << "frame " << frame << ", category " << b2HashCategoryName(static_cast<b2HashCategory>(c));
            }
        }
        run.Advance();
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SnapshotHashScenes, ::testing::ValuesIn(testing_state::SceneNames(/*large=*/false)),
                         [](const ::testing::TestParamInfo<std::string_view>& p) { return std::string(p.param); });

/// A scene's image after 10 frames (ragdolls: bodies, fixtures, contacts and joints).
std::vector<uint8> SceneImage(const char* name = "ragdolls") {
    SceneRun run(name);
    run.Advance(10);
    return run.world().Save();
}

TEST(SnapshotHash, AnEditedSectionChangesItsCategoryOnly) {
    std::vector<uint8> image = SceneImage();
    const b2SnapshotHashResult before = b2SnapshotHash(image);
    ASSERT_TRUE(before.ok());
    // The last byte of the broad-phase section (its move buffer, or its count).
    const auto [begin, end] = SectionBytes(image, 6);
    ASSERT_LT(begin, end);
    image[end - 1] ^= 0x40;
    const b2SnapshotHashResult after = b2SnapshotHash(image);
    ASSERT_TRUE(after.ok()) << "the hash checks framing, not the checksum: " << after.message;
    EXPECT_NE(after.total, before.total);
    for (uint32 c = 0; c < static_cast<uint32>(b2HashCategory::e_broadphase); ++c) {
        EXPECT_EQ(after.categories[c], before.categories[c]) << b2HashCategoryName(static_cast<b2HashCategory>(c));
    }
    EXPECT_NE(after.categories[static_cast<uint32>(b2HashCategory::e_broadphase)],
              before.categories[static_cast<uint32>(b2HashCategory::e_broadphase)]);
}

TEST(SnapshotHash, TheJointReactionSectionIsNotHashed) {
    // pulley_gear's pulley and gear joints carry reaction directions (section 7).
    std::vector<uint8> image = SceneImage("pulley_gear");
    const auto [begin, end] = SectionBytes(image, 7);
    ASSERT_LT(begin, end) << "no joint reactions in pulley_gear";
    const b2SnapshotHashResult before = b2SnapshotHash(image);
    image[begin] ^= 0x01;
    b2SealSnapshot(image);
    const b2SnapshotHashResult after = b2SnapshotHash(image);
    ASSERT_TRUE(after.ok()) << after.message;
    EXPECT_EQ(after.total, before.total);
    // It restores, and the world's own hash agrees with the image's.
    b2World world(b2Vec2(Fixed(0), Fixed(0)));
    ASSERT_TRUE(world.Restore(image).ok());
    EXPECT_EQ(world.Hash(), after.total);
}

TEST(SnapshotHash, BadFramingIsRefusedWithAMessage) {
    const std::vector<uint8> image = SceneImage();
    auto expectError = [](const std::vector<uint8>& bytes, b2SnapshotError error, const char* what) {
        const b2SnapshotHashResult r = b2SnapshotHash(bytes);
        EXPECT_EQ(r.error, error) << what << ": " << r.message;
        EXPECT_FALSE(r.message.empty()) << what;
        EXPECT_EQ(r.total, 0u) << what;
    };
    // Every cut: the header, a section header or a section's contents is missing.
    for (size_t len = 0; len < image.size(); len += (len < 120 ? 1 : 211)) {
        std::vector<uint8> cut(image.begin(), image.begin() + static_cast<std::ptrdiff_t>(len));
        ASSERT_EQ(b2SnapshotHash(cut).error, b2SnapshotError::e_truncated) << "length " << len;
    }
    std::vector<uint8> bytes = image;
    bytes.push_back(7);
    expectError(bytes, b2SnapshotError::e_trailingBytes, "a byte after the payload");

    bytes = image;
    bytes[0] = 0;
    expectError(bytes, b2SnapshotError::e_badEndianFlag, "endianness flag");
    bytes = image;
    bytes[1] ^= 1;
    expectError(bytes, b2SnapshotError::e_badMagic, "magic");
    bytes = image;
    bytes[5] ^= 1;
    expectError(bytes, b2SnapshotError::e_badFormatVersion, "format version");
    bytes = image;
    bytes[13] ^= 1;
    expectError(bytes, b2SnapshotError::e_badDeterminismVersion, "determinism version");

    // The first section's tag (settings = 1) right after the 33-byte header.
    bytes = image;
    bytes[33] = 2;
    expectError(bytes, b2SnapshotError::e_corrupt, "section tag");
    // The settings section claims one byte more: the next tag is then misread.
    bytes = image;
    bytes[37] += 1;
    const b2SnapshotHashResult grown = b2SnapshotHash(bytes);
    EXPECT_FALSE(grown.ok());
    EXPECT_FALSE(grown.message.empty());
}

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
