// Parameter declarations, validation and the ports' message conversion.
// Text parsing lives in param_text.cpp, next to the other YAML code.
#include "apex/core/param.hpp"

#include "apex/core/text.hpp"

#include <cmath>
#include <sstream>

namespace apex {
namespace {

template <class T>
bool holds(const ParamValue& v) {
  return std::holds_alternative<T>(v);
}

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

Status outOfRange(const ParamSpec& s, const std::string& got) {
  std::string m = "parameter '" + s.name + "': " + got + " is out of range [" + num(s.min) + ", " + num(s.max) + "]";
  return Status::error(m);
}

Status wrongType(const ParamSpec& s, const ParamValue& v) {
  return Status::error("parameter '" + s.name + "' (" + s.kindName() + ") cannot hold the value " + toText(v));
}

Status checkNumber(const ParamSpec& s, double v) {
  if (!std::isfinite(v)) return Status::error("parameter '" + s.name + "': " + num(v) + " is not a finite number");
  if (v < s.min || v > s.max) return outOfRange(s, num(v));
  return Status::ok();
}

Status checkIntRange(const ParamSpec& s, int v) {
  if (auto st = checkNumber(s, v); !st) return st;
  const int step = static_cast<int>(s.step);
  if (step > 1 && (v - static_cast<int>(s.min)) % step != 0) {
    return Status::error("parameter '" + s.name + "': " + std::to_string(v) + " is not on the step: allowed are " + num(s.min) +
                         ", " + num(s.min + s.step) + ", ... up to " + num(s.max));
  }
  return Status::ok();
}

Status checkSet(const ParamSpec& s, const std::string& v) {
  for (const auto& o : s.options)
    if (o == v) return Status::ok();
  std::string list;
  for (const auto& o : s.options) list += (list.empty() ? "" : ", ") + o;
  return Status::error("parameter '" + s.name + "': '" + v + "' is not one of: " + list);
}

/** Every number of a list, pair or interval is finite: NaN and infinities print as text YAML reads as
 *  a string, so a saved graph would not load again. */
Status checkFinite(const ParamSpec& s, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      return Status::error("parameter '" + s.name + "': element " + std::to_string(i + 1) + " (" + num(values[i]) +
                           ") is not a finite number");
  return Status::ok();
}

Status checkInterval(const ParamSpec& s, const Interval& v) {
  if (auto st = checkFinite(s, {v.low, v.high}); !st) return st;
  if (v.low > v.high) return Status::error("parameter '" + s.name + "': low " + num(v.low) + " is above high " + num(v.high));
  if (v.low < s.min || v.high > s.max) return outOfRange(s, "[" + num(v.low) + ", " + num(v.high) + "]");
  return Status::ok();
}

Status checkColor(const ParamSpec& s, const Color& c) {
  for (int ch : {c.r, c.g, c.b}) {
    if (ch < 0 || ch > 255)
      return Status::error("parameter '" + s.name + "': colour channel " + std::to_string(ch) + " is outside 0..255");
  }
  return Status::ok();
}

ParamSpec make(std::string name, ParamKind kind, ParamValue def) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = kind;
  s.default_value = std::move(def);
  return s;
}

Status checkText(const ParamSpec& s, const std::string& v) {
  if (auto st = apex::checkText(v); !st) return Status::error("parameter '" + s.name + "': " + st.message());
  return Status::ok();
}

Status checkFileName(const ParamSpec& s, const std::string& v) {
  if (v.find('/') == std::string::npos && v.find('\0') == std::string::npos && v != "." && v != "..") return Status::ok();
  return Status::error("parameter '" + s.name + "' is a file name, not a path: '" + v + "' (no '/', not '.' or '..')");
}

}  // namespace

Status ParamSpec::validate(const ParamValue& v) const {
  switch (kind) {
    case ParamKind::Bool:
      return holds<bool>(v) ? Status::ok() : wrongType(*this, v);
    case ParamKind::Int:
      return holds<int>(v) ? Status::ok() : wrongType(*this, v);
    case ParamKind::Double:
      if (!holds<double>(v)) return wrongType(*this, v);
      return std::isfinite(std::get<double>(v)) ? Status::ok() : Status::error("parameter '" + name + "' is not a finite number");
    case ParamKind::String:
      if (!holds<std::string>(v)) return wrongType(*this, v);
      if (auto st = checkText(*this, std::get<std::string>(v)); !st) return st;
      return file_name ? checkFileName(*this, std::get<std::string>(v)) : Status::ok();
    case ParamKind::Path:
      return holds<std::string>(v) ? checkText(*this, std::get<std::string>(v)) : wrongType(*this, v);
    case ParamKind::IntRange:
      return holds<int>(v) ? checkIntRange(*this, std::get<int>(v)) : wrongType(*this, v);
    case ParamKind::DoubleRange:
    case ParamKind::Angle:
      return holds<double>(v) ? checkNumber(*this, std::get<double>(v)) : wrongType(*this, v);
    case ParamKind::Interval:
      return holds<Interval>(v) ? checkInterval(*this, std::get<Interval>(v)) : wrongType(*this, v);
    case ParamKind::Set:
      return holds<std::string>(v) ? checkSet(*this, std::get<std::string>(v)) : wrongType(*this, v);
    case ParamKind::Color:
      return holds<Color>(v) ? checkColor(*this, std::get<Color>(v)) : wrongType(*this, v);
    case ParamKind::Pair:
      if (!holds<Pair>(v)) return wrongType(*this, v);
      return checkFinite(*this, {std::get<Pair>(v).first, std::get<Pair>(v).second});
    case ParamKind::List:
      return holds<std::vector<double>>(v) ? checkFinite(*this, std::get<std::vector<double>>(v)) : wrongType(*this, v);
    case ParamKind::TextList:
      if (!holds<std::vector<std::string>>(v)) return wrongType(*this, v);
      for (const auto& text : std::get<std::vector<std::string>>(v))
        if (auto st = checkText(*this, text); !st) return st;
      return Status::ok();
  }
  return wrongType(*this, v);
}

const TypeInfo* ParamSpec::portType() const {
  switch (kind) {
    case ParamKind::Bool:
      return typeOf<bool>();
    case ParamKind::Int:
    case ParamKind::IntRange:
      return typeOf<int>();
    case ParamKind::Double:
    case ParamKind::DoubleRange:
    case ParamKind::Angle:
      return typeOf<double>();
    case ParamKind::String:
    case ParamKind::Set:
    case ParamKind::Path:
      return typeOf<std::string>();
    case ParamKind::Interval:
      return typeOf<Interval>();
    case ParamKind::Pair:
      return typeOf<Pair>();
    case ParamKind::Color:
      return typeOf<Color>();
    case ParamKind::List:
      return typeOf<std::vector<double>>();
    case ParamKind::TextList:
      return typeOf<std::vector<std::string>>();
  }
  return typeOf<Any>();
}

std::string ParamSpec::kindName() const {
  switch (kind) {
    case ParamKind::Bool:
      return "bool";
    case ParamKind::Int:
      return "int";
    case ParamKind::Double:
      return "double";
    case ParamKind::String:
      return "string";
    case ParamKind::IntRange:
      return "int range";
    case ParamKind::DoubleRange:
      return "double range";
    case ParamKind::Interval:
      return "interval";
    case ParamKind::Set:
      return "set";
    case ParamKind::Angle:
      return "angle";
    case ParamKind::Path:
      return "path";
    case ParamKind::Color:
      return "color";
    case ParamKind::Pair:
      return "pair";
    case ParamKind::List:
      return "list";
    case ParamKind::TextList:
      return "text list";
  }
  return "unknown";
}

Message toMessage(const ParamValue& value) {
  return std::visit([](const auto& v) { return Message::make(v); }, value);
}

Result<ParamValue> fromMessage(const ParamSpec& spec, const Message& m) {
  ParamValue v;
  if (auto p = m.as<bool>()) v = *p;
  else if (auto p = m.as<int>()) v = spec.portType() == typeOf<double>() ? ParamValue(double(*p)) : ParamValue(*p);
  else if (auto p = m.as<double>()) v = *p;
  else if (auto p = m.as<std::string>()) v = *p;
  else if (auto p = m.as<Interval>()) v = *p;
  else if (auto p = m.as<Pair>()) v = *p;
  else if (auto p = m.as<Color>()) v = *p;
  else if (auto p = m.as<std::vector<double>>()) v = *p;
  else if (auto p = m.as<std::vector<std::string>>()) v = *p;
  else
    return Status::error("parameter '" + spec.name + "' (" + spec.kindName() + ") cannot take a message of type " + m.typeName());
  if (auto st = spec.validate(v); !st) return st;
  return v;
}

namespace param {
ParamSpec boolean(std::string n, bool d) { return make(std::move(n), ParamKind::Bool, d); }
ParamSpec integer(std::string n, int d) { return make(std::move(n), ParamKind::Int, d); }
ParamSpec real(std::string n, double d) { return make(std::move(n), ParamKind::Double, d); }
ParamSpec text(std::string n, std::string d) { return make(std::move(n), ParamKind::String, std::move(d)); }
ParamSpec range(std::string n, int min, int max, int step, int d) {
  auto s = make(std::move(n), ParamKind::IntRange, d);
  s.min = min, s.max = max, s.step = step;
  return s;
}
ParamSpec range(std::string n, double min, double max, double step, double d) {
  auto s = make(std::move(n), ParamKind::DoubleRange, d);
  s.min = min, s.max = max, s.step = step;
  return s;
}
ParamSpec interval(std::string n, double min, double max, double low, double high, double step) {
  auto s = make(std::move(n), ParamKind::Interval, Interval{low, high});
  s.min = min, s.max = max, s.step = step;
  return s;
}
ParamSpec options(std::string n, std::vector<std::string> opts, std::string d) {
  auto s = make(std::move(n), ParamKind::Set, std::move(d));
  s.options = std::move(opts);
  return s;
}
ParamSpec angle(std::string n, double d, double min, double max) {
  auto s = make(std::move(n), ParamKind::Angle, d);
  s.min = min, s.max = max;
  return s;
}
ParamSpec path(std::string n, std::string d, PathMode mode) {
  auto s = make(std::move(n), ParamKind::Path, std::move(d));
  s.path_mode = mode;
  return s;
}
ParamSpec color(std::string n, int r, int g, int b) { return make(std::move(n), ParamKind::Color, Color{r, g, b}); }
ParamSpec pair(std::string n, double a, double b) { return make(std::move(n), ParamKind::Pair, Pair{a, b}); }
ParamSpec list(std::string n, std::vector<double> d) { return make(std::move(n), ParamKind::List, std::move(d)); }
ParamSpec textList(std::string n, std::vector<std::string> d) { return make(std::move(n), ParamKind::TextList, std::move(d)); }
}  // namespace param

}  // namespace apex
