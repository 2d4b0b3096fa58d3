// DnnNetwork against OpenCV's dnn called directly (readNetFromONNX, blobFromImage, forward), float
// for float, on opencv-doc's digits.png (5,000 handwritten digits of 20x20 pixels, 50 rows of 100).
// The network is the test's own: Flatten, Gemm of seeded random weights, Softmax, written as ONNX by
// a Python script with python3-onnx (scripts/install_deps).
#include <gmock/gmock.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Regions;
using ::testing::HasSubstr;

namespace {

constexpr int kCell = 20, kClasses = 10;
constexpr double kScale = 1.0 / 256;  // exact in a double and in the parameter's text
const cv::Scalar kMean(10, 0, 0);
const std::vector<std::pair<std::string, std::string>> kParams{
    {"input_width", "20"}, {"input_height", "20"}, {"scale", "0.00390625"}, {"mean", "[10, 0, 0]"}};

/** Writes the network to argv[1]: a 1x1x20x20 image, flattened, times 10 x 400 weights plus 10 biases
 *  (Python's random, seeded), then a softmax: 10 probabilities. */
const char* const kScript = R"(
import random, sys
import onnx
from onnx import helper, TensorProto

side, classes = 20, 10
rng = random.Random(53)
weights = [rng.gauss(0.0, 0.05) for _ in range(classes * side * side)]
bias = [rng.gauss(0.0, 0.1) for _ in range(classes)]
graph = helper.make_graph(
    [helper.make_node("Flatten", ["image"], ["flat"], axis=1),
     helper.make_node("Gemm", ["flat", "weights", "bias"], ["scores"], transB=1),
     helper.make_node("Softmax", ["scores"], ["probabilities"], axis=1)],
    "tiny_digits",
    [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 1, side, side])],
    [helper.make_tensor_value_info("probabilities", TensorProto.FLOAT, [1, classes])],
    [helper.make_tensor("weights", TensorProto.FLOAT, [classes, side * side], weights),
     helper.make_tensor("bias", TensorProto.FLOAT, [classes], bias)])
model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
onnx.checker.check_model(model)
onnx.save(model, sys.argv[1])
)";

std::string tempPath(const std::string& name) {
  static int n = 0;
  return ::testing::TempDir() + "/apex_dnn_" + std::to_string(::getpid()) + "_" + std::to_string(++n) + "_" + name;
}

/** The network's file, written once per process by the script above. */
const std::string& tinyNetwork() {
  static const std::string model = [] {
    const std::string script = tempPath("tiny_digits.py"), path = tempPath("tiny_digits.onnx");
    std::ofstream(script) << kScript;
    const std::string command = "/usr/bin/python3 " + script + " " + path;
    EXPECT_EQ(std::system(command.c_str()), 0) << command << " failed: is python3-onnx installed (scripts/install_deps)?";
    return path;
  }();
  return model;
}

const cv::Mat& digitsImage() {
  static const cv::Mat image = readGrayData("digits.png");
  return image;
}
cv::Rect cellBox(int i) { return {(i % 100) * kCell, (i / 100) * kCell, kCell, kCell}; }

/** What the network gives for one crop, run directly. */
struct Direct {
  cv::Mat row;  // 1 x 10 floats
  int label;
  float confidence;
};
Direct direct(const cv::Mat& crop, bool center_crop = false) {
  static cv::dnn::Net net = [] {
    cv::dnn::Net n = cv::dnn::readNetFromONNX(tinyNetwork());
    n.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);  // the node's defaults
    n.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
    return n;
  }();
  net.setInput(cv::dnn::blobFromImage(crop, kScale, cv::Size(kCell, kCell), kMean, false, center_crop));
  Direct d;
  d.row = net.forward().reshape(1, 1).clone();  // forward's Mat is the net's own buffer
  const float* v = d.row.ptr<float>();
  d.label = static_cast<int>(std::max_element(v, v + d.row.cols) - v);
  d.confidence = v[d.label];
  return d;
}

std::shared_ptr<Regions> cellRegions(const std::vector<int>& cells) {
  auto r = std::make_shared<Regions>();
  r->header.stamp = ros::Time(42, 7);
  r->header.frame_id = "camera";
  r->image_size = digitsImage().size();
  for (int i : cells) {
    apex_nodes::Region region;
    region.box = cellBox(i);
    region.area = region.box.area();
    r->regions.push_back(region);
  }
  return r;
}

/** A DnnNetwork on the tiny network, sending `output`, its inputs `inputs`. */
std::unique_ptr<NodeHarness> dnn(std::vector<std::string> inputs, const std::string& output) {
  auto h = std::make_unique<NodeHarness>("apex_nodes/DnnNetwork", std::move(inputs), output);
  h->set("model", tinyNetwork());
  for (const auto& [name, value] : kParams) h->set(name, value);
  return h;
}

TEST(DnnNetwork, LabelsEachRegionsCropAsTheNetworkRunDirectly) {
  std::vector<int> cells;
  for (int i = 0; i < 5000; i += 167) cells.push_back(i);  // 30 cells, every digit
  auto regions = cellRegions(cells);
  apex_nodes::Region outside = regions->regions[0];
  outside.box = {5000, 5000, 20, 20};  // outside the image: not run
  regions->regions.push_back(outside);
  const std::vector<Message> in{Message::share<apex_nodes::Image>(imageOf(digitsImage(), "mono8")),
                                Message::share<Regions>(regions)};

  auto labels = dnn({"image", "regions"}, "regions");
  const Message m = labels->run(in);
  ASSERT_TRUE(m.as<Regions>()) << labels->error();
  const Regions& got = *m.as<Regions>();
  EXPECT_EQ(got.header, regions->header);
  ASSERT_EQ(got.regions.size(), cells.size() + 1);
  std::set<int> seen;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const Direct d = direct(digitsImage()(cellBox(cells[k])).clone());
    EXPECT_EQ(got.regions[k].box, cellBox(cells[k]));
    EXPECT_EQ(got.regions[k].label, d.label) << "cell " << cells[k];
    EXPECT_EQ(got.regions[k].confidence, double(d.confidence)) << "cell " << cells[k];
    seen.insert(d.label);
  }
  EXPECT_GE(seen.size(), 3u) << "the network should tell some cells apart";
  EXPECT_EQ(got.regions.back().label, -1);
  EXPECT_EQ(got.regions.back().confidence, 0.0);

  // The raw output: a row of 10 per region, zeros for the one outside.
  auto raw = dnn({"image", "regions"}, "output");
  const Message out = raw->run(in);
  ASSERT_TRUE(out.as<apex_nodes::Image>()) << raw->error();
  const apex_nodes::Image& rows = *out.as<apex_nodes::Image>();
  expectCameraHeader(rows.header);
  EXPECT_EQ(rows.encoding, "32FC1");
  ASSERT_EQ(rows.mat.size(), cv::Size(kClasses, int(cells.size()) + 1));
  for (std::size_t k = 0; k < cells.size(); ++k)
    expectSameMat(rows.mat.row(int(k)), direct(digitsImage()(cellBox(cells[k])).clone()).row);
  EXPECT_EQ(cv::countNonZero(rows.mat.row(int(cells.size()))), 0);
}

TEST(DnnNetwork, WithoutRegionsItClassifiesTheWholeImageResizedOrCropped) {
  const cv::Mat six = digitsImage()(cv::Rect(600, 600, 60, 40)).clone();  // 3 x 2 cells of sixes, resized to 20x20
  for (const bool center_crop : {false, true}) {
    auto h = dnn({"image"}, "regions");
    h->set("crop", center_crop ? "true" : "false");
    const Message m = h->run<apex_nodes::Image>(imageOf(six, "mono8"));
    ASSERT_TRUE(m.as<Regions>()) << h->error();
    const Regions& got = *m.as<Regions>();
    expectCameraHeader(got.header);
    EXPECT_EQ(got.image_size, six.size());
    ASSERT_EQ(got.regions.size(), 1u);
    EXPECT_EQ(got.regions[0].box, cv::Rect(0, 0, 60, 40));
    const Direct d = direct(six, center_crop);
    EXPECT_EQ(got.regions[0].label, d.label);
    EXPECT_EQ(got.regions[0].confidence, double(d.confidence));
    // min_confidence above it: unlabelled, the confidence kept
    h->set("min_confidence", std::to_string(std::min(1.0, d.confidence + 0.01)));
    const Message unsure = h->run<apex_nodes::Image>(imageOf(six, "mono8"));
    ASSERT_TRUE(unsure.as<Regions>()) << h->error();
    EXPECT_EQ(unsure.as<Regions>()->regions[0].label, -1);
    EXPECT_EQ(unsure.as<Regions>()->regions[0].confidence, double(d.confidence));
  }
}

TEST(DnnNetwork, AMissingOrUnreadableModelIsAnErrorNamingIt) {
  auto h = dnn({"image"}, "regions");
  const auto cell = imageOf(digitsImage()(cellBox(0)).clone(), "mono8");
  const std::string missing = tempPath("none.onnx");
  h->set("model", missing);
  expectNothing(*h, h->run<apex_nodes::Image>(cell), "the model '" + missing + "' cannot be read: no such file");

  const std::string damaged = tempPath("damaged.onnx");
  std::ofstream(damaged) << "not a network";
  h->set("model", damaged);
  expectNothing(*h, h->run<apex_nodes::Image>(cell), "the model '" + damaged + "' cannot be read by OpenCV's dnn");

  const std::string unknown = tempPath("net.xyz");
  std::ofstream(unknown) << "not a network either";
  h->set("model", unknown);
  expectNothing(*h, h->run<apex_nodes::Image>(cell), "the model '" + unknown + "' cannot be read by OpenCV's dnn");
  EXPECT_THAT(h->error(), HasSubstr("Cannot determine an origin framework"));

  h->set("model", "''");  // YAML's empty text
  expectNothing(*h, h->run<apex_nodes::Image>(cell), "no model: set 'model'");

  // A colour image for a network of one channel: an error naming the network and the crop.
  h->set("model", tinyNetwork());
  cv::Mat colour;
  cv::cvtColor(digitsImage()(cellBox(0)), colour, cv::COLOR_GRAY2BGR);
  expectNothing(*h, h->run<apex_nodes::Image>(imageOf(colour, "bgr8")),
                "the network '" + tinyNetwork() + "' cannot run on a 20x20 crop of 3 channels at 20x20");

  // The model back: labelled, the error gone.
  const Message m = h->run<apex_nodes::Image>(cell);
  ASSERT_TRUE(m.as<Regions>()) << h->error();
  EXPECT_EQ(m.as<Regions>()->regions[0].label, direct(cell->mat).label);
  EXPECT_EQ(h->error(), "");
}

}  // namespace
