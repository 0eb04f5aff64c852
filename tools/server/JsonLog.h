#pragma once
// lockbox_server's log: one JSON object per line ({"ts_ms":..., "event":"admitted", "match":7,
// "peer":"127.0.0.1:40000", ...}), so a log collector reads it without a parser of its own.

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>

namespace lockbox::server {

class JsonLog {
public:
    /// Writes to `out` (not owned; nullptr: nothing is written). Lines are flushed one by one.
    explicit JsonLog(std::FILE* out) : m_out(out) {}

    /// One line under construction; written when it goes out of scope.
    class Line {
    public:
        Line(JsonLog& log, std::string_view event);
        ~Line();
        Line(const Line&) = delete;
        Line& operator=(const Line&) = delete;
        Line& Str(std::string_view key, std::string_view value);
        Line& Num(std::string_view key, uint64_t value);
        Line& Int(std::string_view key, int64_t value);

    private:
        JsonLog& m_log;
        std::string m_text;
    };

    /// Starts a line for `event`: log.Event("admitted").Num("match", 7).Str("peer", "...").
    Line Event(std::string_view event) { return Line(*this, event); }
    /// Lines written so far.
    uint64_t Lines() const noexcept { return m_lines; }

private:
    void Write(const std::string& text);
    std::FILE* m_out;
    std::mutex m_mutex;
    uint64_t m_lines = 0;
};

}  // namespace lockbox::server
