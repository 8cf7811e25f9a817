// What every registry of names (a table of named choices: water_tables(),
// fog_presets(), snow_types(), ...) needs of its rows: the names in words for
// messages and help, and the order that info() relies on.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/io/check.hpp"

namespace attenuvis::weather::detail {

// "a, b or c" (with `last` = " or "), "a or b", "a"; "" for none.
inline std::string name_list(const std::vector<std::string>& names, const std::string& last = " or ") {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? last : ", ") + names[i];
  return out;
}

// The `name` member of every row, in the registry's order.
template <class Rows>
std::vector<std::string> names_of(const Rows& rows) {
  std::vector<std::string> out;
  for (const auto& row : rows) out.push_back(row.name);
  return out;
}

// The row of an enum value: info(E) of every registry (check_enum_order
// below holds the rows to the enum's order).
template <class Rows, class Enum>
const typename Rows::value_type& row_of(const Rows& rows, Enum value) {
  return rows.at(static_cast<std::size_t>(value));
}

// The row of a name; nullptr for any other text.
template <class Rows>
const typename Rows::value_type* find_by_name(const Rows& rows, const std::string& name) {
  for (const auto& row : rows)
    if (row.name == name) return &row;
  return nullptr;
}

// info(E) indexes a registry by the enum value: row i must hold value i.
template <class Rows, class Member>
void check_enum_order(const Rows& rows, Member id) {
  for (std::size_t i = 0; i < rows.size(); ++i) ATTENUVIS_CHECK_EQ(static_cast<std::size_t>(rows[i].*id), i);
}

}  // namespace attenuvis::weather::detail
