#pragma once
// An enum's names as one table (the command line's choices, config values, reports): both
// directions and the list of names read the same table, so a new value is added in one place.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace makeway {

template <class E>
using NameTable = std::vector<std::pair<std::string, E>>;

/// The name of `value` in `table`; nullopt when the table lacks it.
template <class E>
std::optional<std::string_view> name_of(const NameTable<E>& table, E value) {
    for (const auto& [name, v] : table) {
        if (v == value) return name;
    }
    return std::nullopt;
}

/// The name of `value` in `table`; "unknown" when the table lacks it.
template <class E>
std::string_view name_in(const NameTable<E>& table, E value) {
    return name_of(table, value).value_or("unknown");
}

/// The value named `name` exactly; nullopt when no entry has that name.
template <class E>
std::optional<E> value_named(const NameTable<E>& table, std::string_view name) {
    for (const auto& [n, v] : table) {
        if (n == name) return v;
    }
    return std::nullopt;
}

/// The names in the table's order.
template <class E>
std::vector<std::string> names_in(const NameTable<E>& table) {
    std::vector<std::string> names;
    for (const auto& entry : table) names.push_back(entry.first);
    return names;
}

}  // namespace makeway
