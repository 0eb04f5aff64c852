#pragma once
/// @file
/// Custom properties (R.U.B.E.'s "customProperties"): named values of six types attached to the
/// world, a body, a fixture, a joint or an image. As in b2dJson, a name may hold one value of
/// each type at once ("speed" as an int and "speed" as a float are two properties). Floats are
/// Fixed: they arrive as text and are converted like every other number of the file.

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "lockbox/Export.h"
#include "lockbox/common/Settings.h"
#include "lockbox/fixed/Vec2.h"

namespace lockbox::scenefile {

/// An RGBA colour, each channel 0..255 (b2dJson's b2dJsonColor4; default opaque white).
struct CustomColor {
    /// Red, green, blue and alpha, each 0..255 (alpha 255 is opaque).
    ///@{
    int32 r = 255, g = 255, b = 255, a = 255;
    ///@}
    /// Channel-wise equality.
    friend bool operator==(const CustomColor&, const CustomColor&) = default;
};

/// A property value. The order of the alternatives is the order b2dJson writes the types in:
/// int, string, bool, float, vec2, color.
using CustomValue = std::variant<int32, std::string, bool, Fixed, b2Vec2, CustomColor>;

/// The JSON member name of a value's type: "int", "string", "bool", "float", "vec2", "color".
LOCKBOX_API const char* CustomTypeName(const CustomValue& value) noexcept;

/// One named value.
struct CustomProperty {
    /// The property's name (any text; one name may hold one value of each type).
    std::string name;
    /// The value; its type is part of the property's identity.
    CustomValue value;
    /// Equal name and equal value of the same type.
    friend bool operator==(const CustomProperty&, const CustomProperty&) = default;
};

/// The custom properties of one object, kept sorted by type (in CustomValue's order), then by
/// name: the order they are saved in, whatever order they were set in.
class LOCKBOX_API CustomProperties {
public:
    /// Sets `name` for the type of `value` (replacing the value of that name and type).
    void Set(std::string name, CustomValue value);
    /// Removes `name` of the type of alternative `typeIndex` (CustomValue::index()); true when
    /// it was there.
    bool Remove(std::string_view name, size_t typeIndex);

    /// The value of `name` with type T (one of CustomValue's alternatives), or nullptr.
    template <class T>
    const T* Find(std::string_view name) const noexcept {
        for (const CustomProperty& p : m_items) {
            if (p.name == name && std::holds_alternative<T>(p.value)) return &std::get<T>(p.value);
        }
        return nullptr;
    }
    /// The value of `name` with type T, or `fallback` (b2dJson's getCustomInt and friends).
    template <class T>
    T Get(std::string_view name, T fallback) const {
        const T* v = Find<T>(name);
        return v ? *v : fallback;
    }
    /// True when `name` holds the same type and value as `value`.
    bool Matches(std::string_view name, const CustomValue& value) const noexcept;

    /// Every property, sorted by type then name.
    const std::vector<CustomProperty>& Items() const noexcept { return m_items; }
    /// True when there is no property.
    bool Empty() const noexcept { return m_items.empty(); }
    /// Number of properties.
    size_t Size() const noexcept { return m_items.size(); }
    /// Equal when both hold the same properties (same names, types and values).
    friend bool operator==(const CustomProperties&, const CustomProperties&) = default;

private:
    std::vector<CustomProperty> m_items;
};

}  // namespace lockbox::scenefile
