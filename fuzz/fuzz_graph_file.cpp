// libFuzzer: graph file text -> description -> a graph (placeholders, parameters, interfaces
// per instance, connections) -> text again. Any crash, hang or sanitizer report is a bug;
// a refused file is fine.
#include <cstddef>
#include <cstdint>
#include <string>

#include "apex/core/graph_file.hpp"
#include "apex/core/registry.hpp"

namespace {

class Pass : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("passes")
        .input<int>("in")
        .output<int>("out")
        .param(apex::param::range("gain", -5, 5, 1, 1).makeInteractive())
        .param(apex::param::text("label", "x"))
        .slot("reset", &Pass::reset)
        .trigger("done");
  }
  void process() override {}
  void reset() {}
};

/** Every parameter kind, and `inputs` shaping its ports. */
class Shaped : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("every kind")
        .output<int>("out")
        .param(apex::param::range("inputs", 0, 8, 1, 2).shapesInterface())
        .param(apex::param::boolean("b", false))
        .param(apex::param::integer("i", 1))
        .param(apex::param::real("d", 0.5))
        .param(apex::param::range("r", 0.0, 1.0, 0.1, 0.5))
        .param(apex::param::interval("v", 0, 10, 2, 4))
        .param(apex::param::options("o", {"a", "b"}, "a"))
        .param(apex::param::angle("a", 0.1))
        .param(apex::param::color("c", 1, 2, 3))
        .param(apex::param::pair("p", 1, 2))
        .param(apex::param::list("l", {1, 2}))
        .param(apex::param::textList("t", {"x"}))
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          for (int i = 0; i < p.get<int>("inputs"); ++i) m.optionalInput<int>("in_" + std::to_string(i));
          return apex::Status::ok();
        });
  }
  void process() override {}
};

apex::NodeRegistry registry() {
  apex::NodeRegistry r;
  (void)r.add<Pass>("fuzz/Pass");
  (void)r.add<Shaped>("fuzz/Shaped");
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const apex::NodeRegistry types = registry();
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)apex::parseParameterMap(text);
  auto parsed = apex::parseGraphText(text);
  if (!parsed) return 0;
  apex::Graph graph(types);  // not started: no threads
  if (!graph.load(parsed.value())) return 0;
  const std::string again = apex::formatGraphText(graph.describe());
  if (!apex::parseGraphText(again)) __builtin_trap();  // what we write, we read
  return 0;
}
