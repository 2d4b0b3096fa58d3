// Messages of any ROS type: fields read by path from real serialized messages (nav_msgs/Odometry,
// sensor_msgs/Imu, LaserScan, geometry_msgs/PoseArray made by ros::serialization), each equal to
// the field set; errors for bad paths, numbers that are not, truncated bytes and indices out of
// range; RosMessage's header, inspector and conversions to the typed ports; FieldExtract on a
// RosMessage and on a typed message (test_bag_reader plays and records any type). No master:
// TopicSubscriber and TopicPublisher need one (a rostest).
#include <geometry_msgs/PoseArray.h>
#include <gmock/gmock.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int64.h>

#include "../../apex_nodes/ros_io/message_fields.hpp"
#include "apex/ros/inspect.hpp"
#include "apex_nodes/ros_message.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/node_harness.hpp"
#include "apex_test/test_bags.hpp"

/** A type with no ROS message (no inspector registered). */
struct NoRosForm {};
APEX_TYPE_NAME(NoRosForm, "test/NoRosForm");

using namespace apex_test;
using apex_nodes::FieldReader;
using apex_nodes::MessageSchema;
using apex_nodes::RosMessage;
using testing::HasSubstr;

namespace {

nav_msgs::Odometry odometry(int k = 0) {
  nav_msgs::Odometry o;
  o.header.seq = 41 + k;
  o.header.stamp = frameTime(k) + ros::Duration(0, 250000000);
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.position.x = 1.5 + k, o.pose.pose.position.y = -2.25, o.pose.pose.position.z = 0.125;
  o.pose.pose.orientation.w = 0.75;
  for (int i = 0; i < 36; ++i) o.pose.covariance[i] = 0.5 * i;
  o.twist.twist.linear.x = 0.4, o.twist.twist.angular.z = -0.3;
  return o;
}

sensor_msgs::Imu imu(int k = 0) {
  sensor_msgs::Imu m;
  m.header.stamp = frameTime(k);
  m.header.frame_id = "imu";
  m.orientation.w = 1;
  m.angular_velocity.x = 0.01 * k;
  m.linear_acceleration.z = 9.81;
  m.orientation_covariance[8] = -1;
  return m;
}

double read(const RosMessage& m, const std::string& path) {
  return FieldReader(std::make_shared<const MessageSchema>(m.datatype, m.definition), path).read(m.bytes.data(), m.bytes.size());
}

template <class M>
double field(const M& message, const std::string& path) {
  return read(apex_nodes::toRosMessage(message), path);
}

/** The error reading `path` of `message` (a RosMessage or a typed one), or "" if it reads. */
template <class M>
std::string fieldError(const M& message, const std::string& path) {
  try {
    if constexpr (std::is_same_v<M, RosMessage>) read(message, path);
    else field(message, path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MessageFields, OdometryFieldsAreTheValuesSet) {
  const nav_msgs::Odometry o = odometry();
  EXPECT_EQ(field(o, "pose.pose.position.x"), 1.5);
  EXPECT_EQ(field(o, "pose.pose.position.y"), -2.25);
  EXPECT_EQ(field(o, "pose.pose.position.z"), 0.125);
  EXPECT_EQ(field(o, "pose.pose.orientation.w"), 0.75);
  EXPECT_EQ(field(o, "pose.covariance[7]"), 3.5);
  EXPECT_EQ(field(o, "pose.covariance[35]"), 17.5);
  EXPECT_EQ(field(o, "twist.twist.linear.x"), 0.4);
  EXPECT_EQ(field(o, "twist.twist.angular.z"), -0.3);  // after a string (child_frame_id) and nested messages
  EXPECT_EQ(field(o, "header.seq"), 41);
  EXPECT_DOUBLE_EQ(field(o, "header.stamp"), o.header.stamp.toSec());  // a time: seconds
  EXPECT_EQ(field(o, "header.stamp.secs"), o.header.stamp.sec);  // as rostopic echo shows it
  EXPECT_EQ(field(o, "header.stamp.nsecs"), 250000000);
}

TEST(MessageFields, ImuLaserScanAndPoseArrayFields) {
  EXPECT_EQ(field(imu(3), "linear_acceleration.z"), 9.81);
  EXPECT_EQ(field(imu(3), "angular_velocity.x"), 0.03);
  EXPECT_EQ(field(imu(3), "orientation.w"), 1);
  EXPECT_EQ(field(imu(3), "orientation_covariance[8]"), -1);

  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "laser";
  scan.angle_increment = 0.25f, scan.range_max = 30.f;
  scan.ranges = {0.5f, 1.25f, 2.f, 3.75f};
  scan.intensities = {7.f, 8.f};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(field(scan, "ranges[" + std::to_string(i) + "]"), scan.ranges[i]) << i;
  EXPECT_EQ(field(scan, "intensities[1]"), 8);  // after a variable array
  EXPECT_EQ(field(scan, "angle_increment"), 0.25);
  EXPECT_EQ(field(scan, "range_max"), 30);

  geometry_msgs::PoseArray poses;
  poses.header.frame_id = "map";
  poses.poses.resize(3);
  poses.poses[1].position.y = 42.5;
  poses.poses[2].orientation.w = -1;
  EXPECT_EQ(field(poses, "poses[1].position.y"), 42.5);
  EXPECT_EQ(field(poses, "poses[2].orientation.w"), -1);
  EXPECT_EQ(field(poses, "poses[0].position.y"), 0);
}

/** Bytes of the builtin types, little-endian as ROS serializes them. */
template <class... T>
std::vector<std::uint8_t> pack(T... values) {
  std::vector<std::uint8_t> out;
  auto one = [&out](auto v) {
    const auto at = out.size();
    out.resize(at + sizeof v);
    std::memcpy(out.data() + at, &v, sizeof v);
  };
  (one(values), ...);
  return out;
}

TEST(MessageFields, EveryBuiltinTypeConstantsCommentsAndRelativeTypes) {
  const std::string definition =
      "# a comment, then constants (no bytes)\n"
      "int8 MINUS=-1\n"
      "string GREETING=hello # not a comment = still the value\n"
      "int8 a  # trailing comment\n"
      "uint16 b\n"
      "byte c\n"
      "char d\n"
      "bool e\n"
      "int64 f\n"
      "uint64 g\n"
      "float32 h\n"
      "duration i\n"
      "Inner[2] inner\n"
      "\n"
      "================================================================================\n"
      "MSG: test_msgs/Inner\n"
      "int16 x\n";
  const auto schema = std::make_shared<const MessageSchema>("test_msgs/All", definition);
  const auto bytes = pack(std::int8_t(-5), std::uint16_t(65535), std::int8_t(-7), std::uint8_t(200), std::uint8_t(1),
                          std::int64_t(-1234567890123), std::uint64_t(9876543210), 2.5f, std::int32_t(-2),
                          std::int32_t(-500000000), std::int16_t(-3), std::int16_t(4));
  auto read = [&](const std::string& path) { return FieldReader(schema, path).read(bytes.data(), bytes.size()); };
  EXPECT_EQ(read("a"), -5);
  EXPECT_EQ(read("b"), 65535);
  EXPECT_EQ(read("c"), -7);  // byte: int8
  EXPECT_EQ(read("d"), 200);  // char: uint8
  EXPECT_EQ(read("e"), 1);
  EXPECT_EQ(read("f"), -1234567890123.0);
  EXPECT_EQ(read("g"), 9876543210.0);
  EXPECT_EQ(read("h"), 2.5);
  EXPECT_DOUBLE_EQ(read("i"), -2.5);  // a duration: seconds
  EXPECT_EQ(read("inner[1].x"), 4);
  EXPECT_EQ(schema->root().fieldNames(), "a, b, c, d, e, f, g, h, i, inner");
}

TEST(MessageFields, BadPathsNameThePathAndTheFieldsThatExist) {
  const nav_msgs::Odometry o = odometry();
  EXPECT_EQ(fieldError(o, "pose.pose.positon"),
            "nav_msgs/Odometry has no field 'pose.pose.positon' (pose has: position, orientation)");
  EXPECT_EQ(fieldError(o, "posse.x"),
            "nav_msgs/Odometry has no field 'posse.x' (nav_msgs/Odometry has: header, child_frame_id, pose, twist)");
  EXPECT_EQ(fieldError(o, "pose.pose.position.x.y"), "'pose.pose.position.x' is a float64: it has no field 'y'");
  EXPECT_EQ(fieldError(o, "pose.covariance"),
            "'pose.covariance' is an array (float64[36]): give an index, e.g. pose.covariance[0]");
  EXPECT_EQ(fieldError(o, "pose[0].pose"), "'pose' is a geometry_msgs/PoseWithCovariance, not an array");
  EXPECT_EQ(fieldError(o, "pose.covariance[36]"), "'pose.covariance[36]' is out of range: covariance has 36 elements");
  EXPECT_EQ(fieldError(o, "pose.covariance[x]"), "'pose.covariance[x]' has no valid index (e.g. ranges[3])");
  EXPECT_THAT(fieldError(o, ""), HasSubstr("is not a field path"));
  EXPECT_THAT(fieldError(o, "pose."), HasSubstr("is not a field path"));
}

TEST(MessageFields, FieldsThatAreNotNumbersAreErrorsNamingTheirType) {
  const nav_msgs::Odometry o = odometry();
  EXPECT_EQ(fieldError(o, "child_frame_id"), "'child_frame_id' is a string, not a number");
  EXPECT_EQ(fieldError(o, "header.frame_id"), "'header.frame_id' is a string, not a number");
  EXPECT_EQ(fieldError(o, "pose.pose"),
            "'pose.pose' is a geometry_msgs/Pose, not a number: name one of its fields (position, orientation)");
  EXPECT_EQ(fieldError(o, "header"),
            "'header' is a std_msgs/Header, not a number: name one of its fields (seq, stamp, frame_id)");
}

TEST(MessageFields, AnIndexPastTheMessagesArrayIsAnError) {
  sensor_msgs::LaserScan scan;
  scan.ranges = {1.f, 2.f};
  EXPECT_EQ(fieldError(scan, "ranges[2]"), "'ranges[2]' is out of range: this message's ranges has 2 elements");
  EXPECT_EQ(fieldError(scan, "intensities[0]"), "'intensities[0]' is out of range: this message's intensities has 0 elements");
  geometry_msgs::PoseArray poses;
  poses.poses.resize(1);
  EXPECT_EQ(fieldError(poses, "poses[1].position.x"), "'poses[1]' is out of range: this message's poses has 1 element");
}

TEST(MessageFields, TruncatedBytesAreErrorsAtEveryLength) {
  const RosMessage m = apex_nodes::toRosMessage(odometry());
  const auto schema = std::make_shared<const MessageSchema>(m.datatype, m.definition);
  const FieldReader last(schema, "twist.covariance[35]");
  EXPECT_EQ(last.read(m.bytes.data(), m.bytes.size()), 0.0);
  EXPECT_NO_THROW(schema->check(m.bytes.data(), m.bytes.size()));
  for (std::size_t n = 0; n < m.bytes.size(); ++n) {
    const std::vector<std::uint8_t> cut(m.bytes.begin(), m.bytes.begin() + n);  // its own buffer: a read past it is caught
    try {
      last.read(cut.data(), cut.size());
      ADD_FAILURE() << n << " bytes read";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("a nav_msgs/Odometry message of " + std::to_string(n) +
                                      " bytes is truncated before 'twist.covariance[35]'"));
    }
    EXPECT_THROW(schema->check(cut.data(), cut.size()), std::invalid_argument) << n;
  }
  // A count that claims more than the bytes hold: an error, nothing allocated or read.
  sensor_msgs::LaserScan scan;
  scan.ranges = {1.f, 2.f};
  RosMessage s = apex_nodes::toRosMessage(scan);
  const std::size_t count_at = 4 + 8 + 4 + 7 * 4;  // seq, stamp, frame_id "", 7 float32
  const std::uint32_t huge = 0xFFFFFFFF;
  std::memcpy(s.bytes.data() + count_at, &huge, 4);
  EXPECT_THAT(fieldError(s, "intensities[0]"), HasSubstr("is truncated"));
}

TEST(MessageFields, DefinitionsThatCannotBeReadAreErrors) {
  auto error = [](const std::string& definition) {
    try {
      MessageSchema("test_msgs/A", definition);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("B b\n"), "test_msgs/A's definition has no section for test_msgs/B (field 'b' of test_msgs/A)");
  EXPECT_EQ(error("A a\n"), "type test_msgs/A contains itself");
  EXPECT_EQ(error("int32\n"), "line 1 of test_msgs/A's definition: 'int32' is not a field (type name)");
  EXPECT_EQ(error("# x\nint32[ y\n"), "line 2 of test_msgs/A's definition: 'int32[' is not a type");
  EXPECT_THAT(error("float64[4294967295] a\nB[4294967295] b\nMSG: test_msgs/B\nfloat64[4294967295] c\n"),
              HasSubstr("is too large"));
  EXPECT_EQ(error(""), "");  // no fields (std_msgs/Empty)
}

TEST(RosMessage, HeaderOfTypesThatStartWithOne) {
  const RosMessage o = apex_nodes::toRosMessage(odometry());
  ASSERT_TRUE(o.header());
  EXPECT_EQ(o.header()->frame_id, "odom");
  EXPECT_EQ(o.header()->seq, 41u);
  EXPECT_EQ(o.stamp(), odometry().header.stamp);
  std_msgs::Float64 number;
  EXPECT_FALSE(apex_nodes::toRosMessage(number).header());
  EXPECT_EQ(apex_nodes::toRosMessage(number).stamp(), ros::Time());
  RosMessage cut = o;
  cut.bytes.resize(14);  // the stamp, not the frame
  EXPECT_FALSE(cut.header());
}

TEST(RosMessage, ItsInspectorRecordsItAsTheMessageItIs) {
  pluginRegistry();  // apex_nodes_ros loaded
  const auto shared = std::make_shared<const RosMessage>(apex_nodes::toRosMessage(odometry()));
  const apex::Inspector inspector = apex::findInspector(apex::typeOf<RosMessage>());
  ASSERT_TRUE(inspector.serialize);
  const apex::SerializedMessage s = inspector.serialize(Message::share<RosMessage>(shared));
  EXPECT_EQ(s.datatype, "nav_msgs/Odometry");
  EXPECT_EQ(s.md5sum, ros::message_traits::md5sum<nav_msgs::Odometry>());
  EXPECT_EQ(s.definition, shared->definition);
  EXPECT_EQ(s.bytes, shared->bytes);
  EXPECT_EQ(s.stamp, odometry().header.stamp);  // BagWriter's record time
  EXPECT_EQ(inspector.describe(Message::share<RosMessage>(shared)),
            "nav_msgs/Odometry, " + std::to_string(shared->bytes.size()) + " bytes, frame 'odom' at 1000.250000000");
  EXPECT_THAT(apex::inspectedTypes(), testing::Contains("ROS message"));
}

TEST(RosConversions, KnownTypesBecomeTheirPortTypesAndOthersStayRosMessages) {
  using apex_nodes::portType;
  EXPECT_EQ(portType("sensor_msgs/Image"), apex::typeOf<apex_nodes::Image>());
  EXPECT_EQ(portType("sensor_msgs/PointCloud2"), apex::typeOf<apex_nodes::Cloud>());
  EXPECT_EQ(portType("geometry_msgs/PoseStamped"), apex::typeOf<geometry_msgs::PoseStamped>());
  EXPECT_EQ(portType("std_msgs/Float32"), apex::typeOf<double>());
  EXPECT_EQ(portType("std_msgs/Int64"), apex::typeOf<int>());
  EXPECT_EQ(portType("apex/Regions"), apex::typeOf<apex_nodes::Regions>());
  EXPECT_EQ(portType("nav_msgs/Odometry"), apex::typeOf<RosMessage>());

  const Message image = apex_nodes::toPort(std::make_shared<const RosMessage>(apex_nodes::toRosMessage(apex_test::image(7))));
  ASSERT_TRUE(image.as<apex_nodes::Image>());
  EXPECT_EQ(image.as<apex_nodes::Image>()->mat.at<std::uint8_t>(1, 2), 7);
  EXPECT_EQ(image.as<apex_nodes::Image>()->header.stamp, frameTime(7));
  const Message cloud = apex_nodes::toPort(std::make_shared<const RosMessage>(apex_nodes::toRosMessage(apex_test::cloud(2))));
  ASSERT_TRUE(cloud.as<apex_nodes::Cloud>());
  EXPECT_EQ(cloud.as<apex_nodes::Cloud>()->header.stamp, frameTime(2));

  const auto odom = std::make_shared<const RosMessage>(apex_nodes::toRosMessage(odometry()));
  EXPECT_EQ(apex_nodes::toPort(odom).as<RosMessage>(), odom);  // itself, shared
}

TEST(RosConversions, AnotherDefinitionTruncatedBytesAndNumbersOutOfRangeAreErrors) {
  const apex_nodes::RosConversion* scan = apex_nodes::findConversion("sensor_msgs/LaserScan");
  ASSERT_TRUE(scan);
  sensor_msgs::LaserScan s;
  s.ranges = {1.f, 2.f, 3.f};
  RosMessage m = apex_nodes::toRosMessage(s);
  EXPECT_EQ(*scan->convert(m).as<sensor_msgs::LaserScan>(), s);
  m.bytes.resize(m.bytes.size() - 3);
  EXPECT_THROW(scan->convert(m), std::invalid_argument);
  m = apex_nodes::toRosMessage(s);
  m.md5sum = "0123456789abcdef0123456789abcdef";
  try {
    scan->convert(m);
    ADD_FAILURE() << "converted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("has another definition than this build's"));
  }
  std_msgs::Int64 big;
  big.data = std::int64_t(1) << 40;
  EXPECT_THROW(apex_nodes::findConversion("std_msgs/Int64")->convert(apex_nodes::toRosMessage(big)), std::invalid_argument);
  big.data = -12;
  EXPECT_EQ(*apex_nodes::findConversion("std_msgs/Int64")->convert(apex_nodes::toRosMessage(big)).as<int>(), -12);
}

TEST(TopicSubscriber, ItsOutputIsTypedByItsTypeParameter) {  // not started: no subscription, no master
  Graph g(pluginRegistry());
  add(g, "apex_nodes/TopicSubscriber", "sub");
  auto output = [&] { return g.nodeInterface("sub")->findOutput("message")->type; };
  EXPECT_EQ(output(), typeOf<RosMessage>());  // any type, as received
  for (const auto& [type, port] :
       {std::pair("sensor_msgs/Image", typeOf<apex_nodes::Image>()), std::pair("std_msgs/Float64", typeOf<double>()),
        std::pair("nav_msgs/Odometry", typeOf<RosMessage>())}) {
    ASSERT_TRUE(g.setParameter("sub", "type", type));
    EXPECT_EQ(output(), port) << type;
  }
  auto r = g.setParameter("sub", "type", "Odometry");
  ASSERT_FALSE(r);
  EXPECT_THAT(r.message(), HasSubstr("type 'Odometry' is not a ROS message type (package/Name, e.g. nav_msgs/Odometry)"));
}

Message rosMessage(const nav_msgs::Odometry& o) { return Message::make<RosMessage>(apex_nodes::toRosMessage(o)); }

TEST(FieldExtract, ReadsAFieldOfARosMessage) {
  NodeHarness h("apex_nodes/FieldExtract", {"message"}, "value", {{"field", "pose.pose.position.x"}});
  const Message out = h.run({rosMessage(odometry(2))});
  ASSERT_TRUE(out.as<double>()) << h.error();
  EXPECT_EQ(*out.as<double>(), 3.5);
  h.set("field", "twist.twist.angular.z");  // the path changes: read anew
  EXPECT_EQ(*h.run({rosMessage(odometry(2))}).as<double>(), -0.3);
  h.set("field", "header.stamp");  // one path, messages of two types: each read as its type has it
  EXPECT_DOUBLE_EQ(*h.run({rosMessage(odometry(4))}).as<double>(), odometry(4).header.stamp.toSec());
  EXPECT_DOUBLE_EQ(*h.run({Message::make<RosMessage>(apex_nodes::toRosMessage(imu(5)))}).as<double>(), frameTime(5).toSec());
}

TEST(FieldExtract, ReadsAFieldOfATypedMessageThroughItsRosForm) {
  NodeHarness h("apex_nodes/FieldExtract", {"message"}, "value", {{"field", "pose.orientation.z"}});
  geometry_msgs::PoseStamped pose;
  pose.header.stamp = frameTime(3);
  pose.pose.orientation.z = 0.5;
  const Message out = h.run({Message::make<geometry_msgs::PoseStamped>(pose)});
  ASSERT_TRUE(out.as<double>()) << h.error();
  EXPECT_EQ(*out.as<double>(), 0.5);
  h.set("field", "header.stamp");
  EXPECT_DOUBLE_EQ(*h.run({Message::make<geometry_msgs::PoseStamped>(pose)}).as<double>(), frameTime(3).toSec());
  sensor_msgs::CameraInfo info = cameraInfo(1);
  h.set("field", "K[2]");
  EXPECT_EQ(*h.run({Message::make<sensor_msgs::CameraInfo>(info)}).as<double>(), 1.5);
}

TEST(FieldExtract, ABadPathOrATypeWithNoRosFormIsAnErrorOnTheNode) {
  NodeHarness h("apex_nodes/FieldExtract", {"message"}, "value", {{"field", "pose.pose.positon.x"}});
  EXPECT_TRUE(h.run({rosMessage(odometry())}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("nav_msgs/Odometry has no field 'pose.pose.positon.x' (pose has: position, orientation)"));
  h.set("field", "child_frame_id");
  EXPECT_TRUE(h.run({rosMessage(odometry())}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("'child_frame_id' is a string, not a number"));
  EXPECT_TRUE(h.run({Message::make<NoRosForm>({})}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("input 'message' carries test/NoRosForm, which has no ROS message to read a field of"));
  EXPECT_THAT(h.error(), HasSubstr("ROS message"));  // among the types that have one
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::Time::init();
  return RUN_ALL_TESTS();
}
