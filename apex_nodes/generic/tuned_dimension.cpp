// The Optimizer's dimensions (tuned_dimension.hpp).
#include "tuned_dimension.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace apex_nodes {
namespace tuning {

namespace {

const char* const kHow =
    "write 'name', 'name min max', 'name int', 'name min max int', 'name interval [min max]', "
    "'name choice [option ...]' or 'name bool', e.g. 'block_size 3 51 int'";

bool readNumber(const std::string& word, double& out) {
  std::istringstream in(word);
  return (in >> out) && in.peek() == EOF && std::isfinite(out);
}

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

/** `min max` at words[i], if there: consumed, with its check. */
apex::Status readRange(const std::vector<std::string>& words, std::size_t& i, const std::string& text, DimensionText& d) {
  if (i + 1 < words.size() && readNumber(words[i], d.min) && readNumber(words[i + 1], d.max)) {
    d.has_range = true;
    i += 2;
    if (d.min > d.max) return apex::Status::error("dimension '" + text + "': min is above max");
  }
  return apex::Status::ok();
}

/** The range: the parameter's, narrowed to the dimension's if it gives one. */
void narrow(const DimensionText& d, const std::string& text, const apex::ParamSpec& spec, const std::string& where, double& lo,
            double& hi) {
  lo = d.min, hi = d.max;
  if (spec.max > spec.min) {  // within the parameter's range, whatever the dimension says
    lo = d.has_range ? std::max(d.min, spec.min) : spec.min;
    hi = d.has_range ? std::min(d.max, spec.max) : spec.max;
    if (lo > hi)
      throw std::invalid_argument("dimension '" + text + "' lies outside the range of " + where + " [" + number(spec.min) + ", " +
                                  number(spec.max) + "]");
  } else if (!d.has_range) {
    throw std::invalid_argument("dimension '" + d.name + "': " + where + " has no range; give one, e.g. '" + d.name + " 0 10'");
  }
}

void requireKind(const std::string& text, const apex::ParamSpec& spec, const std::string& where, apex::ParamKind kind,
                 const char* words) {
  if (spec.kind != kind)
    throw std::invalid_argument("dimension '" + text + "': " + where + " is a " + spec.kindName() + " parameter, not " + words);
}

/** Point `k` of the grid from `origin` by `step`: a step of 1/n as k/n (0.83, not 83 * 0.01 =
 *  0.8300000000000001). */
double gridPoint(double origin, double step, double k) {
  const double per_unit = std::round(1 / step);
  return std::abs(per_unit * step - 1) < 1e-9 ? origin + k / per_unit : origin + k * step;
}

/** The indices of the first and last grid points within [lo, hi] (first > last: none). */
std::pair<double, double> gridSpan(double lo, double hi, double step, double origin) {
  return {std::ceil((lo - origin) / step - 1e-9), std::floor((hi - origin) / step + 1e-9)};
}

/** Throws unless a value of the dimension lies in [lo, hi] (an integer; a point of the step's grid). */
void requireValue(const std::string& text, double lo, double hi, bool integer, double step, double origin) {
  const bool none = step > 0 ? gridSpan(lo, hi, step, origin).first > gridSpan(lo, hi, step, origin).second
                             : integer && std::ceil(lo) > std::floor(hi);
  if (none)
    throw std::invalid_argument(
        "dimension '" + text + "': no value of the parameter lies between " + number(lo) + " and " + number(hi) +
        (step > 0 ? " (it goes in steps of " + number(step) + " from " + number(origin) + ")" : " (it is an integer)"));
}

}  // namespace

apex::Result<DimensionText> parseDimension(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  if (words.empty()) return apex::Status::error(std::string("an empty dimension: ") + kHow);
  DimensionText d;
  d.name = words[0];
  std::size_t i = 1;
  const std::string kind = words.size() > 1 ? words[1] : "";
  if (kind == "choice") {
    d.kind = Kind::Choice;
    d.options.assign(words.begin() + 2, words.end());
    return d;
  }
  if (kind == "bool") {
    d.kind = Kind::Flag;
    i = 2;
  } else if (kind == "interval") {
    d.kind = Kind::Interval;
    i = 2;
    if (auto st = readRange(words, i, text, d); !st) return st;
  } else {
    if (auto st = readRange(words, i, text, d); !st) return st;
    if (i < words.size() && words[i] == "int") d.kind = Kind::Integer, ++i;
  }
  if (i != words.size()) return apex::Status::error("dimension '" + text + "': cannot read '" + words[i] + "'; " + kHow);
  return d;
}

const apex::TypeInfo* outputType(Kind kind) {
  switch (kind) {
    case Kind::Integer:
      return apex::typeOf<int>();
    case Kind::Interval:
      return apex::typeOf<apex::Interval>();
    case Kind::Choice:
      return apex::typeOf<std::string>();
    case Kind::Flag:
      return apex::typeOf<bool>();
    default:
      return apex::typeOf<double>();
  }
}

apex::Status addOutputs(const std::vector<std::string>& dimensions, apex::Manifest& m) {
  for (const auto& text : dimensions) {
    auto d = parseDimension(text);
    if (!d) return d.status();
    m.outputs.push_back({d->name, outputType(d->kind), false,
                         "the candidate's value of '" + d->name + "': connect it to the parameter it tunes"});
  }
  return apex::Status::ok();
}

TunedDimension resolve(const DimensionText& d, const std::string& text, const apex::ParamSpec& spec, const std::string& where,
                       const apex::ParamValue& before) {
  TunedDimension t;
  t.port = d.name;
  t.kind = d.kind;
  t.before = before;
  double lo = 0, hi = 0;
  switch (d.kind) {
    case Kind::Number:
    case Kind::Integer:
      narrow(d, text, spec, where, lo, hi);
      t.coordinates.push_back({d.name, lo, hi, d.kind == Kind::Integer});
      if (d.kind == Kind::Integer && spec.step > 1) t.step = spec.step, t.origin = spec.min;
      requireValue(text, lo, hi, d.kind == Kind::Integer, t.step, t.origin);
      break;
    case Kind::Interval:
      requireKind(text, spec, where, apex::ParamKind::Interval, "an interval");
      narrow(d, text, spec, where, lo, hi);
      t.coordinates.push_back({d.name + ".low", lo, hi, false});
      t.coordinates.push_back({d.name + ".high", lo, hi, false});
      if (spec.step > 0) t.step = spec.step, t.origin = spec.min;
      requireValue(text, lo, hi, false, t.step, t.origin);
      break;
    case Kind::Choice:
      requireKind(text, spec, where, apex::ParamKind::Set, "a choice");
      t.options = d.options.empty() ? spec.options : d.options;
      for (const auto& o : t.options)
        if (std::find(spec.options.begin(), spec.options.end(), o) == spec.options.end())
          throw std::invalid_argument("dimension '" + text + "': '" + o + "' is not an option of " + where);
      if (t.options.empty()) throw std::invalid_argument("dimension '" + text + "': " + where + " has no options");
      t.coordinates.push_back({d.name, 0, static_cast<double>(t.options.size() - 1), true});
      break;
    case Kind::Flag:
      requireKind(text, spec, where, apex::ParamKind::Bool, "a flag (bool)");
      t.coordinates.push_back({d.name, 0, 1, true});
      break;
  }
  return t;
}

apex::ParamValue TunedDimension::value(const double* x) const {
  const auto snap = [&](double v, const search::Dimension& c) {
    if (c.integer) v = std::round(v);
    if (step > 0) {
      v = gridPoint(origin, step, std::round((v - origin) / step));
      while (v > c.max && v - step >= origin) v -= step;
      while (v < c.min) v += step;
    }
    return std::min(std::max(v, c.min), std::max(c.min, c.max));
  };
  switch (kind) {
    case Kind::Integer:
      return static_cast<int>(std::lround(snap(x[0], coordinates[0])));
    case Kind::Interval: {
      const double a = snap(x[0], coordinates[0]), b = snap(x[1], coordinates[1]);
      return apex::Interval{std::min(a, b), std::max(a, b)};
    }
    case Kind::Choice: {
      const long i = std::lround(std::min(std::max(x[0], 0.0), static_cast<double>(options.size() - 1)));
      return options[static_cast<std::size_t>(i)];
    }
    case Kind::Flag:
      return x[0] >= 0.5;
    default:
      return snap(x[0], coordinates[0]);
  }
}

std::vector<TunedDimension> resolveAll(const std::vector<std::string>& dimensions, const TargetsOf& targets) {
  std::vector<TunedDimension> out;
  for (const auto& text : dimensions) {
    const DimensionText d = parseDimension(text).value();
    const auto fed = targets(d.name);
    if (fed.empty())
      throw std::invalid_argument("dimension '" + d.name +
                                  "': its output feeds no parameter; connect it to the "
                                  "parameter it tunes");
    const apex::ParamSpec& spec = fed.front().spec;
    out.push_back(resolve(d, text, spec, fed.front().node + "/" + spec.name, fed.front().value));
  }
  if (out.empty()) throw std::invalid_argument("no dimensions: add one per parameter to tune, e.g. 'c 0 60'");
  return out;
}

std::vector<apex::ParamValue> valuesAt(const std::vector<TunedDimension>& dims, const std::vector<double>& x) {
  std::vector<apex::ParamValue> out;
  std::size_t at = 0;
  for (const auto& d : dims) {
    out.push_back(d.value(x.data() + at));
    at += d.coordinates.size();
  }
  return out;
}

namespace {

/** "low: a, high: b[, step: s]": the coordinate's range on the grid from `origin` by `step` (0: none). */
std::string gridText(const search::Dimension& c, double step, double origin) {
  double lo = c.min, hi = c.max;
  if (step > 0) {
    const auto [first, last] = gridSpan(c.min, c.max, step, origin);
    lo = gridPoint(origin, step, first), hi = gridPoint(origin, step, last);
  } else if (c.integer) {
    lo = std::ceil(c.min), hi = std::floor(c.max), step = 1;
  }
  const auto text = [&](double v) { return c.integer ? std::to_string(std::llround(v)) : apex::toText(v); };
  return "low: " + text(lo) + ", high: " + text(hi) + (step > 0 ? ", step: " + text(step) : "");
}

/** A word as YAML reads it back as that word: quoted ("8", "on" and "1.50" stay text). */
std::string quoted(const std::string& word) {
  std::string out = "\"";
  for (char c : word) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string TunedDimension::spaceText() const {
  std::string out = "{name: " + port + ", kind: ";
  switch (kind) {
    case Kind::Number:
      return out + "number, " + gridText(coordinates[0], step, origin) + "}";
    case Kind::Integer:
      return out + "integer, " + gridText(coordinates[0], step, origin) + "}";
    case Kind::Interval:
      return out + "interval, " + gridText(coordinates[0], step, origin) + "}";
    case Kind::Choice: {
      std::string options;
      for (const auto& o : this->options) options += (options.empty() ? "" : ", ") + quoted(o);
      return out + "choice, options: [" + options + "]}";
    }
    case Kind::Flag:
      return out + "flag}";
  }
  return out + "number}";
}

}  // namespace tuning
}  // namespace apex_nodes
