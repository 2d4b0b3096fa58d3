// Parameters: every kind parses YAML text, round-trips through toText, and
// refuses bad values with a message naming the parameter and the reason.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex/core/param.hpp"
#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

namespace {

using namespace apex;
using apex_test::add;
using apex_test::buildFromText;
using apex_test::object;
using apex_test::testRegistry;

// Asserts that `text` contains every one of `parts` (case-sensitive).
::testing::AssertionResult Contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const auto& p : parts)
    if (text.find(p) == std::string::npos)
      return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << p << "'";
  return ::testing::AssertionSuccess();
}

// Parses `text` and expects success; returns the value.
ParamValue parseOk(const ParamSpec& spec, const std::string& text) {
  auto r = spec.parse(text);
  EXPECT_TRUE(r) << spec.name << " <- '" << text << "': " << r.message();
  return r ? r.value() : ParamValue{};
}

// Parses `text` and expects a refusal; returns the message.
std::string parseFails(const ParamSpec& spec, const std::string& text) {
  auto r = spec.parse(text);
  EXPECT_FALSE(r) << spec.name << " <- '" << text << "' was accepted as " << (r ? toText(r.value()) : "");
  return r.message();
}

// value → text → value gives the same value, and the text is stable.
void expectRoundTrip(const ParamSpec& spec, const ParamValue& v) {
  const std::string text = toText(v);
  auto back = spec.parse(text);
  ASSERT_TRUE(back) << spec.name << ": toText gave '" << text << "' which does not parse back: " << back.message();
  EXPECT_EQ(back.value(), v) << spec.name << ": '" << text << "' came back as '" << toText(back.value()) << "'";
  EXPECT_EQ(toText(back.value()), text);
}

// ---------------------------------------------------------------- valid values

TEST(ParamParse, BoolAcceptsTrueAndFalse) {
  const auto spec = param::boolean("flag", false);
  EXPECT_EQ(parseOk(spec, "true"), ParamValue(true));
  EXPECT_EQ(parseOk(spec, "false"), ParamValue(false));
  EXPECT_EQ(toText(ParamValue(true)), "true");
  expectRoundTrip(spec, false);
}

TEST(ParamParse, IntAndDouble) {
  const auto i = param::integer("count", 0);
  EXPECT_EQ(parseOk(i, "12"), ParamValue(12));
  EXPECT_EQ(parseOk(i, "-7"), ParamValue(-7));
  EXPECT_EQ(toText(ParamValue(12)), "12");
  expectRoundTrip(i, -7);

  const auto d = param::real("alpha", 1.0);
  EXPECT_EQ(parseOk(d, "0.5"), ParamValue(0.5));
  EXPECT_EQ(parseOk(d, "2"), ParamValue(2.0));  // an integer literal is a fine double
  EXPECT_EQ(toText(ParamValue(0.5)), "0.5");
  EXPECT_EQ(toText(ParamValue(2.0)), "2.0");  // stays recognisable as a double
  for (double v : {0.5, 2.0, -1e-9, 1e20, 0.1, 1.0 / 3.0}) expectRoundTrip(d, v);
}

TEST(ParamParse, StringAndPath) {
  const auto s = param::text("label", "x");
  EXPECT_EQ(parseOk(s, "mean"), ParamValue(std::string("mean")));
  EXPECT_EQ(parseOk(s, "'hello world'"), ParamValue(std::string("hello world")));
  EXPECT_EQ(toText(ParamValue(std::string("mean"))), "mean");
  for (std::string v : {"hello", "hello world", "a: b", "x, y", "[not a list]", "#hash", "12", "true", "", "~", "null", "it's"})
    expectRoundTrip(s, v);
  // what yaml-cpp's emitter leaves plain but reads as something else: a document's start or end,
  // a sequence; a "\r" alone is text to it (found by fuzz_param_text)
  for (std::string v : {"---", "...", "--- a", "- - x", "? a", "-\r?\r-"}) expectRoundTrip(s, v);
  // no text is the empty string (a cleared field, `value: ''` over rosservice), not null
  EXPECT_EQ(parseOk(s, ""), ParamValue(std::string()));
  for (std::string v : {" ", "\r", "\n", " \t"}) expectRoundTrip(s, v);  // blanks stay what they are
  EXPECT_EQ(parseOk(param::path("file", "", PathMode::Write), ""), ParamValue(std::string()));

  const auto p = param::path("file", "/tmp/in.png", PathMode::Write);
  EXPECT_EQ(parseOk(p, "/data/out image.png"), ParamValue(std::string("/data/out image.png")));
  expectRoundTrip(p, std::string("/data/a b/c.png"));
  EXPECT_EQ(p.kindName(), "path");
}

TEST(ParamParse, IntRangeWithStep) {
  const auto spec = param::range("block_size", 3, 99, 2, 11);
  EXPECT_EQ(parseOk(spec, "3"), ParamValue(3));
  EXPECT_EQ(parseOk(spec, "13"), ParamValue(13));
  EXPECT_EQ(parseOk(spec, "99"), ParamValue(99));
  expectRoundTrip(spec, 51);
  EXPECT_EQ(spec.kindName(), "int range");
}

TEST(ParamParse, DoubleRangeAndAngle) {
  const auto r = param::range("sigma", 0.0, 10.0, 0.5, 1.0);
  EXPECT_EQ(parseOk(r, "2.5"), ParamValue(2.5));
  EXPECT_EQ(parseOk(r, "10"), ParamValue(10.0));
  expectRoundTrip(r, 0.0);

  const auto a = param::angle("theta", 0.0);
  EXPECT_EQ(parseOk(a, "1.5"), ParamValue(1.5));
  EXPECT_EQ(parseOk(a, "-3.14"), ParamValue(-3.14));
  expectRoundTrip(a, 0.25);
}

TEST(ParamParse, IntervalAsListOrMap) {
  const auto spec = param::interval("band", 0, 255, 10, 200);
  EXPECT_EQ(parseOk(spec, "[20, 100]"), ParamValue(Interval{20, 100}));
  EXPECT_EQ(parseOk(spec, "{low: 1.5, high: 2}"), ParamValue(Interval{1.5, 2}));
  EXPECT_EQ(parseOk(spec, "[5, 5]"), ParamValue(Interval{5, 5}));  // an empty interval is fine
  EXPECT_EQ(toText(ParamValue(Interval{20, 100})), "[20.0, 100.0]");
  expectRoundTrip(spec, Interval{0.5, 254.5});
}

TEST(ParamParse, SetOfOptions) {
  const auto spec = param::options("method", {"mean", "median", "gaussian"}, "mean");
  EXPECT_EQ(parseOk(spec, "median"), ParamValue(std::string("median")));
  EXPECT_EQ(toText(ParamValue(std::string("gaussian"))), "gaussian");
  expectRoundTrip(spec, std::string("mean"));
  EXPECT_EQ(spec.kindName(), "set");
}

TEST(ParamParse, ColorAsMapOrList) {
  const auto spec = param::color("tint", 0, 0, 0);
  EXPECT_EQ(parseOk(spec, "{r: 1, g: 2, b: 3}"), ParamValue(Color{1, 2, 3}));
  EXPECT_EQ(parseOk(spec, "[255, 0, 128]"), ParamValue(Color{255, 0, 128}));
  EXPECT_EQ(toText(ParamValue(Color{1, 2, 3})), "[1, 2, 3]");
  expectRoundTrip(spec, Color{0, 255, 7});
}

TEST(ParamParse, PairAsListOrMap) {
  const auto spec = param::pair("size", 1, 2);
  EXPECT_EQ(parseOk(spec, "[1, 2]"), ParamValue(Pair{1, 2}));
  EXPECT_EQ(parseOk(spec, "{first: 3, second: 4.5}"), ParamValue(Pair{3, 4.5}));
  EXPECT_EQ(toText(ParamValue(Pair{3, 4.5})), "[3.0, 4.5]");
  expectRoundTrip(spec, Pair{-1, 0.125});
}

TEST(ParamParse, ListOfNumbers) {
  const auto spec = param::list("weights", {1, 2});
  EXPECT_EQ(parseOk(spec, "[1, 2.5, -3]"), ParamValue(std::vector<double>{1, 2.5, -3}));
  EXPECT_EQ(parseOk(spec, "[]"), ParamValue(std::vector<double>{}));
  EXPECT_EQ(toText(ParamValue(std::vector<double>{1, 2.5})), "[1.0, 2.5]");
  EXPECT_EQ(toText(ParamValue(std::vector<double>{})), "[]");
  expectRoundTrip(spec, std::vector<double>{0.1, 2, 3e-5});
  expectRoundTrip(spec, std::vector<double>{});
}

TEST(ParamParse, ListOfStrings) {
  const auto spec = param::textList("topics", {"/camera/image_raw"});
  EXPECT_EQ(parseOk(spec, "[/a, /b/c]"), ParamValue(std::vector<std::string>{"/a", "/b/c"}));
  EXPECT_EQ(parseOk(spec, "[]"), ParamValue(std::vector<std::string>{}));
  EXPECT_EQ(toText(ParamValue(std::vector<std::string>{"/a", "/b"})), "[/a, /b]");
  expectRoundTrip(spec, std::vector<std::string>{"a, b", "[x]", "true", "3", ""});
  EXPECT_TRUE(Contains(parseFails(spec, "/a"), {"'topics'", "a list of strings"}));
  EXPECT_TRUE(Contains(parseFails(spec, "[[a]]"), {"'topics'", "a list of strings"}));
}

TEST(ParamParse, EveryDefaultIsValidAndRoundTrips) {
  const std::vector<ParamSpec> specs = {param::boolean("b", true),
                                        param::integer("i", 4),
                                        param::real("d", 0.5),
                                        param::text("s", "hi there"),
                                        param::range("ir", 1, 9, 2, 5),
                                        param::range("dr", 0.0, 1.0, 0.1, 0.3),
                                        param::interval("iv", 0, 10, 2, 3),
                                        param::options("o", {"a", "b"}, "b"),
                                        param::angle("an", 0.5),
                                        param::path("p", "/tmp/x"),
                                        param::color("c", 1, 2, 3),
                                        param::pair("pr", 1, 2),
                                        param::list("l", {1, 2, 3}),
                                        param::textList("tl", {"a", "b c"})};
  for (const auto& s : specs) {
    SCOPED_TRACE(s.name + " (" + s.kindName() + ")");
    EXPECT_TRUE(s.validate(s.default_value)) << s.validate(s.default_value).message();
    expectRoundTrip(s, s.default_value);
    EXPECT_EQ(toMessage(s.default_value).type(), s.portType());
  }
}

// ---------------------------------------------------------------- refused values

TEST(ParamRefuse, OutOfRangeNamesTheBounds) {
  const auto spec = param::range("block_size", 3, 99, 2, 11);
  EXPECT_TRUE(Contains(parseFails(spec, "101"), {"'block_size'", "101", "out of range", "[3, 99]"}));
  EXPECT_TRUE(Contains(parseFails(spec, "1"), {"'block_size'", "out of range", "[3, 99]"}));

  const auto d = param::range("sigma", 0.0, 10.0, 0.5, 1.0);
  EXPECT_TRUE(Contains(parseFails(d, "10.5"), {"'sigma'", "out of range", "[0, 10]"}));
  EXPECT_TRUE(Contains(parseFails(d, "-0.1"), {"'sigma'", "out of range"}));

  const auto a = param::angle("theta", 0.0, -1.0, 1.0);
  EXPECT_TRUE(Contains(parseFails(a, "1.5"), {"'theta'", "out of range", "[-1, 1]"}));
}

TEST(ParamRefuse, IntRangeOffTheStepListsAllowedValues) {
  const auto spec = param::range("block_size", 3, 99, 2, 11);
  EXPECT_TRUE(Contains(parseFails(spec, "12"), {"'block_size'", "12", "not on the step", "3, 5, ...", "99"}));
  const auto neg = param::range("offset", -9, 9, 3, 0);
  EXPECT_TRUE(neg.parse("-6"));
  EXPECT_TRUE(neg.parse("9"));
  EXPECT_TRUE(Contains(parseFails(neg, "-5"), {"'offset'", "not on the step"}));
}

TEST(ParamRefuse, NotInTheSetListsTheOptions) {
  const auto spec = param::options("method", {"mean", "median", "gaussian"}, "mean");
  EXPECT_TRUE(Contains(parseFails(spec, "max"), {"'method'", "'max'", "not one of", "mean, median, gaussian"}));
  EXPECT_TRUE(Contains(parseFails(spec, "Mean"), {"not one of"}));  // case matters
  EXPECT_FALSE(spec.parse("[mean]"));
}

TEST(ParamRefuse, WrongTypeSaysWhatIsExpected) {
  EXPECT_TRUE(Contains(parseFails(param::integer("count", 0), "abc"), {"'count'", "int", "an integer", "abc"}));
  EXPECT_TRUE(Contains(parseFails(param::integer("count", 0), "1.5"), {"'count'", "an integer"}));
  EXPECT_TRUE(Contains(parseFails(param::range("gain", -100, 100, 1, 1), "abc"), {"'gain'", "an integer"}));
  EXPECT_TRUE(Contains(parseFails(param::real("alpha", 0), "abc"), {"'alpha'", "a number"}));
  EXPECT_TRUE(Contains(parseFails(param::real("alpha", 0), "[1]"), {"'alpha'", "a number"}));
  EXPECT_TRUE(Contains(parseFails(param::boolean("flag", false), "maybe"), {"'flag'", "true or false"}));
  EXPECT_TRUE(Contains(parseFails(param::text("label", ""), "{a: 1}"), {"'label'", "a string"}));
  EXPECT_TRUE(Contains(parseFails(param::pair("size", 0, 0), "[1, 2, 3]"), {"'size'", "two numbers"}));
  EXPECT_TRUE(Contains(parseFails(param::list("weights", {}), "[1, x]"), {"'weights'", "a list of numbers"}));
  EXPECT_TRUE(Contains(parseFails(param::list("weights", {}), "3"), {"'weights'", "a list of numbers"}));
  EXPECT_TRUE(Contains(parseFails(param::color("tint", 0, 0, 0), "[1, 2]"), {"'tint'", "a colour"}));
}

TEST(ParamRefuse, MapMissingAKeyIsRefusedNotThrown) {
  // A map form with a key left out must be a refusal, never a yaml-cpp exception.
  std::string msg;
  EXPECT_NO_THROW(msg = parseFails(param::pair("size", 0, 0), "{first: 1}"));
  EXPECT_TRUE(Contains(msg, {"'size'", "two numbers"}));
  EXPECT_NO_THROW(msg = parseFails(param::interval("band", 0, 10, 0, 1), "{low: 1}"));
  EXPECT_TRUE(Contains(msg, {"'band'", "two numbers"}));
  EXPECT_NO_THROW(msg = parseFails(param::color("tint", 0, 0, 0), "{r: 1, g: 2}"));
  EXPECT_TRUE(Contains(msg, {"'tint'", "a colour"}));
  EXPECT_NO_THROW(msg = parseFails(param::pair("size", 0, 0), "{x: 1, y: 2}"));
  EXPECT_TRUE(Contains(msg, {"'size'", "two numbers"}));
}

TEST(ParamRefuse, NonFiniteDoubles) {
  EXPECT_TRUE(Contains(parseFails(param::real("alpha", 0), ".nan"), {"'alpha'", "finite"}));
  EXPECT_TRUE(Contains(parseFails(param::range("sigma", 0.0, 1.0, 0.0, 0.0), ".inf"), {"'sigma'"}));
  // Found by fuzz_param_text: a list or pair took NaN, printed it as "nan", and read that back as text.
  EXPECT_TRUE(
      Contains(parseFails(param::list("weights", {1}), "[2, .NAN, 23]"), {"'weights'", "element 2", "not a finite number"}));
  EXPECT_TRUE(Contains(parseFails(param::pair("size", 1, 2), "[1, -.inf]"), {"'size'", "element 2"}));
  EXPECT_TRUE(Contains(parseFails(param::interval("band", 0, 255, 10, 200), "[19, .NaN]"), {"'band'", "element 2"}));
}

TEST(ParamRefuse, TextThatYamlCannotGiveBackIsRefused) {
  // Found by fuzz_param_text: a NUL came back from YAML as other bytes, printed as another string.
  EXPECT_TRUE(
      Contains(parseFails(param::text("label", "x"), std::string("\x01\0\0.", 4)), {"'label'", "a control character at byte 1"}));
  EXPECT_TRUE(Contains(parseFails(param::text("label", "x"), "\"a\\x00b\""), {"a control character at byte 2"}));
  EXPECT_TRUE(Contains(parseFails(param::path("file", ""), "\xff.bag"), {"'file'", "not UTF-8 at byte 1"}));
  EXPECT_TRUE(Contains(parseFails(param::textList("topics", {}), "[ok, \"\\x07\"]"), {"'topics'", "control character"}));
  EXPECT_TRUE(param::text("label", "x").parse("\"caf\u00e9\tbar\"").isOk());  // UTF-8 and tabs are fine
}

TEST(ParamRefuse, IntervalLowAboveHighOrOutsideBounds) {
  const auto spec = param::interval("band", 0, 255, 10, 200);
  EXPECT_TRUE(Contains(parseFails(spec, "[100, 20]"), {"'band'", "low 100", "above high 20"}));
  EXPECT_TRUE(Contains(parseFails(spec, "[-5, 10]"), {"'band'", "out of range", "[0, 255]"}));
  EXPECT_TRUE(Contains(parseFails(spec, "{low: 0, high: 300}"), {"'band'", "out of range"}));
  EXPECT_TRUE(Contains(parseFails(spec, "[1]"), {"'band'", "two numbers"}));
}

TEST(ParamRefuse, ColourChannelOutside0To255) {
  const auto spec = param::color("tint", 0, 0, 0);
  EXPECT_TRUE(Contains(parseFails(spec, "{r: 300, g: 0, b: 0}"), {"'tint'", "300", "0..255"}));
  EXPECT_TRUE(Contains(parseFails(spec, "[0, -1, 0]"), {"'tint'", "-1", "0..255"}));
}

TEST(ParamRefuse, InvalidYaml) {
  EXPECT_TRUE(Contains(parseFails(param::list("weights", {}), "[1, 2"), {"'weights'", "not valid YAML"}));
  EXPECT_TRUE(Contains(parseFails(param::color("tint", 0, 0, 0), "{r: 1, g: 2"), {"'tint'", "not valid YAML"}));
}

TEST(ParamRefuse, ValidateRefusesAValueOfAnotherType) {
  const auto spec = param::range("gain", -100, 100, 1, 1);
  EXPECT_TRUE(Contains(spec.validate(std::string("x")).message(), {"'gain'", "int range", "cannot hold"}));
  EXPECT_FALSE(param::color("tint", 0, 0, 0).validate(Pair{1, 2}));
  EXPECT_FALSE(param::list("l", {}).validate(3.0));
}

// ---------------------------------------------------------------- port messages

TEST(ParamMessage, IntMessageIntoDoubleParameterIsAccepted) {
  const auto spec = param::range("sigma", 0.0, 10.0, 0.0, 1.0);
  auto v = fromMessage(spec, Message::make<int>(3));
  ASSERT_TRUE(v) << v.message();
  EXPECT_EQ(v.value(), ParamValue(3.0));
  auto angle = fromMessage(param::angle("theta", 0), Message::make<int>(1));
  ASSERT_TRUE(angle) << angle.message();
  EXPECT_EQ(angle.value(), ParamValue(1.0));
}

TEST(ParamMessage, WrongTypesAndBadValuesAreRefused) {
  const auto gain = param::range("gain", -100, 100, 1, 1);
  auto s = fromMessage(gain, Message::make<std::string>("abc"));
  ASSERT_FALSE(s);
  EXPECT_TRUE(Contains(s.message(), {"'gain'"}));
  auto far = fromMessage(gain, Message::make<int>(1000));
  ASSERT_FALSE(far);
  EXPECT_TRUE(Contains(far.message(), {"'gain'", "out of range", "[-100, 100]"}));
  auto odd = fromMessage(gain, Message::make<float>(1.0f));
  ASSERT_FALSE(odd);
  EXPECT_TRUE(Contains(odd.message(), {"'gain'", "cannot take a message of type"}));
  auto nothing = fromMessage(gain, Message::nothing());
  ASSERT_FALSE(nothing);
  EXPECT_TRUE(Contains(nothing.message(), {"'gain'", "Nothing"}));
  EXPECT_FALSE(fromMessage(param::options("m", {"a", "b"}, "a"), Message::make<std::string>("c")));
}

TEST(ParamMessage, ToMessageThenFromMessageRoundTrips) {
  const std::vector<std::pair<ParamSpec, ParamValue>> cases = {{param::boolean("b", false), true},
                                                               {param::range("ir", 0, 10, 1, 0), 7},
                                                               {param::real("d", 0), 2.5},
                                                               {param::options("o", {"a", "b"}, "a"), std::string("b")},
                                                               {param::interval("iv", 0, 10, 0, 1), Interval{2, 3}},
                                                               {param::color("c", 0, 0, 0), Color{9, 8, 7}},
                                                               {param::pair("p", 0, 0), Pair{1, -1}},
                                                               {param::list("l", {}), std::vector<double>{4, 5}}};
  for (const auto& [spec, value] : cases) {
    SCOPED_TRACE(spec.name);
    const Message m = toMessage(value);
    EXPECT_EQ(m.type(), spec.portType());
    auto back = fromMessage(spec, m);
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back.value(), value);
  }
}

// ---------------------------------------------------------------- Graph::setParameter

std::string gainText(const Graph& g, const std::string& node) {
  for (const auto& n : g.describe().nodes)
    if (n.name == node)
      for (const auto& [name, text] : n.parameters)
        if (name == "gain") return text;
  ADD_FAILURE() << "no gain parameter on " << node;
  return {};
}

TEST(GraphSetParameter, ReturnsTheAppliedValueText) {
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  EXPECT_EQ(gainText(g, "amp"), "1");  // the default
  auto r = g.setParameter("amp", "gain", "5");
  ASSERT_TRUE(r) << r.message();
  EXPECT_EQ(r.value(), "5");
  EXPECT_EQ(gainText(g, "amp"), "5");
  auto spaced = g.setParameter("amp", "gain", "  -12  ");
  ASSERT_TRUE(spaced) << spaced.message();
  EXPECT_EQ(spaced.value(), "-12");  // canonical text, not what was typed
  EXPECT_EQ(gainText(g, "amp"), "-12");
}

TEST(GraphSetParameter, BadValueIsRefusedAndTheOldValueStays) {
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  ASSERT_TRUE(g.setParameter("amp", "gain", "5"));

  auto far = g.setParameter("amp", "gain", "500");
  ASSERT_FALSE(far);
  EXPECT_TRUE(Contains(far.message(), {"'amp'", "'gain'", "500", "range", "[-100, 100]"}));
  EXPECT_EQ(gainText(g, "amp"), "5");

  auto word = g.setParameter("amp", "gain", "abc");
  ASSERT_FALSE(word);
  EXPECT_TRUE(Contains(word.message(), {"'amp'", "'gain'", "an integer"}));
  EXPECT_EQ(gainText(g, "amp"), "5");

  auto broken = g.setParameter("amp", "gain", "[1,");
  ASSERT_FALSE(broken);
  EXPECT_TRUE(Contains(broken.message(), {"'amp'", "'gain'", "YAML"}));
  EXPECT_EQ(gainText(g, "amp"), "5");
}

TEST(GraphSetParameter, UnknownNodeOrParameterIsNamed) {
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  auto p = g.setParameter("amp", "gian", "2");
  ASSERT_FALSE(p);
  EXPECT_TRUE(Contains(p.message(), {"'amp'", "test/Gain", "no parameter 'gian'", "parameters: gain"}));
  auto n = g.setParameter("nope", "gain", "2");
  ASSERT_FALSE(n);
  EXPECT_TRUE(Contains(n.message(), {"no node named 'nope'"}));
  EXPECT_EQ(gainText(g, "amp"), "1");
}

TEST(GraphSetParameter, NewValueIsUsedByTheNextFiring) {
  Graph g(testRegistry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: feed, type: test/Feeder}
      - {name: amp, type: test/Gain, parameters: {gain: 3}}
      - {name: sink, type: test/Collector}
    connections: [{from: feed/out, to: amp/in}, {from: amp/out, to: sink/in}])"));
  g.start();
  auto* feed = object<apex_test::Feeder>(g, "feed");
  auto* sink = object<apex_test::Collector>(g, "sink");
  feed->feed(2);
  ASSERT_TRUE(sink->waitFor(1));
  ASSERT_TRUE(g.waitIdle(apex_test::kWait));
  ASSERT_FALSE(g.setParameter("amp", "gain", "101"));  // refused: no effect on firing
  ASSERT_TRUE(g.setParameter("amp", "gain", "-4"));
  feed->feed(5);
  ASSERT_TRUE(sink->waitFor(2));
  g.stop();
  EXPECT_EQ(sink->ints(), (std::vector<int>{6, -20}));
}

}  // namespace
