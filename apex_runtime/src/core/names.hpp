// Naming rules shared by the registry, the graph and the file format.
#pragma once

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

#include "apex/core/limits.hpp"

namespace apex {

inline constexpr const char* kNameRule =
    "must start with a letter or '_' and hold only letters, digits and '_', at most 200 of them";
static_assert(kMaxNameLength == 200, "kNameRule says 200");
inline constexpr const char* kTypeIdRule = "must look like 'package/Name' (letters, digits, '_')";

inline bool validName(const std::string& s) {
  if (s.empty() || s.size() > kMaxNameLength || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

inline bool validTypeId(const std::string& id) {
  auto slash = id.find('/');
  return slash != std::string::npos && validName(id.substr(0, slash)) && validName(id.substr(slash + 1));
}

/** The index of the item named `n` (ports, parameters, events), or -1. */
template <class T>
int indexOf(const std::vector<T>& items, std::string_view n) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == n) return static_cast<int>(i);
  return -1;
}

}  // namespace apex
