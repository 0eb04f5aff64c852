// JSON-lines log (JsonLog.h).
#include "JsonLog.h"

#include <chrono>

namespace lockbox::server {

namespace {

void AppendQuoted(std::string& out, std::string_view s) {
    static constexpr char kHex[] = "0123456789abcdef";
    out += '"';
    for (char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20) {
            out += "\\u00";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        } else {
            out += c;
        }
    }
    out += '"';
}

}  // namespace

JsonLog::Line::Line(JsonLog& log, std::string_view event) : m_log(log) {
    const auto ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count();
    m_text = "{\"ts_ms\":" + std::to_string(ms) + ",\"event\":";
    AppendQuoted(m_text, event);
}

JsonLog::Line::~Line() {
    m_text += "}\n";
    m_log.Write(m_text);
}

JsonLog::Line& JsonLog::Line::Str(std::string_view key, std::string_view value) {
    m_text += ',';
    AppendQuoted(m_text, key);
    m_text += ':';
    AppendQuoted(m_text, value);
    return *this;
}

JsonLog::Line& JsonLog::Line::Num(std::string_view key, uint64_t value) {
    m_text += ',';
    AppendQuoted(m_text, key);
    m_text += ':' + std::to_string(value);
    return *this;
}

JsonLog::Line& JsonLog::Line::Int(std::string_view key, int64_t value) {
    m_text += ',';
    AppendQuoted(m_text, key);
    m_text += ':' + std::to_string(value);
    return *this;
}

void JsonLog::Write(const std::string& text) {
    std::lock_guard lock(m_mutex);
    ++m_lines;
    if (m_out == nullptr) return;
    std::fwrite(text.data(), 1, text.size(), m_out);
    std::fflush(m_out);
}

}  // namespace lockbox::server
