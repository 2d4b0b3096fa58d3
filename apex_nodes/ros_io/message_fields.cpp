#include "message_fields.hpp"

#include <cctype>
#include <sstream>
#include <string_view>

namespace apex_nodes {
namespace {

using Kind = MessageField::Kind;
using Array = MessageField::Array;

constexpr std::uint64_t kMaxSize = std::uint64_t(1) << 40;  // a fixed size beyond this is a mistake
constexpr int kMaxDepth = 100;  // messages inside messages: bounds the recursion of reading too

struct Builtin {
  Kind kind;
  std::optional<std::uint64_t> size;  // none: a string
};

const std::map<std::string, Builtin>& builtins() {
  static const std::map<std::string, Builtin> table{{"bool", {Kind::Bool, 1}},       {"int8", {Kind::Int8, 1}},
                                                    {"uint8", {Kind::UInt8, 1}},     {"byte", {Kind::Int8, 1}},
                                                    {"char", {Kind::UInt8, 1}},      {"int16", {Kind::Int16, 2}},
                                                    {"uint16", {Kind::UInt16, 2}},   {"int32", {Kind::Int32, 4}},
                                                    {"uint32", {Kind::UInt32, 4}},   {"int64", {Kind::Int64, 8}},
                                                    {"uint64", {Kind::UInt64, 8}},   {"float32", {Kind::Float32, 4}},
                                                    {"float64", {Kind::Float64, 8}}, {"string", {Kind::String, std::nullopt}},
                                                    {"time", {Kind::Time, 8}},       {"duration", {Kind::Duration, 8}}};
  return table;
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return "";
  return std::string(s.substr(b, s.find_last_not_of(" \t\r") - b + 1));
}

bool isName(const std::string& s, bool slash_allowed) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && !(slash_allowed && c == '/')) return false;
  return true;
}

std::uint64_t product(std::uint64_t a, std::uint64_t b, const std::string& what) {
  if (a != 0 && b > kMaxSize / a) throw std::invalid_argument(what + " is too large (over 2^40 bytes)");
  return a * b;
}

/** "36" → 36; none for an empty text, a non-digit, or a number past uint32's range. */
std::optional<std::uint32_t> count(const std::string& digits) {
  if (digits.empty() || digits.size() > 10 || digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const unsigned long long n = std::stoull(digits);
  if (n > 0xFFFFFFFFull) return std::nullopt;
  return static_cast<std::uint32_t>(n);
}

struct FieldLine {
  std::string type, name;
};

/** A trimmed line of a definition as a field; none for a blank line, a comment or a constant. */
std::optional<FieldLine> fieldLine(const std::string& line, const std::string& where) {
  if (line.empty() || line[0] == '#') return std::nullopt;
  const auto eq = line.find('='), hash = line.find('#');
  if (eq != std::string::npos && (hash == std::string::npos || eq < hash)) return std::nullopt;  // a constant
  const auto space = line.find_first_of(" \t");
  FieldLine f{line.substr(0, space), space == std::string::npos ? "" : trim(line.substr(space, hash - space))};
  if (!isName(f.name, false)) throw std::invalid_argument(where + ": '" + line + "' is not a field (type name)");
  return f;
}

/** "geometry_msgs/Pose[3]" → a field of that type; a bare type is in `package` (Header: std_msgs). */
MessageField makeField(const FieldLine& line, const std::string& package, const std::string& where) {
  MessageField f;
  f.name = line.name;
  std::string base = line.type;
  if (const auto open = base.find('['); open != std::string::npos) {
    const std::string digits = base.substr(open + 1, base.size() - open - 2);
    const auto length = count(digits);
    if (base.back() != ']' || (!digits.empty() && !length))
      throw std::invalid_argument(where + ": '" + line.type + "' is not a type");
    f.array = digits.empty() ? Array::Variable : Array::Fixed;
    f.length = length.value_or(0);
    base.erase(open);
  }
  if (!isName(base, true)) throw std::invalid_argument(where + ": '" + line.type + "' is not a type");
  if (auto b = builtins().find(base); b != builtins().end()) {
    f.type = base, f.kind = b->second.kind, f.element_size = b->second.size;
  } else {
    if (base.find('/') == std::string::npos && package.empty())
      throw std::invalid_argument(where + ": type '" + base + "' has no package to be found in");
    f.type = base == "Header" ? "std_msgs/Header" : base.find('/') == std::string::npos ? package + "/" + base : base;
    f.kind = Kind::Message;
  }
  return f;
}

/** The fields, or the whole message, skipped: counts and lengths checked against what is left. */
void skipMessage(ByteCursor& c, const MessageType& t);

void skipElements(ByteCursor& c, const MessageField& f, std::uint64_t count) {
  if (f.element_size) {
    c.require(count, *f.element_size);
    c.take(count * *f.element_size);
    return;
  }
  c.require(count, 4);  // a string or a message of variable size holds at least one uint32 count
  for (std::uint64_t i = 0; i < count; ++i) {
    if (f.kind == Kind::String) c.take(c.next<std::uint32_t>());
    else skipMessage(c, *f.message);
  }
}

void skipField(ByteCursor& c, const MessageField& f) {
  if (f.size) return (void)c.take(*f.size);
  if (f.array == Array::None) return skipElements(c, f, 1);
  skipElements(c, f, f.array == Array::Fixed ? f.length : c.next<std::uint32_t>());
}

void skipMessage(ByteCursor& c, const MessageType& t) {
  if (t.size) return (void)c.take(*t.size);
  for (const MessageField& f : t.fields) skipField(c, f);
}

double readNumber(ByteCursor& c, Kind kind) {
  switch (kind) {
    case Kind::Bool:
      return c.next<std::uint8_t>() != 0;
    case Kind::Int8:
      return c.next<std::int8_t>();
    case Kind::UInt8:
      return c.next<std::uint8_t>();
    case Kind::Int16:
      return c.next<std::int16_t>();
    case Kind::UInt16:
      return c.next<std::uint16_t>();
    case Kind::Int32:
      return c.next<std::int32_t>();
    case Kind::UInt32:
      return c.next<std::uint32_t>();
    case Kind::Int64:
      return static_cast<double>(c.next<std::int64_t>());
    case Kind::UInt64:
      return static_cast<double>(c.next<std::uint64_t>());
    case Kind::Float32:
      return c.next<float>();
    case Kind::Float64:
      return c.next<double>();
    case Kind::Time: {
      const auto sec = c.next<std::uint32_t>();
      return sec + c.next<std::uint32_t>() * 1e-9;
    }
    case Kind::Duration: {
      const auto sec = c.next<std::int32_t>();
      return sec + c.next<std::int32_t>() * 1e-9;
    }
    default:
      throw std::logic_error("not a number");  // the path was checked
  }
}

}  // namespace

std::string MessageField::typeText() const {
  if (array == Array::None) return type;
  return type + "[" + (array == Array::Fixed ? std::to_string(length) : "") + "]";
}

const MessageField* MessageType::find(const std::string& field) const {
  for (const MessageField& f : fields)
    if (f.name == field) return &f;
  return nullptr;
}

std::string MessageType::fieldNames() const {
  std::string out;
  for (const MessageField& f : fields) out += (out.empty() ? "" : ", ") + f.name;
  return out.empty() ? "no fields" : out;
}

MessageSchema::MessageSchema(const std::string& datatype, const std::string& definition) {
  std::string current = datatype;
  bool duplicate = false;  // a section of a type seen before: skipped
  types_[current].name = current;
  std::istringstream in(definition);
  int number = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++number;
    const std::string line = trim(raw);
    if (!line.empty() && line.find_first_not_of('=') == std::string::npos) continue;  // a separator
    if (line.rfind("MSG:", 0) == 0) {
      current = trim(line.substr(4));
      duplicate = !types_.emplace(current, MessageType{current, {}, std::nullopt}).second;
      continue;
    }
    const std::string where = "line " + std::to_string(number) + " of " + datatype + "'s definition";
    auto field = fieldLine(line, where);
    if (!field || duplicate) continue;
    const std::string package = current.substr(0, current.find('/') == std::string::npos ? 0 : current.find('/'));
    types_[current].fields.push_back(makeField(*field, package, where));
  }
  root_ = &types_.at(datatype);
  resolve();
}

void MessageSchema::resolve() {
  std::map<const MessageType*, bool> done;
  for (auto& [name, type] : types_) sizeType(type, done, 0);
}

void MessageSchema::sizeType(MessageType& t, std::map<const MessageType*, bool>& done, int depth) {
  if (auto it = done.find(&t); it != done.end()) {
    if (!it->second) throw std::invalid_argument("type " + t.name + " contains itself");
    return;
  }
  if (depth > kMaxDepth) throw std::invalid_argument("type " + t.name + " is nested over " + std::to_string(kMaxDepth) + " deep");
  done[&t] = false;
  std::optional<std::uint64_t> total = 0;
  for (MessageField& f : t.fields) {
    if (f.kind == Kind::Message) {
      auto it = types_.find(f.type);
      if (it == types_.end())
        throw std::invalid_argument(root_->name + "'s definition has no section for " + f.type + " (field '" + f.name + "' of " +
                                    t.name + ")");
      sizeType(it->second, done, depth + 1);
      f.message = &it->second;
      f.element_size = it->second.size;
    }
    if (f.array == Array::None) f.size = f.element_size;
    if (f.array == Array::Fixed && f.element_size) f.size = product(f.length, *f.element_size, t.name + "." + f.name);
    total = total && f.size ? std::optional<std::uint64_t>(*total + *f.size) : std::nullopt;
    if (total && *total > kMaxSize) throw std::invalid_argument("type " + t.name + " is too large (over 2^40 bytes)");
  }
  t.size = total;
  done[&t] = true;
}

void MessageSchema::check(const std::uint8_t* data, std::size_t size) const {
  ByteCursor c(data, size);
  try {
    skipMessage(c, *root_);
  } catch (const TruncatedMessage& e) {
    throw std::invalid_argument("a " + root_->name + " message of " + std::to_string(size) + " bytes is truncated (" + e.what() +
                                ")");
  }
}

FieldReader::FieldReader(std::shared_ptr<const MessageSchema> schema, const std::string& path)
    : schema_(std::move(schema)), path_(path) {
  const MessageType* in = &schema_->root();
  std::istringstream parts(path);
  for (std::string component; std::getline(parts, component, '.');) {
    if (in) {
      addStep(*in, component);
      in = leaf().message;
    } else if (!addTimePart(component)) {
      const std::string last = steps_.back().path + (time_part_ == 0 ? "" : time_part_ == 1 ? ".secs" : ".nsecs");
      throw std::invalid_argument("'" + last + "' is a " + (time_part_ ? "number" : leaf().type) + ": it has no field '" +
                                  component + "'");
    }
  }
  if (steps_.empty() || path.back() == '.')
    throw std::invalid_argument("'" + path + "' is not a field path (e.g. pose.position.x)");
  if (leaf().kind == Kind::Message)
    throw std::invalid_argument("'" + path + "' is a " + leaf().type + ", not a number: name one of its fields (" +
                                leaf().message->fieldNames() + ")");
  if (leaf().kind == Kind::String) throw std::invalid_argument("'" + path + "' is a string, not a number");
}

const MessageField& FieldReader::leaf() const { return steps_.back().in->fields[steps_.back().field]; }

bool FieldReader::addTimePart(const std::string& component) {
  if (time_part_ != 0 || (leaf().kind != Kind::Time && leaf().kind != Kind::Duration)) return false;
  if (component != "secs" && component != "nsecs") return false;
  time_part_ = component == "secs" ? 1 : 2;
  return true;
}

void FieldReader::addStep(const MessageType& in, const std::string& component) {
  const std::string before = steps_.empty() ? "" : steps_.back().path + ".";
  Step step{&in, 0, false, 0, before + component};
  std::string name = component;
  if (const auto open = component.find('['); open != std::string::npos) {
    const auto index = count(component.substr(open + 1, component.size() - open - 2));
    if (component.back() != ']' || !index) throw std::invalid_argument("'" + step.path + "' has no valid index (e.g. ranges[3])");
    step.indexed = true, step.index = *index;
    name.erase(open);
  }
  const MessageField* f = in.find(name);
  if (!f) {
    const std::string level = steps_.empty() ? in.name : steps_.back().path.substr(steps_.back().path.rfind('.') + 1);
    throw std::invalid_argument(schema_->root().name + " has no field '" + path_ + "' (" + level + " has: " + in.fieldNames() +
                                ")");
  }
  if (step.indexed && f->array == Array::None)
    throw std::invalid_argument("'" + before + name + "' is a " + f->type + ", not an array");
  if (step.indexed && f->array == Array::Fixed && step.index >= f->length)
    throw std::invalid_argument("'" + step.path + "' is out of range: " + name + " has " + std::to_string(f->length) +
                                " elements");
  if (!step.indexed && f->array != Array::None)
    throw std::invalid_argument("'" + step.path + "' is an array (" + f->typeText() + "): give an index, e.g. " + step.path +
                                "[0]");
  step.field = static_cast<std::size_t>(f - in.fields.data());
  steps_.push_back(std::move(step));
}

double FieldReader::read(const std::uint8_t* data, std::size_t size) const {
  ByteCursor c(data, size);
  try {
    for (const Step& s : steps_) {
      for (std::size_t k = 0; k < s.field; ++k) skipField(c, s.in->fields[k]);
      const MessageField& f = s.in->fields[s.field];
      if (!s.indexed) continue;
      const std::uint32_t count = f.array == Array::Fixed ? f.length : c.next<std::uint32_t>();
      if (s.index >= count)
        throw std::invalid_argument("'" + s.path + "' is out of range: this message's " + f.name + " has " +
                                    std::to_string(count) + (count == 1 ? " element" : " elements"));
      skipElements(c, f, s.index);
    }
    if (time_part_ == 0) return readNumber(c, leaf().kind);
    if (time_part_ == 2) c.take(4);  // after secs
    return readNumber(c, leaf().kind == Kind::Duration ? Kind::Int32 : Kind::UInt32);
  } catch (const TruncatedMessage& e) {
    throw std::invalid_argument("a " + schema_->root().name + " message of " + std::to_string(size) +
                                " bytes is truncated before '" + path_ + "' (" + e.what() + ")");
  }
}

bool startsWithHeader(const std::string& definition) {
  std::istringstream in(definition);
  for (std::string raw; std::getline(in, raw);) {
    const std::string line = trim(raw);
    if (line.rfind("MSG:", 0) == 0 || (!line.empty() && line.find_first_not_of('=') == std::string::npos)) return false;
    try {
      if (auto f = fieldLine(line, "")) return f->name == "header" && (f->type == "Header" || f->type == "std_msgs/Header");
    } catch (const std::invalid_argument&) {
      return false;
    }
  }
  return false;
}

}  // namespace apex_nodes
