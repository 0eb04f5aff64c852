// LOCKBOX_ASSERT (lockbox/fixed/Assert.h): a replaced handler sees the failed condition, the
// message and where it failed; release builds evaluate nothing; nullptr restores the default.
#include "lockbox/fixed/Assert.h"

#include <string>

#include <gtest/gtest.h>

namespace lockbox {
namespace LOCKBOX_TEST_FILE {

struct Seen {
    int calls = 0;
    std::string expr, msg, file;
    int line = 0;
};
Seen g_seen;

void Record(const char* expr, const char* msg, const char* file, int line) {
    ++g_seen.calls;
    g_seen.expr = expr;
    g_seen.msg = msg;
    g_seen.file = file;
    g_seen.line = line;
}

TEST(Assert, AReplacedHandlerSeesTheMessage) {
    g_seen = Seen{};
    const b2AssertHandler previous = b2SetAssertHandler(&Record);
    int evaluated = 0;
    const int line = __LINE__ + 1;
    LOCKBOX_ASSERT(++evaluated == 2, "one plus one is not two");
    LOCKBOX_ASSERT(evaluated >= 0, "never fails");
    EXPECT_EQ(b2SetAssertHandler(previous), &Record);
    if (b2_assertsEnabled) {
        EXPECT_EQ(evaluated, 1);
        ASSERT_EQ(g_seen.calls, 1);
        EXPECT_EQ(g_seen.expr, "++evaluated == 2");
        EXPECT_EQ(g_seen.msg, "one plus one is not two");
        EXPECT_NE(g_seen.file.find("assert_test.cpp"), std::string::npos) << g_seen.file;
        EXPECT_EQ(g_seen.line, line);
    } else {
        // Release builds do not evaluate the condition at all.
        EXPECT_EQ(evaluated, 0);
        EXPECT_EQ(g_seen.calls, 0);
    }
}

TEST(Assert, NullRestoresTheDefaultHandler) {
    const b2AssertHandler previous = b2SetAssertHandler(&Record);
    const b2AssertHandler mine = b2SetAssertHandler(nullptr);
    EXPECT_EQ(mine, &Record);
    // The default is a real function (not null), and the one in place before the test.
    const b2AssertHandler fallback = b2SetAssertHandler(previous);
    EXPECT_NE(fallback, nullptr);
    EXPECT_EQ(fallback, previous);
}

#if defined(LOCKBOX_CHECKED) || !defined(NDEBUG)
TEST(AssertDeathTest, TheDefaultHandlerPrintsAndAborts) {
    EXPECT_DEATH(LOCKBOX_ASSERT(1 + 1 == 3, "arithmetic"), "check '1 \\+ 1 == 3' failed: arithmetic");
}
#endif

}  // namespace LOCKBOX_TEST_FILE
}  // namespace lockbox
