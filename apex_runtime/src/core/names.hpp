// Naming rules shared by the registry, the graph and the file format.
#pragma once

#include <cctype>
#include <string>

namespace apex {

inline constexpr const char* kNameRule = "must start with a letter or '_' and hold only letters, digits and '_'";
inline constexpr const char* kTypeIdRule = "must look like 'package/Name' (letters, digits, '_')";

inline bool validName(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

inline bool validTypeId(const std::string& id) {
  auto slash = id.find('/');
  return slash != std::string::npos && validName(id.substr(0, slash)) && validName(id.substr(slash + 1));
}

}  // namespace apex
