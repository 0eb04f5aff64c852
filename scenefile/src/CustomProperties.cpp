// CustomProperties: a small sorted list (objects carry a handful of properties).
#include "lockbox/scenefile/CustomProperties.h"

#include <algorithm>

namespace lockbox::scenefile {

const char* CustomTypeName(const CustomValue& value) noexcept {
    static constexpr const char* kNames[] = {"int", "string", "bool", "float", "vec2", "color"};
    return kNames[value.index()];
}

void CustomProperties::Set(std::string name, CustomValue value) {
    const size_t type = value.index();
    // First entry not ordered before (type, name).
    const auto at = std::lower_bound(m_items.begin(), m_items.end(), std::pair<size_t, std::string_view>(type, name),
                                     [](const CustomProperty& p, const std::pair<size_t, std::string_view>& key) {
                                         return p.value.index() != key.first ? p.value.index() < key.first
                                                                             : std::string_view(p.name) < key.second;
                                     });
    if (at != m_items.end() && at->value.index() == type && at->name == name) {
        at->value = std::move(value);
        return;
    }
    m_items.insert(at, CustomProperty{std::move(name), std::move(value)});
}

bool CustomProperties::Remove(std::string_view name, size_t typeIndex) {
    const auto it = std::find_if(m_items.begin(), m_items.end(), [&](const CustomProperty& p) {
        return p.value.index() == typeIndex && p.name == name;
    });
    if (it == m_items.end()) return false;
    m_items.erase(it);
    return true;
}

bool CustomProperties::Matches(std::string_view name, const CustomValue& value) const noexcept {
    for (const CustomProperty& p : m_items) {
        if (p.name == name && p.value == value) return true;
    }
    return false;
}

}  // namespace lockbox::scenefile
