// OptionReader: what every lockbox program accepts and how it names what it refuses.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lockbox_cli/OptionReader.h"

namespace LOCKBOX_TEST_FILE {

using lockbox::cli::OptionReader;

// argv as a program receives it (mutable strings, argv[0] the program).
struct Argv {
    explicit Argv(std::vector<std::string> words) : m_words(std::move(words)) {
        m_words.insert(m_words.begin(), "prog");
        for (std::string& w : m_words) m_pointers.push_back(w.data());
    }
    int argc() const { return static_cast<int>(m_pointers.size()); }
    char** argv() { return m_pointers.data(); }

private:
    std::vector<std::string> m_words;
    std::vector<char*> m_pointers;
};

struct Parsed {
    bool flag = false;
    int count = 7;
    std::string name;
    std::string mode = "a";
    int w = 0, h = 0;
    uint64_t seed = 0;
    std::string error;
};

Parsed Parse(std::vector<std::string> words) {
    Argv a(std::move(words));
    OptionReader args("prog", a.argc(), a.argv());
    Parsed p;
    while (args.Next()) {
        if (args.Is("--flag"))
            p.flag = true;
        else if (args.Is("--count"))
            args.Int(1, 10, p.count);
        else if (args.Is("--name"))
            args.Text(p.name);
        else if (args.Is("--mode"))
            args.Choice({"a", "b"}, p.mode);
        else if (args.Is("--size"))
            args.IntPair('x', "WxH", 1, 100, 1, 50, p.w, p.h);
        else if (args.Is("--seed"))
            args.Uint64(p.seed);
        else
            args.Unknown();
    }
    p.error = args.Error();
    return p;
}

TEST(OptionReader, ReadsEveryKindOfValue) {
    const Parsed p = Parse({"--flag", "--count", "10", "--name", "x y", "--mode", "b", "--size", "100x50", "--seed",
                            "0xFFFFFFFFFFFFFFFF"});
    EXPECT_EQ(p.error, "");
    EXPECT_TRUE(p.flag);
    EXPECT_EQ(p.count, 10);
    EXPECT_EQ(p.name, "x y");
    EXPECT_EQ(p.mode, "b");
    EXPECT_EQ(p.w, 100);
    EXPECT_EQ(p.h, 50);
    EXPECT_EQ(p.seed, 0xFFFFFFFFFFFFFFFFull);
    EXPECT_EQ(Parse({"--seed", "12345678901234567890"}).seed, 12345678901234567890ull);
    EXPECT_EQ(Parse({"--count", "+3"}).count, 3);
}

TEST(OptionReader, NamesTheUnknownOption) {
    EXPECT_EQ(Parse({"--flag", "--bogus", "--count", "3"}).error, "unknown option '--bogus'");
    EXPECT_EQ(Parse({"stray"}).error, "unexpected argument 'stray'");
    // The walk stops at the first refusal: a later good option is not read.
    EXPECT_EQ(Parse({"--bogus", "--count", "3"}).count, 7);
}

TEST(OptionReader, NamesTheMalformedValue) {
    EXPECT_EQ(Parse({"--count", "ten"}).error, "--count needs a whole number in 1..10, not 'ten'");
    EXPECT_EQ(Parse({"--count", "11"}).error, "--count needs a whole number in 1..10, not '11'");
    EXPECT_EQ(Parse({"--count", "3x"}).error, "--count needs a whole number in 1..10, not '3x'");
    EXPECT_EQ(Parse({"--count", ""}).error, "--count needs a whole number in 1..10, not ''");
    EXPECT_EQ(Parse({"--count", "99999999999999999999"}).error,
              "--count needs a whole number in 1..10, not '99999999999999999999'");
    EXPECT_EQ(Parse({"--count"}).error, "--count needs a whole number in 1..10");
    EXPECT_EQ(Parse({"--count", "ten"}).count, 7);  // untouched
    EXPECT_EQ(Parse({"--name"}).error, "--name needs a value");
    EXPECT_EQ(Parse({"--mode", "c"}).error, "--mode needs one of a|b, not 'c'");
    EXPECT_EQ(Parse({"--size", "100x51"}).error, "--size needs WxH, not '100x51'");
    EXPECT_EQ(Parse({"--size", "100"}).error, "--size needs WxH, not '100'");
    EXPECT_EQ(Parse({"--seed", "0x"}).error, "--seed needs a number (decimal or 0x hex) below 2^64, not '0x'");
    EXPECT_EQ(Parse({"--seed", "18446744073709551616"}).error,
              "--seed needs a number (decimal or 0x hex) below 2^64, not '18446744073709551616'");
}

TEST(OptionReader, FailPrintsTheProgramAndReturnsTwo) {
    Argv a({"--bogus"});
    OptionReader args("prog", a.argc(), a.argv());
    while (args.Next()) args.Unknown();
    ASSERT_TRUE(args.Failed());
    testing::internal::CaptureStderr();
    EXPECT_EQ(args.Fail("usage: prog\n"), 2);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "prog: unknown option '--bogus'\nusage: prog\n");
}

}  // namespace LOCKBOX_TEST_FILE
