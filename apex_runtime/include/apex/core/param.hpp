// Parameters: typed, validated values a node type declares with a default,
// a description and (where it applies) a range, step or set of options.
#pragma once

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "apex/core/message.hpp"
#include "apex/core/result.hpp"

namespace apex {

/** @brief An interval [low, high] inside a parameter's bounds. */
struct Interval {
  double low = 0, high = 0;
  bool operator==(const Interval& o) const { return low == o.low && high == o.high; }
};
/** @brief Two numbers (e.g. a size or an offset). */
struct Pair {
  double first = 0, second = 0;
  bool operator==(const Pair& o) const { return first == o.first && second == o.second; }
};
/** @brief An RGB colour, each channel 0..255. */
struct Color {
  int r = 0, g = 0, b = 0;
  bool operator==(const Color& o) const { return r == o.r && g == o.g && b == o.b; }
};

/** @brief Every value a parameter can hold. Sets hold the chosen option's name,
 *  paths a string, angles radians, lists a vector of numbers, text lists a vector of strings. */
using ParamValue =
    std::variant<bool, int, double, std::string, Interval, Pair, Color, std::vector<double>, std::vector<std::string>>;

enum class ParamKind {
  Bool,
  Int,
  Double,
  String,
  IntRange,
  DoubleRange,
  Interval,
  Set,
  Angle,
  Path,
  Color,
  Pair,
  List,
  TextList
};
/** @brief What a path parameter's file is for: read (a regular file), written (its folder exists),
 *  a folder a node writes into, or read as a file or a folder of files (a labelling tool's). */
enum class PathMode { Read, Write, Directory, ReadFileOrFolder };

/** @brief A parameter's declaration: what a node type says about one parameter. */
struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::Int;
  ParamValue default_value;
  std::string description;
  double min = 0, max = 0, step = 0;  ///< ranges, intervals, angles
  std::vector<std::string> options;  ///< sets; paths: the kinds of file (e.g. "*.bag"), for a file chooser
  PathMode path_mode = PathMode::Read;  ///< paths
  bool interactive = false;  ///< gets ports by default
  bool file_name = false;  ///< strings: a single file name, never a path (no '/', not "." or "..")
  bool shapes_interface = false;  ///< a change may change the node's ports (Manifest::shapedBy)
  bool every_set = false;  ///< parameterChanged() on every set, even to the same value
  bool legacy = false;  ///< kept so graphs saved before its replacement load: front ends hide it at its default

  ParamSpec& describe(std::string text) {
    description = std::move(text);
    return *this;
  }
  ParamSpec& makeInteractive(bool on = true) {
    interactive = on;
    return *this;
  }
  /** @brief A string that names a file inside a folder given elsewhere: it cannot carry a path out of it. */
  ParamSpec& fileName() {
    file_name = true;
    return *this;
  }
  /** @brief Its value decides the node's ports (Manifest::shapedBy): setting it is an edit of the
   *  node's interface, so it is set by edits only and cannot have ports itself. */
  ParamSpec& shapesInterface() {
    shapes_interface = true;
    return *this;
  }
  /** @brief Setting it is a command as well as a value (e.g. a player's frame: go there, and
   *  send it again): parameterChanged() runs on every set, also to the value it has. */
  ParamSpec& everySet() {
    every_set = true;
    return *this;
  }

  /** @brief Checks a value's type and bounds; the message names the parameter. */
  Status validate(const ParamValue& value) const;
  /** @brief Parses YAML text ("12", "[1, 2]", "{r: 1, g: 2, b: 3}", "mean") and validates it. */
  Result<ParamValue> parse(std::string_view yaml_text) const;
  /** @brief The type carried by this parameter's input and output ports. */
  const TypeInfo* portType() const;
  /** @brief A readable kind, e.g. "int range", "set". */
  std::string kindName() const;
};

/** @brief A value as YAML flow text, e.g. "3", "0.5", "[1, 2]", "{r: 1, g: 2, b: 3}". */
std::string toText(const ParamValue& value);
/** @brief A message carrying the value; its type is the parameter's port type. */
Message toMessage(const ParamValue& value);
/** @brief A parameter value from a message at a parameter input; fails on a wrong type. */
Result<ParamValue> fromMessage(const ParamSpec& spec, const Message& message);

/** Builders: apex::param::range("block_size", 3, 99, 2, 11).describe("...") */
namespace param {
ParamSpec boolean(std::string name, bool def);
ParamSpec integer(std::string name, int def);
ParamSpec real(std::string name, double def);
ParamSpec text(std::string name, std::string def);
ParamSpec range(std::string name, int min, int max, int step, int def);
ParamSpec range(std::string name, double min, double max, double step, double def);
ParamSpec interval(std::string name, double min, double max, double low, double high, double step = 0);
ParamSpec options(std::string name, std::vector<std::string> options, std::string def);
ParamSpec angle(std::string name, double def_radians, double min = -3.14159265358979323846, double max = 3.14159265358979323846);
ParamSpec path(std::string name, std::string def, PathMode mode = PathMode::Read);
ParamSpec color(std::string name, int r, int g, int b);
ParamSpec pair(std::string name, double first, double second);
ParamSpec list(std::string name, std::vector<double> def);
ParamSpec textList(std::string name, std::vector<std::string> def);
}  // namespace param

}  // namespace apex

APEX_TYPE_NAME(apex::Interval, "interval");
APEX_TYPE_NAME(apex::Pair, "pair");
APEX_TYPE_NAME(apex::Color, "color");
APEX_TYPE_NAME(std::vector<std::string>, "list<string>");
