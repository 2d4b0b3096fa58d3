// Parameter values to and from YAML text. With graph_text.cpp and yaml_load.cpp the only code
// that includes yaml-cpp.
#include <yaml-cpp/yaml.h>

#include <charconv>

#include "apex/core/param.hpp"
#include "yaml_load.hpp"

namespace apex {
namespace {

std::string number(double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  // keep doubles recognisable as such when read back by people and tools
  if (s.find_first_of(".eEni") == std::string::npos) s += ".0";
  return s;
}

/** Whether YAML reads `plain` back as the string `s`, not as a bool, number, null or anything else. */
bool readsBackAs(const std::string& plain, const std::string& s) {
  try {
    const YAML::Node back = detail::loadYaml(plain);  // its shape checked too: "- - - x" nests
    bool b;
    double d;
    return back.IsScalar() && back.Tag() != "!" && back.Scalar() == s && !YAML::convert<bool>::decode(back, b) &&
           !YAML::convert<double>::decode(back, d);
  } catch (const YAML::Exception&) {
    return false;
  }
}

/** A string as YAML; quoted where plain text would not read back as the same string (a bool, a
 *  number, null, or what yaml-cpp's emitter leaves plain but cannot read, such as "---"). */
std::string quoted(const std::string& s) {
  YAML::Emitter e;
  e << YAML::Flow << s;
  if (readsBackAs(e.c_str(), s)) return e.c_str();
  YAML::Emitter q;
  q << YAML::DoubleQuoted << s;
  return q.c_str();
}

struct Parser {
  const ParamSpec& spec;
  const YAML::Node& node;

  Status fail(const std::string& what) const {
    YAML::Emitter e;
    e << YAML::Flow << node;
    return Status::error("parameter '" + spec.name + "' (" + spec.kindName() + ") expects " + what + ", got '" + e.c_str() + "'");
  }
  template <class T>
  bool scalar(const YAML::Node& n, T& out) const {
    if (!n || !n.IsScalar()) return false;  // a missing map key is an invalid node
    return YAML::convert<T>::decode(n, out);
  }
  Result<std::vector<double>> numbers(std::size_t count) const {
    std::vector<double> v;
    if (!node.IsSequence() || (count && node.size() != count)) return Status::error("");
    for (const auto& item : node) {
      double d;
      if (!scalar(item, d)) return Status::error("");
      v.push_back(d);
    }
    return v;
  }

  Result<ParamValue> parse() const {
    switch (spec.kind) {
      case ParamKind::Bool: {
        bool b;
        if (scalar(node, b)) return ParamValue(b);
        return fail("true or false");
      }
      case ParamKind::Int:
      case ParamKind::IntRange: {
        int i;
        if (scalar(node, i)) return ParamValue(i);
        return fail("an integer");
      }
      case ParamKind::Double:
      case ParamKind::DoubleRange:
      case ParamKind::Angle: {
        double d;
        if (scalar(node, d)) return ParamValue(d);
        return fail("a number");
      }
      case ParamKind::String:
      case ParamKind::Path:
      case ParamKind::Set: {
        std::string s;
        if (scalar(node, s)) return ParamValue(s);
        return fail("a string");
      }
      case ParamKind::Interval:
        return pairLike<Interval>("low", "high");
      case ParamKind::Pair:
        return pairLike<Pair>("first", "second");
      case ParamKind::Color:
        return color();
      case ParamKind::List: {
        auto v = numbers(0);
        if (!v) return fail("a list of numbers, e.g. [1, 2.5]");
        return ParamValue(v.value());
      }
      case ParamKind::TextList: {
        std::vector<std::string> v;
        if (!node.IsSequence()) return fail("a list of strings, e.g. [/camera/image_raw, /camera/points]");
        for (const auto& item : node) {
          std::string text;
          if (!scalar(item, text)) return fail("a list of strings, e.g. [/camera/image_raw, /camera/points]");
          v.push_back(std::move(text));
        }
        return ParamValue(std::move(v));
      }
    }
    return fail("a value");
  }

  template <class T>
  Result<ParamValue> pairLike(const char* a, const char* b) const {
    double x, y;
    if (node.IsMap() && scalar(node[a], x) && scalar(node[b], y)) return ParamValue(T{x, y});
    auto v = numbers(2);
    if (v) return ParamValue(T{v.value()[0], v.value()[1]});
    return fail(std::string("two numbers, e.g. [1, 2] or {") + a + ": 1, " + b + ": 2}");
  }

  Result<ParamValue> color() const {
    int r, g, b;
    if (node.IsMap() && scalar(node["r"], r) && scalar(node["g"], g) && scalar(node["b"], b)) return ParamValue(Color{r, g, b});
    if (node.IsSequence() && node.size() == 3 && scalar(node[0], r) && scalar(node[1], g) && scalar(node[2], b))
      return ParamValue(Color{r, g, b});
    return fail("a colour, e.g. [255, 0, 0] or {r: 255, g: 0, b: 0}");
  }
};

}  // namespace

Result<ParamValue> ParamSpec::parse(std::string_view text) const {
  // No text at all is the empty string, as a cleared field or `value: ''` over rosservice means it
  // (YAML would read it as null). Not blanks: "\r" is a string toText leaves plain.
  if (text.empty() && (kind == ParamKind::String || kind == ParamKind::Path)) {
    ParamValue none{std::string()};
    if (auto st = validate(none); !st) return st;
    return none;
  }
  YAML::Node node;
  try {
    node = detail::loadYaml(std::string(text));
  } catch (const YAML::Exception& e) {
    return Status::error("parameter '" + name + "': '" + std::string(text) + "' is not valid YAML: " + e.msg);
  }
  auto value = Parser{*this, node}.parse();
  if (!value) return value;
  if (auto st = validate(value.value()); !st) return st;
  return value;
}

std::string toText(const ParamValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(int i) const { return std::to_string(i); }
    std::string operator()(double d) const { return number(d); }
    std::string operator()(const std::string& s) const { return quoted(s); }
    std::string operator()(const Interval& i) const { return "[" + number(i.low) + ", " + number(i.high) + "]"; }
    std::string operator()(const Pair& p) const { return "[" + number(p.first) + ", " + number(p.second) + "]"; }
    std::string operator()(const Color& c) const {
      return "[" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + "]";
    }
    std::string operator()(const std::vector<double>& v) const {
      std::string s = "[";
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + number(v[i]);
      return s + "]";
    }
    std::string operator()(const std::vector<std::string>& v) const {
      YAML::Emitter e;  // in a flow sequence ',', '[' and ']' need quotes: the emitter knows
      e << YAML::Flow << YAML::BeginSeq;
      for (const auto& s : v) e << s;
      e << YAML::EndSeq;
      return e.c_str();
    }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace apex
