// YAML text to a yaml-cpp tree, its shape checked first by a scan that allocates nothing.
// yaml-cpp queues every token of a line behind an unresolved key before it builds the tree:
// 4 MiB of "[" cost it a gigabyte, so a text too deep or with too many values is refused before
// it is parsed.
#include <vector>

#include "yaml_load.hpp"

namespace apex {
namespace detail {
namespace {

/** One pass over the text with what decides nesting: the columns of the open block collections
 *  and the depth of flow collections; quoted and block scalars and comments skipped. Nesting that
 *  costs a character a level ("[[[", "{a: {a: ", "- - - ") is counted as the tree will have it;
 *  nesting by indentation costs the square of its depth in text and may be counted lower (the
 *  tree's check finds it). The values it counts (the separators that start one: "- ", ": ", ",",
 *  "[", "{") are at most the tree's nodes. */
class ShapeScan {
 public:
  ShapeScan(std::string_view text, const YamlShapeLimits& limits) : t_(text), limits_(limits) {}

  std::optional<YamlShapeError> run() {
    while (i_ < t_.size() && !error_) line();
    return error_;
  }

 private:
  std::string_view t_;
  YamlShapeLimits limits_;
  std::size_t i_ = 0, line_start_ = 0;
  int line_ = 0, flow_ = 0;
  std::size_t values_ = 1;
  std::vector<std::size_t> block_;  // columns of the open block collections: a few more than limits_.depth at most
  std::optional<YamlShapeError> error_;

  char at(std::size_t k) const { return k < t_.size() ? t_[k] : '\n'; }
  /** A space or a tab, or the "\r" of a "\r\n" (a line break to yaml-cpp: a "\r" alone is text). */
  bool blank(std::size_t k) const {
    const char c = at(k);
    return c == ' ' || c == '\t' || (c == '\r' && at(k + 1) == '\n');
  }
  bool lineEnds(std::size_t k) const { return at(k) == '\n' || (at(k) == '\r' && at(k + 1) == '\n'); }
  std::size_t column() const { return i_ - line_start_; }
  void fail(const std::string& what) { error_ = YamlShapeError{line_, static_cast<int>(column()), what}; }
  void deeper() {
    constexpr int kCountedAbove = 2;  // see YamlShapeLimits
    if (static_cast<int>(block_.size()) + flow_ > limits_.depth + kCountedAbove)
      fail("nested deeper than " + std::to_string(limits_.depth) + " levels");
  }
  void value() {
    if (++values_ > limits_.values) fail("more than " + std::to_string(limits_.values) + " values");
  }
  void newLine() {
    ++line_;
    line_start_ = ++i_;
  }
  void toEndOfLine() {
    while (i_ < t_.size() && t_[i_] != '\n') ++i_;
  }

  /** A line in block context (or the next line of a flow collection that spans lines). */
  void line() {
    if (flow_ > 0) return flow();
    std::size_t indent = 0;
    while (at(i_) == ' ') ++i_, ++indent;
    if (lineEnds(i_)) {
      toEndOfLine();
      return newLine();
    }
    if (at(i_) == '#') return toEndOfLine();
    while (!block_.empty() && block_.back() > indent) block_.pop_back();
    if (block_.empty() || block_.back() < indent) {
      block_.push_back(indent);
      deeper();
    }
    if (t_.compare(i_, 3, "---") == 0 && indent == 0 && (blank(i_ + 3) || lineEnds(i_ + 3))) i_ += 3;
    content();
  }

  /** The rest of a block line, from where a value may start. */
  void content() {
    bool start = true;
    while (!error_ && i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\n') return newLine();
      if (blank(i_)) {
        ++i_;
        continue;
      }
      if (c == '#' && (i_ == line_start_ || blank(i_ - 1))) return toEndOfLine();
      if (start && (c == '-' || c == '?') && (blank(i_ + 1) || lineEnds(i_ + 1))) {
        i_ += 1;  // "- - x": a collection in a collection, at the column of what follows
        while (blank(i_)) ++i_;
        if (!lineEnds(i_) && at(i_) != '#' && at(i_) != '|' && at(i_) != '>') {
          block_.push_back(column());
          deeper();
        }
        value();
        continue;
      }
      if (start && (c == '[' || c == '{')) return flow();
      if (start && (c == '\'' || c == '"')) {
        quoted(c);
        start = false;
        continue;
      }
      if (start && (c == '|' || c == '>')) return blockScalar();
      if (start && (c == '&' || c == '!')) {  // an anchor or a tag: the value follows
        while (i_ < t_.size() && !blank(i_) && t_[i_] != '\n') ++i_;
        continue;
      }
      if (c == ':' && (blank(i_ + 1) || lineEnds(i_ + 1))) {
        ++i_;
        value();
        start = true;
        continue;
      }
      start = false;
      ++i_;
    }
  }

  /** Flow collections, over as many lines as they take; back to block context at their end. */
  void flow() {
    bool start = true;  // where a quoted scalar may begin: after [ { , : or a blank, or on a new line
    while (!error_ && i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\n') return newLine();
      if (c == '#' && (i_ == line_start_ || blank(i_ - 1))) {
        toEndOfLine();
        continue;
      }
      if (c == '[' || c == '{') {
        ++flow_;
        deeper();
        value();
      } else if (c == ']' || c == '}') {
        if (flow_ > 0 && --flow_ == 0) {
          ++i_;
          return content();
        }
      } else if (c == ',') {
        value();
      } else if ((c == '\'' || c == '"') && start) {
        quoted(c);
        start = false;
        continue;
      }
      start = blank(i_) || c == '[' || c == '{' || c == ',' || c == ':';
      ++i_;
    }
  }

  /** '...' ('' inside) or "..." (\ escapes), over lines too. */
  void quoted(char quote) {
    ++i_;
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\n') {
        ++line_;
        line_start_ = i_ + 1;
      } else if (quote == '"' && c == '\\') {
        ++i_;
      } else if (c == quote) {
        if (quote == '\'' && at(i_ + 1) == '\'') {
          ++i_;
        } else {
          ++i_;
          return;
        }
      }
      ++i_;
    }
  }

  /** "|" or ">": the lines indented deeper than the innermost open collection are its text. */
  void blockScalar() {
    const std::size_t parent = block_.empty() ? 0 : block_.back();
    toEndOfLine();
    while (i_ < t_.size()) {
      newLine();
      std::size_t k = i_;
      while (at(k) == ' ') ++k;
      if (!lineEnds(k) && k - i_ <= parent) return;  // the next node
      i_ = k;
      toEndOfLine();
    }
  }
};

}  // namespace

std::optional<YamlShapeError> yamlShapeError(std::string_view text, const YamlShapeLimits& limits) {
  return ShapeScan(text, limits).run();
}

YAML::Node loadYaml(const std::string& text) {
  if (const auto e = yamlShapeError(text)) {
    YAML::Mark mark;
    mark.line = e->line;
    mark.column = e->column;
    throw YAML::ParserException(mark, e->what);
  }
  return YAML::Load(text);
}

}  // namespace detail
}  // namespace apex
