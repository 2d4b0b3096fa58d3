// libFuzzer: parameter text -> value, for every parameter kind. The first byte picks the
// kind, the rest is the text a service or a graph file would give. A value that parses
// must print as text that parses to the same value.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "apex/core/param.hpp"

namespace {

std::vector<apex::ParamSpec> specs() {
  namespace p = apex::param;
  return {p::boolean("b", false),
          p::integer("i", 1),
          p::real("d", 0.5),
          p::text("s", "x"),
          p::text("f", "x").fileName(),
          p::range("ri", -10, 10, 2, 0),
          p::range("rd", 0.0, 1.0, 0.1, 0.5),
          p::interval("v", 0, 10, 2, 4, 0.5),
          p::options("o", {"a", "b", "c"}, "a"),
          p::angle("a", 0.1),
          p::path("p", "/tmp/x"),
          p::color("c", 1, 2, 3),
          p::pair("pr", 1, 2),
          p::list("l", {1, 2}),
          p::textList("t", {"x"})};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<apex::ParamSpec> kinds = specs();
  if (size == 0) return 0;
  const apex::ParamSpec& spec = kinds[data[0] % kinds.size()];
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  auto value = spec.parse(text);
  if (!value) return 0;
  const std::string printed = apex::toText(value.value());
  auto again = spec.parse(printed);
  if (!again || apex::toText(again.value()) != printed) __builtin_trap();  // what we print, we read back
  (void)apex::toMessage(value.value());
  return 0;
}
