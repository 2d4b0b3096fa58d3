#include "apex/core/text.hpp"

#include <cstdio>

namespace apex {

Status checkText(std::string_view v) {
  auto bad = [](std::size_t at, const char* what) {
    return Status::error(std::string(what) + " at byte " + std::to_string(at + 1));
  };
  auto byte = [&v](std::size_t i) { return static_cast<unsigned char>(v[i]); };
  for (std::size_t i = 0; i < v.size();) {
    const unsigned char c = byte(i);
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return bad(i, "a control character");
    const int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || i + extra >= v.size()) return bad(i, "not UTF-8");
    for (int k = 1; k <= extra; ++k)
      if ((byte(i + k) >> 6) != 0x2) return bad(i, "not UTF-8");
    if ((extra == 1 && c < 0xC2) || (extra == 2 && c == 0xE0 && byte(i + 1) < 0xA0) ||
        (extra == 2 && c == 0xED && byte(i + 1) >= 0xA0) || (extra == 3 && c == 0xF0 && byte(i + 1) < 0x90) ||
        (extra == 3 && (c > 0xF4 || (c == 0xF4 && byte(i + 1) >= 0x90))))
      return bad(i, "not UTF-8 (an overlong, surrogate or out-of-range sequence)");
    i += extra + 1;
  }
  return Status::ok();
}

std::string printable(std::string_view text, std::size_t limit) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return text.size() > limit ? out + "..." : out;
}

}  // namespace apex
