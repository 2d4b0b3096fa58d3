// Internal: small YAML checks for code outside the file format.
#pragma once

#include <string>

#include "apex/core/result.hpp"

namespace apex {
namespace detail {

/** @brief OK if the text parses as YAML; else the parser's message. */
Status checkYamlText(const std::string& text);
/** @brief True if the text is a YAML map with the key `apex_graph`: a graph file, valid or not. */
bool isGraphText(const std::string& text);
}  // namespace detail
}  // namespace apex
