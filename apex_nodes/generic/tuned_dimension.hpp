// The Optimizer's dimensions: the output each entry of its `dimensions` gives it, the parameter
// it tunes, and how a point of the search becomes the value sent to the tuned parameter. A number
// is one coordinate of the search; an interval two (its ends, sorted into low and high); a choice
// one, over the indices of its options; a flag one, 0 or 1. ROS-free.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "apex/core/manifest.hpp"
#include "apex/core/node.hpp"
#include "apex/core/param.hpp"
#include "apex_nodes/search.hpp"

namespace apex_nodes {
namespace tuning {

enum class Kind { Number, Integer, Interval, Choice, Flag };

/** @brief One entry of `dimensions` as written: "name [min max] [int]", "name interval [min max]",
 *  "name choice [option ...]" or "name bool". */
struct DimensionText {
  std::string name;
  Kind kind = Kind::Number;
  bool has_range = false;
  double min = 0, max = 0;
  std::vector<std::string> options;  ///< a choice's, if given
};

/** @brief Reads one entry; the message says what is wrong and how to write it. */
apex::Result<DimensionText> parseDimension(const std::string& text);

/** @brief The type of a dimension's output: that of the parameter ports it feeds. */
const apex::TypeInfo* outputType(Kind kind);

/** @brief The Optimizer's interface as its `dimensions` shape it: one output per entry, named as
 *  the entry, of the type of the parameter it tunes, added to `m`; refused, with its message, at
 *  the first entry that does not read. */
apex::Status addOutputs(const std::vector<std::string>& dimensions, apex::Manifest& m);

/** @brief A dimension resolved against the parameter it tunes. */
struct TunedDimension {
  std::string port;
  Kind kind = Kind::Number;
  std::vector<search::Dimension> coordinates;  ///< its part of the search's point, in order
  double step = 0, origin = 0;  ///< numbers and interval ends on the parameter's grid (odd sizes: 3, 5, ...)
  std::vector<std::string> options;  ///< a choice's
  apex::ParamValue before;  ///< what the parameter held when the run started

  /** @brief The value at `x` (this dimension's coordinates, from the first), on the grid and in range. */
  apex::ParamValue value(const double* x) const;

  /** @brief This dimension as a search outside the runtime samples it (Optuna's distributions:
   *  python/apex/tuning.py), as YAML: {name, kind: number|integer|interval|choice|flag}, with low and
   *  high (their grid's first and last points) and step (none: continuous) for the first three and
   *  options for a choice. Every value sampled from it is one value() gives. */
  std::string spaceText() const;
};

/** @brief The parameters an output feeds now (apex::Node::parameterTargets). */
using TargetsOf = std::function<std::vector<apex::ParamTarget>(const std::string& output)>;

/** @brief Every entry of `dimensions` (each of which reads: addOutputs() refused the others)
 *  resolved against the parameter its output feeds, the first if it feeds several. Throws
 *  std::invalid_argument for an output that feeds no parameter, and for no dimensions at all. */
std::vector<TunedDimension> resolveAll(const std::vector<std::string>& dimensions, const TargetsOf& targets);

/** @brief The values at the search's point `x`, one per dimension of `dims`, each from its own
 *  coordinates (they follow one another in `x`, in the order of `dims`). */
std::vector<apex::ParamValue> valuesAt(const std::vector<TunedDimension>& dims, const std::vector<double>& x);

/** @brief `d` (written as `text`) against the parameter `spec` at `where` (node/parameter) that
 *  now holds `before`. Throws std::invalid_argument naming the dimension and the parameter. */
TunedDimension resolve(const DimensionText& d, const std::string& text, const apex::ParamSpec& spec, const std::string& where,
                       const apex::ParamValue& before);

}  // namespace tuning
}  // namespace apex_nodes
