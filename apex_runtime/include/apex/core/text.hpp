// Text from outside: the one rule for what a name, a value, a path or a UI note may hold.
#pragma once

#include <string>
#include <string_view>

#include "apex/core/result.hpp"

namespace apex {

/** @brief OK if `text` is UTF-8 without control characters (tab and line breaks aside): what YAML
 *  writes and reads back unchanged, and what a client can show. Else where it is not, e.g.
 *  "not UTF-8 at byte 3". (yaml-cpp turns a NUL into bytes it then writes as another string.) */
Status checkText(std::string_view text);

/** @brief `text` with each byte outside printable ASCII as \xNN, at most `limit` bytes of it:
 *  safe to quote in a message whatever the text held. */
std::string printable(std::string_view text, std::size_t limit = 60);

}  // namespace apex
