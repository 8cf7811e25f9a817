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

// info(E) indexes a registry by the enum value: row i must hold value i.
template <class Rows, class Member>
void check_enum_order(const Rows& rows, Member id) {
  for (std::size_t i = 0; i < rows.size(); ++i) ATTENUVIS_CHECK_EQ(static_cast<std::size_t>(rows[i].*id), i);
}

}  // namespace attenuvis::weather::detail
