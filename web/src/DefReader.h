#pragma once
/// Reads a definition (body, fixture, shape, joint) that JavaScript wrote into the module's
/// memory as int32 words: a presence mask, then every field of the definition's table in
/// order, each taking its fixed number of words whether given or not. A field whose mask bit
/// is clear keeps the C++ default, so JavaScript never repeats a default value; absent fields
/// at the end may also be left out of the words. A given field that runs past the words makes
/// the definition malformed (ok() is false).
///
/// Field kinds and their words: Fixed (1, raw Q16.16), Wide (2, raw Q32.32 low half first),
/// vector (2), int and bool (1), uint64 (2, low half first), points (1 + 2n: the count, then
/// x and y of each).

#include <cstdint>
#include <vector>

#include "Bindings.h"

namespace lockbox::web {

class DefReader {
public:
    /// `words` holds `count` words, the first of which is the presence mask; no words at all
    /// (count 0) is the definition with every field left at its default.
    DefReader(const int32_t* words, int32_t count) noexcept : m_words(words), m_count(count) {
        m_mask = count > 0 ? static_cast<uint32_t>(words[0]) : 0;
        m_at = 1;
    }

    /// Each reader consumes its field's words and assigns `out` when the field was given.
    bool Fixed(lockbox::Fixed& out) noexcept {
        const int32_t* v = Take(1);
        if (v) out = Fx(v[0]);
        return v != nullptr;
    }
    bool Wide(lockbox::Wide& out) noexcept {
        const int32_t* v = Take(2);
        if (v) out = lockbox::Wide::FromRaw(static_cast<int64_t>(GetU64(v[0], v[1])));
        return v != nullptr;
    }
    bool Vec(b2Vec2& out) noexcept {
        const int32_t* v = Take(2);
        if (v) out = b2Vec2(Fx(v[0]), Fx(v[1]));
        return v != nullptr;
    }
    bool Int(int32_t& out) noexcept {
        const int32_t* v = Take(1);
        if (v) out = v[0];
        return v != nullptr;
    }
    bool Bool(bool& out) noexcept {
        const int32_t* v = Take(1);
        if (v) out = v[0] != 0;
        return v != nullptr;
    }
    bool U64(uint64& out) noexcept {
        const int32_t* v = Take(2);
        if (v) out = GetU64(v[0], v[1]);
        return v != nullptr;
    }
    /// A point list: its count word, then two words per point.
    bool Points(std::vector<b2Vec2>& out) {
        const bool given = Given();
        if (m_at >= m_count) return given ? Overrun() : false;
        const int32_t n = m_words[m_at++];
        if (n < 0 || n > (m_count - m_at) / 2) return Overrun();
        if (given) {
            out.clear();
            for (int32_t i = 0; i < n; ++i) out.emplace_back(Fx(m_words[m_at + 2 * i]), Fx(m_words[m_at + 2 * i + 1]));
        }
        m_at += 2 * n;
        return given;
    }

    /// False when a field ran past the words given (a malformed definition).
    bool ok() const noexcept { return !m_overrun; }
    /// Words consumed so far (the mask included).
    int32_t consumed() const noexcept { return m_at; }

private:
    const int32_t* Take(int32_t n) noexcept {
        const bool given = Given();
        if (m_at + n > m_count) {
            if (given) Overrun();
            return nullptr;
        }
        const int32_t* v = m_words + m_at;
        m_at += n;
        return given ? v : nullptr;
    }
    // The mask bit of the next field (a table has at most 32 fields; later ones are absent).
    bool Given() noexcept {
        const bool given = m_field < 32 && ((m_mask >> m_field) & 1) != 0;
        ++m_field;
        return given;
    }
    bool Overrun() noexcept {
        m_overrun = true;
        m_at = m_count;
        return false;
    }

    const int32_t* m_words;
    int32_t m_count;
    uint32_t m_mask = 0;
    int32_t m_field = 0;
    int32_t m_at = 0;
    bool m_overrun = false;
};

}  // namespace lockbox::web
