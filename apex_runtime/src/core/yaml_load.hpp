// Internal: YAML text to a yaml-cpp tree, its shape checked first (yaml_load.cpp). For the code
// that reads YAML (graph_text.cpp, param_text.cpp): every YAML text from outside goes through it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <string_view>

#include "apex/core/limits.hpp"

namespace apex {
namespace detail {

/** What a text may hold before yaml-cpp reads it: the file format's own limits, checked exactly on
 *  the tree later. The scan may count a level or two more than the tree has (a scalar after "- ",
 *  a plain scalar's next line) and allows for that: it refuses only what the tree's check would. */
struct YamlShapeLimits {
  int depth = kMaxYamlDepth;
  std::size_t values = kMaxYamlNodes;
};
/** Where a text nests too deep or holds too many values (line and column from 0, as yaml-cpp's). */
struct YamlShapeError {
  int line = 0, column = 0;
  std::string what;
};
/** @brief The first place the text breaks a limit, found without building anything; none if it
 *  keeps them (whether it is valid YAML is yaml-cpp's to say). */
std::optional<YamlShapeError> yamlShapeError(std::string_view text, const YamlShapeLimits& limits = {});
/** @brief YAML::Load, after yamlShapeError.
 *  @throws YAML::Exception (a YAML::ParserException at the place a limit is broken) */
YAML::Node loadYaml(const std::string& text);

}  // namespace detail
}  // namespace apex
