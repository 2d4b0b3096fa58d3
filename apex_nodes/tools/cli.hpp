// Command-line options of the project's tools.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace apex_tools {

/** @brief `text` as a whole number in [lo, hi]; throws std::invalid_argument naming `what`. */
inline std::uint64_t number(const std::string& what, const std::string& text, std::uint64_t lo, std::uint64_t hi) {
  std::size_t used = 0;
  unsigned long long n = 0;
  try {
    if (!text.empty() && text[0] != '-' && text[0] != '+') n = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;  // out of range: reported below
  }
  if (used == 0 || used != text.size() || n < lo || n > hi)
    throw std::invalid_argument(what + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                                ", not '" + text + "'");
  return n;
}

}  // namespace apex_tools
