// NodeletHost's mirror of a nodelet's dynamic_reconfigure parameters, without a nodelet: the
// entries made from a description as servers publish it (image_proc's interpolation enum, pcl_ros'
// unbounded doubles), the parameters they make, and values both ways.
#include <gtest/gtest.h>

#include <limits>

#include "../../apex_nodes/ros_io/nodelet_reconfigure.hpp"

namespace {

using namespace apex_nodes::nodelet_host;
using dynamic_reconfigure::ConfigDescription;
using dynamic_reconfigure::ParamDescription;

// As dynamic_reconfigure's generator writes an enum's edit_method: a Python dict's text.
const char* kInterpolation =
    "{'enum': [{'name': 'NN', 'type': 'int', 'value': 0, 'srcline': 8, 'srcfile': '/cfg/Rectify.cfg', "
    "'description': 'Nearest neighbor', 'ctype': 'int', 'cconsttype': 'const int'}, "
    "{'name': 'Linear', 'type': 'int', 'value': 1, 'srcline': 9, 'srcfile': '/cfg/Rectify.cfg', "
    "'description': 'Linear', 'ctype': 'int', 'cconsttype': 'const int'}, "
    "{'name': 'Cubic', 'type': 'int', 'value': 2, 'srcline': 10, 'srcfile': '/cfg/Rectify.cfg', "
    "'description': 'Cubic', 'ctype': 'int', 'cconsttype': 'const int'}, "
    "{'name': 'Lanczos4', 'type': 'int', 'value': 4, 'srcline': 12, 'srcfile': '/cfg/Rectify.cfg', "
    "'description': 'Lanczos4', 'ctype': 'int', 'cconsttype': 'const int'}], 'enum_description': 'Interpolation'}";

/** A description with one parameter, its default and bounds. */
struct Description {
  ConfigDescription all;
  ParamDescription param;
  Description(const std::string& name, const std::string& type, const std::string& edit_method = "") {
    param.name = name;
    param.type = type;
    param.description = "what " + name + " does";
    param.edit_method = edit_method;
  }
  Description& ints(int dflt, int min, int max) {
    add(all.dflt.ints, dflt), add(all.min.ints, min), add(all.max.ints, max);
    return *this;
  }
  Description& doubles(double dflt, double min, double max) {
    add(all.dflt.doubles, dflt), add(all.min.doubles, min), add(all.max.doubles, max);
    return *this;
  }
  template <class List, class V>
  void add(List& list, V v) {
    list.emplace_back();
    list.back().name = param.name;
    list.back().value = v;
  }
  std::string entry() const { return entryOf(param, all); }
};

/** The parameter `entry` makes, and what it was parsed as. */
std::pair<apex::ParamSpec, Offered> made(const std::string& entry) {
  apex::Manifest m;
  auto st = addOffered({entry}, m);
  EXPECT_TRUE(st) << st.message();
  auto parsed = parseOffered({entry});
  EXPECT_TRUE(parsed) << parsed.message();
  if (!st || !parsed || m.params.size() != 1) return {};
  return {m.params.front(), parsed->front()};
}

TEST(NodeletReconfigure, AnEnumIsAChoiceOfItsNamesAndGoesToTheNodeletAsItsValue) {
  const auto [spec, offered] = made(Description("interpolation", "int", kInterpolation).ints(1, 0, 4).entry());
  EXPECT_EQ(spec.kind, apex::ParamKind::Set);
  EXPECT_EQ(spec.options, (std::vector<std::string>{"NN", "Linear", "Cubic", "Lanczos4"}));
  EXPECT_EQ(spec.default_value, apex::ParamValue(std::string("Linear")));
  EXPECT_NE(spec.description.find("what interpolation does"), std::string::npos);
  EXPECT_EQ(valueOf(offered, "2"), apex::ParamValue(std::string("Cubic")));  // the value the nodelet has
  EXPECT_FALSE(valueOf(offered, "3"));  // none of its options: not taken
  EXPECT_EQ(static_cast<int>(toNodelet(offered, std::string("Lanczos4"))), 4);
}

TEST(NodeletReconfigure, ADoubleEnumsValueIsFoundAsANumberNotAsText) {
  const std::string method =
      "{'enum': [{'name': 'fine', 'type': 'double', 'value': 0.1}, {'name': 'coarse', 'type': 'double', 'value': 0.5}]}";
  const auto [spec, offered] = made(Description("resolution", "double", method).doubles(0.5, 0.0, 1.0).entry());
  EXPECT_EQ(spec.default_value, apex::ParamValue(std::string("coarse")));
  EXPECT_EQ(valueOf(offered, "0.10000000000000001"), apex::ParamValue(std::string("fine")));  // 0.1 as emitted
}

TEST(NodeletReconfigure, FiniteBoundsMakeARangeAndUnboundedOnesAPlainNumber) {
  const auto [leaf, o1] = made(Description("leaf_size", "double").doubles(0.01, 0.0, 1.0).entry());
  EXPECT_EQ(leaf.kind, apex::ParamKind::DoubleRange);
  EXPECT_EQ(leaf.min, 0.0);
  EXPECT_EQ(leaf.max, 1.0);
  EXPECT_FALSE(leaf.validate(5.0));  // refused here, naming it, before the nodelet sees it
  const double inf = std::numeric_limits<double>::infinity();
  const auto [limit, o2] = made(Description("filter_limit_min", "double").doubles(0.0, -inf, inf).entry());
  EXPECT_EQ(limit.kind, apex::ParamKind::Double);
  const int big = std::numeric_limits<int>::max();
  const auto [points, o3] = made(Description("min_points", "int").ints(1, -big - 1, big).entry());
  EXPECT_EQ(points.kind, apex::ParamKind::Int);
  const auto [size, o4] = made(Description("queue", "int").ints(5, 1, 100).entry());
  EXPECT_EQ(size.kind, apex::ParamKind::IntRange);
  EXPECT_EQ(valueOf(o4, "7"), apex::ParamValue(7));
  EXPECT_FALSE(valueOf(o4, "500"));  // out of its bounds: not taken
}

TEST(NodeletReconfigure, TheEntryKeepsTheDefaultSoItIsTheSameAtEveryLoad) {
  Description d("leaf_size", "double");
  d.doubles(0.01, 0.0, 1.0);
  const std::string before = d.entry();
  EXPECT_EQ(d.entry(), before);
  EXPECT_EQ(made(before).first.default_value, apex::ParamValue(0.01));
}

TEST(NodeletReconfigure, ANameTheHostUsesGetsAPrefixAndABadEntryIsRefusedNamingIt) {
  const auto [spec, offered] = made(Description("timeout", "double").doubles(1.0, 0.0, 10.0).entry());
  EXPECT_EQ(spec.name, "nodelet_timeout");
  EXPECT_EQ(offered.name, "timeout");  // as the nodelet names it
  apex::Manifest m;
  auto st = addOffered({"{name: x, type: quaternion, value: 1}"}, m);
  ASSERT_FALSE(st);
  EXPECT_NE(st.message().find("'{name: x, type: quaternion, value: 1}'"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("none of bool, int, double, str"), std::string::npos) << st.message();
  EXPECT_FALSE(addOffered({"not: [yaml"}, m));
}

}  // namespace
