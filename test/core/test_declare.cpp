// Ports and parameters declared once (declare.hpp): the named builders make the same
// declarations as the positional ones, handles built from the constants read and write, a
// handle of another C++ type than its constant does not compile, and a library with a type that
// fails to register is refused as a whole.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "apex/core/graph.hpp"
#include "apex/core/registry.hpp"
#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

namespace {

using namespace apex;

// Everything a ParamSpec says, as text: two specs are the same declaration if these agree.
std::string spelled(const ParamSpec& s) {
  std::string out = s.name + "|" + s.kindName() + "|" + toText(s.default_value) + "|" + s.description + "|" +
                    std::to_string(s.min) + "|" + std::to_string(s.max) + "|" + std::to_string(s.step) + "|" +
                    std::to_string(int(s.path_mode)) + std::to_string(s.interactive) + std::to_string(s.file_name) +
                    std::to_string(s.shapes_interface) + std::to_string(s.every_set) + "|";
  for (const auto& o : s.options) out += o + ",";
  return out;
}

TEST(Declare, NamedBuildersMakeWhatThePositionalOnesMade) {
  EXPECT_EQ(spelled(param::integer("k").range(1, 31).step(2).init(5).describe("odd")),
            spelled(param::range("k", 1, 31, 2, 5).describe("odd")));
  EXPECT_EQ(spelled(param::number("s").range(0.0, 50.0).step(0.1)), spelled(param::range("s", 0.0, 50.0, 0.1, 0.0)));
  EXPECT_EQ(spelled(param::flag("b").init(true)), spelled(param::boolean("b", true)));
  EXPECT_EQ(spelled(param::integer("i").init(7)), spelled(param::integer("i", 7)));
  EXPECT_EQ(spelled(param::number("r").init(0.5)), spelled(param::real("r", 0.5)));
  EXPECT_EQ(spelled(param::text("t").init("x").fileName()), spelled(param::text("t", "x").fileName()));
  EXPECT_EQ(spelled(param::choice("c", {"a", "b"})), spelled(param::options("c", {"a", "b"}, "a")));
  EXPECT_EQ(spelled(param::choice("c", {"a", "b"}).init("b")), spelled(param::options("c", {"a", "b"}, "b")));
  EXPECT_EQ(spelled(param::angle("a").init(0.5)), spelled(param::angle("a", 0.5)));
  EXPECT_EQ(spelled(param::angle("a").range(-6.0, 6.0).init(1.0)), spelled(param::angle("a", 1.0, -6.0, 6.0)));
  EXPECT_EQ(spelled(param::path("p").init("/x").mode(PathMode::Write)), spelled(param::path("p", "/x", PathMode::Write)));
  EXPECT_EQ(spelled(param::interval("v").range(0.0, 10.0).step(0.5).init({2, 3})),
            spelled(param::interval("v", 0, 10, 2, 3, 0.5)));
  EXPECT_EQ(spelled(param::color("c").init({1, 2, 3})), spelled(param::color("c", 1, 2, 3)));
  EXPECT_EQ(spelled(param::pair("p").init({1, 2})), spelled(param::pair("p", 1, 2)));
  EXPECT_EQ(spelled(param::list("l").init({1, 2})), spelled(param::list("l", {1, 2})));
  EXPECT_EQ(spelled(param::textList("l").init({"a"})), spelled(param::textList("l", {"a"})));
  EXPECT_EQ(spelled(param::integer("n").interactive().shapesInterface().everySet()),
            spelled(param::integer("n", 0).makeInteractive().shapesInterface().everySet()));
}

TEST(Declare, ARangeStartsAtItsMinimumUnlessInitSaysOtherwise) {
  EXPECT_EQ(toText(param::integer("k").range(3, 9).spec().default_value), "3");
  EXPECT_EQ(toText(param::integer("k").init(5).range(3, 9).spec().default_value), "5");  // init kept, in any order
  EXPECT_EQ(toText(param::interval("v").range(1.0, 2.0).spec().default_value), "[1.0, 2.0]");
  EXPECT_EQ(toText(param::angle("a").spec().default_value), "0.0");  // within its default bounds, not -pi
  // A default outside the range is the manifest's error, named, as before
  Manifest m("x");
  m.param(param::integer("k").range(3, 9).init(20));
  EXPECT_NE(m.check().message().find("'k'"), std::string::npos) << m.check().message();
}

// A node written only with constants: its manifest and its handles name the same ports.
class Gain : public Node {
 public:
  static inline const InputPort<int> kIn{"in", "the value"};
  static inline const OutputPort<int> kOut{"out"};
  static inline const ParamDecl<int> kGain = param::integer("gain").range(-10, 10).init(3);
  static inline const TriggerPort kBig{"big", "the result passed 10"};
  static Manifest manifest() { return Manifest("multiplies").input(kIn).output(kOut).param(kGain).trigger(kBig); }
  void process() override {
    const int v = *in_.get() * gain_.get();
    if (v > 10) big_.fire();
    out_.publish(v);
  }

 private:
  Input<int> in_{this, kIn};
  Output<int> out_{this, kOut};
  Param<int> gain_{this, kGain};
  Trigger big_{this, kBig};
};

TEST(Declare, ConstantsDeclareTheManifestAndTheHandles) {
  NodeRegistry registry;
  ASSERT_TRUE(registry.add<Gain>("test/Gain"));
  const Manifest& m = *registry.find("test/Gain")->manifest;
  ASSERT_NE(m.findInput("in"), nullptr);
  EXPECT_EQ(m.findInput("in")->description, "the value");
  EXPECT_EQ(m.findInput("in")->type, typeOf<int>());
  ASSERT_NE(m.findParam("gain"), nullptr);
  EXPECT_EQ(m.findParam("gain")->kindName(), "int range");
  EXPECT_NE(m.findTrigger("big"), nullptr);
}

TEST(Declare, ALibraryWithATypeThatFailedToRegisterIsRefusedNamingIt) {
  NodeRegistry types;
  ASSERT_TRUE(types.add<Gain>("test/Gain"));
  EXPECT_EQ(detail::moduleTypesOrThrow(types, {}).size(), 1u);
  try {
    detail::moduleTypesOrThrow(types, {"node type 'test/Bad': Output<int> 'value': manifest() declares no output 'value'"});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "1 of its node types failed to register, so none is loaded: node type 'test/Bad': Output<int> 'value': "
                 "manifest() declares no output 'value'");
  }
}

// A typed choice: its options listed once, as name, value and meaning.
class Kernel : public Node {
 public:
  static inline const InputPort<int> kIn{"in"};
  static inline const OutputPort<int> kOut{"out", "in times 10, plus the shape's value"};
  static inline const ChoiceDecl<int> kShape =
      param::choice<int>("shape", {{"rect", 1, "a square"}, {"cross", 2}, {"ellipse", 3, "round"}})
          .init("cross")
          .describe("the kernel's shape");
  static Manifest manifest() { return Manifest("shapes").input(kIn).output(kOut).param(kShape); }
  void process() override { out_.publish(*in_.get() * 10 + shape_.get()); }

 private:
  Input<int> in_{this, kIn};
  Output<int> out_{this, kOut};
  Choice<int> shape_{this, kShape};
};

TEST(Declare, ATypedChoiceListsItsOptionsOnceAndProcessReadsTheirValues) {
  const ParamSpec& spec = Kernel::kShape;
  EXPECT_EQ(spec.kindName(), "set");
  EXPECT_EQ(spec.options, (std::vector<std::string>{"rect", "cross", "ellipse"}));
  EXPECT_EQ(toText(spec.default_value), "cross");
  EXPECT_EQ(spec.description, "the kernel's shape (rect: a square; ellipse: round)");  // cross says nothing
  EXPECT_EQ(param::choice<int>("s", {{"a", 1, "one"}, {"b", 2, "two"}}).spec().description, "a: one; b: two");

  NodeRegistry types = apex_test::testRegistry();
  ASSERT_TRUE(types.add<Kernel>("test/Kernel"));
  Graph g(types);
  ASSERT_TRUE(apex_test::buildFromText(g, R"(
    nodes:
      - {name: feed, type: test/Feeder}
      - {name: kernel, type: test/Kernel}
      - {name: sink, type: test/Collector}
    connections: [{from: feed/out, to: kernel/in}, {from: kernel/out, to: sink/in}])"));
  g.start();
  auto* feed = apex_test::object<apex_test::Feeder>(g, "feed");
  auto* sink = apex_test::object<apex_test::Collector>(g, "sink");
  feed->feed(1);
  ASSERT_TRUE(sink->waitFor(1));
  ASSERT_TRUE(g.waitIdle(apex_test::kWait));
  ASSERT_TRUE(g.setParameter("kernel", "shape", "ellipse"));
  const auto wrong = g.setParameter("kernel", "shape", "disc");  // refused when set, never met while firing
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.message().find("'disc'"), std::string::npos) << wrong.message();
  EXPECT_NE(wrong.message().find("rect"), std::string::npos) << wrong.message();
  feed->feed(2);
  ASSERT_TRUE(sink->waitFor(2));
  g.stop();
  EXPECT_EQ(sink->ints(), (std::vector<int>{12, 23}));
}

// Compiles `body` (a node class with the handle `handle`) with the compiler this build uses;
// true if it compiles.
bool compiles(const std::string& handle, const std::string& name) {
  const std::string dir = ::testing::TempDir();
  const std::string source = dir + "/apex_declare_" + name + ".cpp";
  std::ofstream(source)
      << "#include \"apex/core/registry.hpp\"\n"
         "struct N : apex::Node {\n"
         "  static inline const apex::InputPort<int> kIn{\"in\"};\n"
         "  static inline const apex::OutputPort<int> kOut{\"out\"};\n"
         "  static inline const apex::ParamDecl<int> kGain = apex::param::integer(\"gain\");\n"
         "  static apex::Manifest manifest() { return apex::Manifest().input(kIn).output(kOut).param(kGain); }\n"
         "  void process() override {}\n  "
      << handle << ";\n};\n";
  const std::string command = std::string(APEX_TEST_CXX) + " -std=c++17 -fsyntax-only -I" + APEX_TEST_INCLUDE + " " + source +
                              " > " + source + ".log 2>&1";
  const int rc = std::system(command.c_str());
  std::remove(source.c_str());
  return rc == 0;
}

TEST(Declare, AHandleOfAnotherTypeThanItsConstantDoesNotCompile) {
  // (each right form compiles: the wrong ones fail for their type alone)
  EXPECT_TRUE(compiles("apex::Input<int> in_{this, kIn}", "input_ok"));
  EXPECT_FALSE(compiles("apex::Input<double> in_{this, kIn}", "input_wrong"));
  EXPECT_TRUE(compiles("apex::Output<int> out_{this, kOut}", "output_ok"));
  EXPECT_FALSE(compiles("apex::Output<float> out_{this, kOut}", "output_wrong"));
  EXPECT_TRUE(compiles("apex::Param<int> gain_{this, kGain}", "param_ok"));
  EXPECT_FALSE(compiles("apex::Param<double> gain_{this, kGain}", "param_wrong"));
  EXPECT_FALSE(compiles("apex::Input<int> in_{this, kOut}", "input_from_output"));
  EXPECT_FALSE(compiles("apex::Choice<int> gain_{this, kGain}", "choice_of_a_number"));
}

}  // namespace
