#pragma once
// Option reading for lockbox's command-line programs. Every program reads its arguments the same
// way, so every program names the argument it refuses ("lockbox_demo: unknown option '--bogus'",
// "lockbox_bench: --steps needs a whole number in 1..1000000, not 'ten'") and exits with 2.
//
//   lockbox::cli::OptionReader args("lockbox_demo", argc, argv);
//   while (args.Next()) {
//       if (args.Is("--offline")) offline = true;
//       else if (args.Is("--frames")) args.Int(1, 1000000, frames);
//       else args.Unknown();
//   }
//   if (args.Failed()) return args.Fail(kUsage);
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

namespace lockbox::cli {

/// Walks argv one option at a time; the first refused argument stops the walk and is named by
/// Fail(). Values are read from the argument after the option.
class OptionReader {
public:
    /// `program` is the name used in messages (argv[0] may be a long path).
    OptionReader(std::string_view program, int argc, char** argv) : m_program(program), m_argc(argc), m_argv(argv) {}

    /// Moves to the next argument; false at the end or once an argument was refused.
    bool Next() {
        if (Failed()) return false;
        m_index = m_next;
        if (m_index >= m_argc) return false;
        m_next = m_index + 1;
        return true;
    }

    /// The current argument.
    std::string_view Current() const { return m_argv[m_index]; }
    /// True when the current argument is `name`.
    bool Is(std::string_view name) const { return Current() == name; }
    /// True when no value follows the current argument.
    bool AtLast() const { return m_next >= m_argc; }

    /// Reads the next argument as a whole decimal number in [lo, hi] into `out`; on failure
    /// records the error (the option, the range and the text given) and leaves `out` unchanged.
    template <class T>
    bool Int(long long lo, long long hi, T& out) {
        static_assert(std::is_integral_v<T>);
        std::string_view text;
        if (!Value(text)) return RefuseValue("a whole number", lo, hi, {});
        long long v = 0;
        if (!Whole(text, lo, hi, v)) return RefuseValue("a whole number", lo, hi, text);
        out = static_cast<T>(v);
        return true;
    }

    /// Reads the next argument as "A<separator>B", two whole numbers with A in [loA, hiA] and B in
    /// [loB, hiB] (e.g. "640x480", "120:2"); `form` describes it in the error ("WxH").
    template <class A, class B>
    bool IntPair(char separator, const char* form, long long loA, long long hiA, long long loB, long long hiB, A& a,
                 B& b) {
        std::string_view text;
        if (!Value(text)) return Refuse(std::string(Current()) + " needs " + form);
        const size_t cut = text.find(separator);
        long long x = 0, y = 0;
        if (cut == std::string_view::npos || !Whole(text.substr(0, cut), loA, hiA, x) ||
            !Whole(text.substr(cut + 1), loB, hiB, y))
            return Refuse(std::string(Current()) + " needs " + form + ", not '" + std::string(text) + "'");
        a = static_cast<A>(x);
        b = static_cast<B>(y);
        return true;
    }

    /// Reads the next argument as an unsigned 64-bit number, decimal or 0x-prefixed hexadecimal.
    bool Uint64(uint64_t& out) {
        std::string_view text;
        if (!Value(text)) return Refuse(std::string(Current()) + " needs a number");
        int base = 10;
        std::string_view digits = text;
        if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
            base = 16;
            digits.remove_prefix(2);
        }
        uint64_t v = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v, base);
        if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size())
            return Refuse(std::string(Current()) + " needs a number (decimal or 0x hex) below 2^64, not '" +
                          std::string(text) + "'");
        out = v;
        return true;
    }

    /// Reads the next argument as free text (a name or a path) into `out`.
    bool Text(std::string& out) {
        std::string_view text;
        if (!Value(text)) return Refuse(std::string(Current()) + " needs a value");
        out = std::string(text);
        return true;
    }

    /// Reads the next argument, which must be one of `choices`, into `out`.
    bool Choice(std::initializer_list<std::string_view> choices, std::string& out) {
        std::string list;
        for (std::string_view c : choices) {
            if (!list.empty()) list += '|';
            list += c;
        }
        std::string_view text;
        if (!Value(text)) return Refuse(std::string(Current()) + " needs one of " + list);
        for (std::string_view c : choices) {
            if (text == c) {
                out = std::string(text);
                return true;
            }
        }
        return Refuse(std::string(Current()) + " needs one of " + list + ", not '" + std::string(text) + "'");
    }

    /// Refuses the current argument as an option this program does not have.
    void Unknown() {
        if (!Current().empty() && Current().front() == '-')
            Refuse("unknown option '" + std::string(Current()) + "'");
        else
            Refuse("unexpected argument '" + std::string(Current()) + "'");
    }

    /// Refuses the run with a message of the program's own (a missing required option, two
    /// options that exclude each other).
    bool Refuse(std::string message) {
        if (!Failed()) m_error = std::move(message);
        return false;
    }

    /// True once an argument was refused.
    bool Failed() const { return !m_error.empty(); }
    /// The refusal, without the program name; empty when none.
    const std::string& Error() const { return m_error; }

    /// Prints "program: error" and then `usage` (when given) to stderr; returns 2, the exit
    /// code for a usage error.
    int Fail(const char* usage = nullptr) const {
        std::fprintf(stderr, "%.*s: %s\n", static_cast<int>(m_program.size()), m_program.data(),
                     m_error.empty() ? "bad arguments" : m_error.c_str());
        if (usage != nullptr) std::fputs(usage, stderr);
        return 2;
    }

private:
    static bool Whole(std::string_view text, long long lo, long long hi, long long& out) {
        const char* first = text.data();
        const char* last = first + text.size();
        if (first != last && *first == '+') ++first;
        long long v = 0;
        const auto [end, ec] = std::from_chars(first, last, v);
        if (first == last || ec != std::errc{} || end != last || v < lo || v > hi) return false;
        out = v;
        return true;
    }

    bool Value(std::string_view& text) {
        if (m_next >= m_argc) return false;
        text = m_argv[m_next++];
        return true;
    }

    bool RefuseValue(const char* what, long long lo, long long hi, std::string_view given) {
        std::string m = std::string(Current()) + " needs " + what;
        if (lo != std::numeric_limits<long long>::min() || hi != std::numeric_limits<long long>::max())
            m += " in " + std::to_string(lo) + ".." + std::to_string(hi);
        if (given.data() != nullptr) m += ", not '" + std::string(given) + "'";
        return Refuse(std::move(m));
    }

    std::string_view m_program;
    int m_argc;
    char** m_argv;
    int m_index = 0;
    int m_next = 1;
    std::string m_error;
};

}  // namespace lockbox::cli
