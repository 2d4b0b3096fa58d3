// Ports and parameters declared once: a typed constant that the manifest lists and the node's
// handle reads, so that a name or a C++ type cannot disagree between the two.
//
//   class Gain : public apex::Node {
//    public:
//     static inline const apex::InputPort<int> kIn{"in", "the value"};
//     static inline const apex::OutputPort<int> kOut{"out", "in times gain"};
//     static inline const apex::ParamDecl<int> kGain = apex::param::integer("gain").range(0, 10).init(2);
//     static apex::Manifest manifest() { return apex::Manifest("Multiplies").input(kIn).output(kOut).param(kGain); }
//     void process() override { out_.publish(*in_.get() * gain_.get()); }
//    private:
//     apex::Input<int> in_{this, kIn};       // apex::Input<double> in_{this, kIn} does not compile
//     apex::Output<int> out_{this, kOut};
//     apex::Param<int> gain_{this, kGain};
//   };
#pragma once

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "apex/core/param.hpp"

namespace apex {

template <class T>
class ParamDecl;
template <class V>
class ChoiceDecl;
namespace param {
ParamDecl<std::string> choice(std::string name, std::vector<std::string> options);
ParamDecl<double> angle(std::string name);
}  // namespace param

/** @brief An input carrying T. `optional`: ignored while unconnected, may receive Nothing. */
template <class T>
struct InputPort {
  const char* name;
  const char* description = "";
  bool optional = false;
};

/** @brief An output carrying T. */
template <class T>
struct OutputPort {
  const char* name;
  const char* description = "";
};

/** @brief A trigger: sends events. */
struct TriggerPort {
  const char* name;
  const char* description = "";
};

/** @brief A parameter of C++ type T, built by the param:: builders below with named steps in
 *  one order — kind, then range, step, init, then the rest:
 *    param::integer("kernel_size").range(1, 31).step(2).init(5).describe("odd")
 *  A manifest lists it (Manifest::param), a handle reads it (apex::Param<T>{this, decl}). */
template <class T>
class ParamDecl {
 public:
  /** Numbers and intervals are bounded by these; an int parameter's by ints. */
  using Bound = std::conditional_t<std::is_same_v<T, int>, int, double>;

  ParamDecl(std::string name, ParamKind kind, T init) {
    spec_.name = std::move(name);
    spec_.kind = kind;
    spec_.default_value = std::move(init);
  }

  /** @brief Bounds [min, max] of a number (it becomes a range), an angle or an interval. The
   *  value starts at min (an interval: the whole of it) unless init() says otherwise. */
  ParamDecl range(Bound min, Bound max) && {
    static_assert(std::is_same_v<T, int> || std::is_same_v<T, double> || std::is_same_v<T, Interval>,
                  "range() is for integer, number, angle and interval parameters");
    if (spec_.kind == ParamKind::Int) spec_.kind = ParamKind::IntRange;
    if (spec_.kind == ParamKind::Double) spec_.kind = ParamKind::DoubleRange;
    spec_.min = min, spec_.max = max;
    if (!init_given_) {
      if constexpr (std::is_same_v<T, Interval>) spec_.default_value = Interval{double(min), double(max)};
      else spec_.default_value = T(min);
    }
    return std::move(*this);
  }
  /** @brief The step between allowed values of a range (an integer range refuses values off it). */
  ParamDecl step(Bound step) && {
    static_assert(std::is_same_v<T, int> || std::is_same_v<T, double> || std::is_same_v<T, Interval>,
                  "step() is for integer, number and interval parameters");
    spec_.step = step;
    return std::move(*this);
  }
  /** @brief The value a new node starts with. */
  ParamDecl init(T value) && {
    spec_.default_value = std::move(value);
    init_given_ = true;
    return std::move(*this);
  }
  /** @brief What the parameter means, for the panel and `describe` (units, odd/even, ...). */
  ParamDecl describe(std::string text) && {
    spec_.description = std::move(text);
    return std::move(*this);
  }
  /** @brief Gets ports by default, so data can drive it (a paper's parameter port). */
  ParamDecl interactive() && {
    spec_.interactive = true;
    return std::move(*this);
  }
  /** @brief A path parameter: read (the default), written, or a folder. */
  ParamDecl mode(PathMode mode) && {
    static_assert(std::is_same_v<T, std::string>, "mode() is for path parameters");
    spec_.path_mode = mode;
    return std::move(*this);
  }
  /** @brief A path parameter's kinds of file, e.g. `.files({"*.bag"})`: the panel's file chooser
   *  lists those first (any file can still be chosen or typed). */
  ParamDecl files(std::vector<std::string> patterns) && {
    static_assert(std::is_same_v<T, std::string>, "files() is for path parameters");
    spec_.options = std::move(patterns);
    return std::move(*this);
  }
  /** @brief A text that names a file inside a folder given elsewhere (ParamSpec::fileName). */
  ParamDecl fileName() && {
    static_assert(std::is_same_v<T, std::string>, "fileName() is for text parameters");
    spec_.file_name = true;
    return std::move(*this);
  }
  /** @brief Its value decides the node's ports (ParamSpec::shapesInterface). */
  ParamDecl shapesInterface() && {
    spec_.shapes_interface = true;
    return std::move(*this);
  }
  /** @brief parameterChanged() on every set, also to the value it has (ParamSpec::everySet). */
  ParamDecl everySet() && {
    spec_.every_set = true;
    return std::move(*this);
  }

  /** @brief Replaced by another parameter but kept, so graphs saved before still load and run as
   *  they did (ParamSpec::legacy): the panel shows it only when it is set away from its default. */
  ParamDecl legacy() && {
    spec_.legacy = true;
    return std::move(*this);
  }

  const ParamSpec& spec() const { return spec_; }
  const std::string& name() const { return spec_.name; }
  operator const ParamSpec&() const { return spec_; }  // NOLINT: what Manifest::param takes

 private:
  friend ParamDecl<std::string> param::choice(std::string, std::vector<std::string>);
  friend ParamDecl<double> param::angle(std::string);
  template <class V>
  friend class ChoiceDecl;
  ParamSpec spec_;
  bool init_given_ = false;
};

/** @brief One option of a typed choice: the name a graph file and the panel use, the value
 *  process() reads (apex::Choice<V>::get), and what it means. */
template <class V>
struct Option {
  const char* name;
  V value;
  const char* description = "";
};

/** @brief A choice whose options are one table of Option<V>: the manifest's names, the
 *  description and the values process() reads all come from it, so they cannot drift apart, and
 *  a name that is not an option is refused when set, never met while firing:
 *    static inline const apex::ChoiceDecl<int> kShape = apex::param::choice<int>(
 *        "shape", {{"rect", cv::MORPH_RECT}, {"cross", cv::MORPH_CROSS}, {"ellipse", cv::MORPH_ELLIPSE}});
 *    apex::Choice<int> shape_{this, kShape};  // shape_.get() is cv::MORPH_RECT, ... */
template <class V>
class ChoiceDecl {
 public:
  ChoiceDecl(std::string name, std::vector<Option<V>> options)
      : options_(std::move(options)), decl_(std::move(name), ParamKind::Set, options_.empty() ? "" : options_.front().name) {
    decl_.spec_.options.clear();
    for (const auto& o : options_) decl_.spec_.options.push_back(o.name);
    setDescription("");
  }
  /** @brief The option a new node starts with (the first unless this says otherwise). */
  ChoiceDecl init(const std::string& option) && {
    decl_ = std::move(decl_).init(option);
    return std::move(*this);
  }
  /** @brief What the parameter means; the options' own descriptions follow it in brackets. */
  ChoiceDecl describe(const std::string& text) && {
    setDescription(text);
    return std::move(*this);
  }
  ChoiceDecl interactive() && {
    decl_ = std::move(decl_).interactive();
    return std::move(*this);
  }
  ChoiceDecl shapesInterface() && {
    decl_ = std::move(decl_).shapesInterface();
    return std::move(*this);
  }

  /** @brief The value of the option named `option`; the first option's if none is (the graph
   *  refuses such a name before a node could read it). */
  const V& valueOf(const std::string& option) const {
    for (const auto& o : options_)
      if (option == o.name) return o.value;
    return options_.front().value;
  }
  const std::vector<Option<V>>& options() const { return options_; }
  const ParamSpec& spec() const { return decl_.spec(); }
  const std::string& name() const { return decl_.name(); }
  operator const ParamSpec&() const { return decl_.spec(); }  // NOLINT: what Manifest::param takes

 private:
  void setDescription(const std::string& text) {  // "text (a: one; b: two)"
    std::string each;
    for (const auto& o : options_)
      if (*o.description) each += (each.empty() ? "" : "; ") + std::string(o.name) + ": " + o.description;
    decl_.spec_.description = text.empty() ? each : each.empty() ? text : text + " (" + each + ")";
  }
  std::vector<Option<V>> options_;
  ParamDecl<std::string> decl_;
};

/** Builders: the kind and the name; the rest by named steps (ParamDecl). */
namespace param {
inline ParamDecl<bool> flag(std::string name) { return {std::move(name), ParamKind::Bool, false}; }
inline ParamDecl<int> integer(std::string name) { return {std::move(name), ParamKind::Int, 0}; }
inline ParamDecl<double> number(std::string name) { return {std::move(name), ParamKind::Double, 0.0}; }
/** @brief Radians, within [-pi, pi] unless range() says otherwise. */
inline ParamDecl<double> angle(std::string name) {
  ParamDecl<double> d(std::move(name), ParamKind::Angle, 0.0);  // 0 unless init() says otherwise, not -pi
  d.spec_.min = -3.14159265358979323846, d.spec_.max = 3.14159265358979323846;
  return d;
}
inline ParamDecl<std::string> text(std::string name) { return {std::move(name), ParamKind::String, std::string()}; }
/** @brief One of `options` (the first unless init() says otherwise). */
inline ParamDecl<std::string> choice(std::string name, std::vector<std::string> options) {
  ParamDecl<std::string> d(std::move(name), ParamKind::Set, options.empty() ? std::string() : options.front());
  d.spec_.options = std::move(options);
  return d;
}
/** @brief One of the options of a table (ChoiceDecl): names, values and descriptions listed once. */
template <class V>
ChoiceDecl<V> choice(std::string name, std::vector<Option<V>> options) {
  return {std::move(name), std::move(options)};
}
/** @brief A file or folder (mode()): resolved against the runtime's file roots. */
inline ParamDecl<std::string> path(std::string name) { return {std::move(name), ParamKind::Path, std::string()}; }
inline ParamDecl<Interval> interval(std::string name) { return {std::move(name), ParamKind::Interval, Interval{}}; }
inline ParamDecl<Color> color(std::string name) { return {std::move(name), ParamKind::Color, Color{}}; }
inline ParamDecl<Pair> pair(std::string name) { return {std::move(name), ParamKind::Pair, Pair{}}; }
inline ParamDecl<std::vector<double>> list(std::string name) { return {std::move(name), ParamKind::List, std::vector<double>()}; }
inline ParamDecl<std::vector<std::string>> textList(std::string name) {
  return {std::move(name), ParamKind::TextList, std::vector<std::string>()};
}
}  // namespace param

}  // namespace apex
