// DnnNetwork's tasks detect and segment against OpenCV's dnn called directly (readNetFromONNX,
// blobFromImage, forward) and the decoding written out here: SSD's rows above the confidence, then
// NMSBoxes class by class, on opencv-doc's messi5.jpg; the largest score's class per pixel, resized
// by nearest neighbour, on fruits.jpg. The networks are the test's own, written as ONNX by a Python
// script with python3-onnx (scripts/install_deps): detection rows that pass through the network
// whatever the pixels (a corner of the image times 0, plus the rows), per-pixel class scores of a
// 1x1 convolution of seeded random weights, and a classifier's [1, 3] for the errors.
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
using apex_nodes::Region;
using apex_nodes::Regions;

namespace {

constexpr double kScale = 1.0 / 256;  // exact in a double and in the parameter's text
const cv::Scalar kMean(10, 20, 30);
const std::vector<std::pair<std::string, std::string>> kParams{
    {"scale", "0.00390625"}, {"mean", "[10, 20, 30]"}, {"swap_rb", "true"}};

/** Writes the networks to the folder argv[1]: detect.onnx, segment.onnx, segment_300.onnx, classify.onnx. */
const char* const kScript = R"(
import os, random, sys
import onnx
from onnx import helper, TensorProto

folder = sys.argv[1]
os.makedirs(folder, exist_ok=True)


def save(name, nodes, image, output, constants):
    graph = helper.make_graph(
        nodes, name, [helper.make_tensor_value_info("image", TensorProto.FLOAT, image)],
        [helper.make_tensor_value_info(nodes[-1].output[0], TensorProto.FLOAT, output)], constants)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
    onnx.checker.check_model(model)
    onnx.save(model, folder + "/" + name + ".onnx")


def floats(name, dims, values):
    return helper.make_tensor(name, TensorProto.FLOAT, dims, values)


# detect: these rows whatever the pixels (the first 9 x 7 values of channel 0, times 0, plus the
# rows; OpenCV 4.6 reads neither a ReduceMean over all axes nor an Add that broadcasts the rows):
# image_id, class_id, confidence, x1, y1, x2, y2
rows = [[0, 1, 0.90, 0.10, 0.10, 0.50, 0.60],
        [0, 1, 0.80, 0.12, 0.12, 0.52, 0.62],  # row 0 moved a little
        [0, 1, 0.70, 0.30, 0.10, 0.70, 0.60],  # over a third of row 0
        [0, 1, 0.20, 0.60, 0.60, 0.90, 0.95],  # unsure, alone
        [0, 2, 0.85, 0.11, 0.11, 0.51, 0.61],  # over row 0, another class
        [0, 2, 0.60, 0.55, 0.50, 1.05, 1.02],  # past the image's right and bottom
        [0, 2, 0.30, 0.56, 0.52, 1.00, 1.00],  # unsure, over row 5
        [0, 2, 0.75, 0.58, 0.52, 1.00, 1.00],  # inside row 5
        [0, 0, 0.00, 0.00, 0.00, 0.00, 0.00]]  # DetectionOutput's filler
save("detect",
     [helper.make_node("Slice", ["image", "starts", "ends"], ["corner"]),
      helper.make_node("Mul", ["corner", "zero"], ["nought"]),
      helper.make_node("Add", ["nought", "rows"], ["detections"])],
     [1, 3, 64, 64], [1, 1, len(rows), 7],
     [helper.make_tensor("starts", TensorProto.INT64, [4], [0, 0, 0, 0]),
      helper.make_tensor("ends", TensorProto.INT64, [4], [1, 1, len(rows), 7]),
      floats("zero", [], [0.0]), floats("rows", [1, 1, len(rows), 7], [v for r in rows for v in r])])

# segment: scores of `classes` per pixel, a 1x1 convolution of seeded random weights (seed 31: each
# of the 3 classes wins somewhere in fruits.jpg)
for name, classes, height, width, seed in [("segment", 3, 48, 64, 31), ("segment_300", 300, 12, 16, 7)]:
    rng = random.Random(seed)
    save(name, [helper.make_node("Conv", ["image", "weights", "bias"], ["scores"], kernel_shape=[1, 1])],
         [1, 3, height, width], [1, classes, height, width],
         [floats("weights", [classes, 3, 1, 1], [rng.gauss(0.0, 1.0) for _ in range(classes * 3)]),
          floats("bias", [classes], [rng.gauss(0.0, 0.1) for _ in range(classes)])])

# classify-shaped: each channel's mean, [1, 3]
save("classify", [helper.make_node("GlobalAveragePool", ["image"], ["pooled"]),
                  helper.make_node("Flatten", ["pooled"], ["means"], axis=1)],
     [1, 3, 64, 64], [1, 3], [])
)";

/** The network `name` (detect, segment, segment_300, classify), written once per process by the script. */
std::string network(const std::string& name) {
  static const std::string folder = [] {
    const std::string base = ::testing::TempDir() + "/apex_dnn_tasks_" + std::to_string(::getpid());
    const std::string script = base + ".py", path = base + "_networks";
    std::ofstream(script) << kScript;
    const std::string command = "/usr/bin/python3 " + script + " " + path;
    EXPECT_EQ(std::system(command.c_str()), 0) << command << " failed: is python3-onnx installed (scripts/install_deps)?";
    return path;
  }();
  return folder + "/" + name + ".onnx";
}

/** The network's output for `image` at `input`, run directly as the node's defaults run it. */
cv::Mat directForward(const std::string& name, const cv::Mat& image, const cv::Size& input) {
  cv::dnn::Net net = cv::dnn::readNetFromONNX(network(name));
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  net.setInput(cv::dnn::blobFromImage(image, kScale, input, kMean, true, false));
  return net.forward().clone();  // forward's Mat is the net's own buffer
}

/** A detection as the test reads it from a row of the output. */
struct Detection {
  int row;
  cv::Rect box;
  int label;
  float confidence;
};

/** The rows of `out` ([1, 1, N, 7]) above `min_confidence`, as boxes of an image of `size` (corners
 *  rounded, cut to the image), then NMSBoxes for each class in turn; the most confident first
 *  (no two rows here are equally confident). */
std::vector<Detection> directDetections(const cv::Mat& out, const cv::Size& size, float min_confidence, float nms_threshold) {
  const cv::Mat rows = out.reshape(1, out.size[2]);  // N x 7
  std::vector<Detection> candidates;
  std::set<int> classes;
  for (int i = 0; i < rows.rows; ++i) {
    const float* d = rows.ptr<float>(i);
    if (!(d[2] > min_confidence)) continue;
    const cv::Point corner1(cvRound(d[3] * size.width), cvRound(d[4] * size.height));
    const cv::Point corner2(cvRound(d[5] * size.width), cvRound(d[6] * size.height));
    const cv::Rect box = cv::Rect(corner1, corner2) & cv::Rect(cv::Point(), size);
    if (box.area() == 0) continue;
    candidates.push_back({i, box, cvRound(d[1]), d[2]});
    classes.insert(cvRound(d[1]));
  }
  std::vector<Detection> kept;
  for (const int label : classes) {
    std::vector<Detection> of_class;
    std::vector<cv::Rect> boxes;
    std::vector<float> scores;
    for (const Detection& c : candidates)
      if (c.label == label) of_class.push_back(c), boxes.push_back(c.box), scores.push_back(c.confidence);
    std::vector<int> indices;
    cv::dnn::NMSBoxes(boxes, scores, min_confidence, nms_threshold, indices);
    for (const int k : indices) kept.push_back(of_class[k]);
  }
  std::sort(kept.begin(), kept.end(), [](const Detection& a, const Detection& b) { return a.confidence > b.confidence; });
  return kept;
}

/** The class of each pixel of `out` ([1, C, H, W]): the first of its largest scores, resized to `size`. */
cv::Mat directMask(const cv::Mat& out, const cv::Size& size) {
  const int classes = out.size[1], rows = out.size[2], cols = out.size[3];
  cv::Mat index(rows, cols, classes <= 256 ? CV_8U : CV_16U);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      int best = 0;
      for (int c = 1; c < classes; ++c)
        if (out.at<float>(cv::Vec4i(0, c, y, x)) > out.at<float>(cv::Vec4i(0, best, y, x))) best = c;
      if (index.depth() == CV_8U) index.at<uchar>(y, x) = static_cast<uchar>(best);
      else index.at<ushort>(y, x) = static_cast<ushort>(best);
    }
  cv::Mat mask;
  cv::resize(index, mask, size, 0, 0, cv::INTER_NEAREST);
  return mask;
}

/** A DnnNetwork on `model` for `task`, its input `input` pixels, sending `output`, fed an image alone. */
std::unique_ptr<NodeHarness> dnn(const std::string& task, const std::string& model, const cv::Size& input,
                                 const std::string& output, std::vector<std::string> inputs = {"image"}) {
  auto h = std::make_unique<NodeHarness>("apex_nodes/DnnNetwork", std::move(inputs), output);
  h->set("task", task);
  h->set("model", network(model));
  h->set("input_width", std::to_string(input.width));
  h->set("input_height", std::to_string(input.height));
  for (const auto& [name, value] : kParams) h->set(name, value);
  return h;
}

const cv::Size kDetectInput(64, 64), kSegmentInput(64, 48);

TEST(DnnNetwork, DetectKeepsTheRowsAboveTheConfidenceThenNmsPerClassAsCalledDirectly) {
  const auto messi = readDataImage("messi5.jpg");
  const cv::Size size = messi->mat.size();
  const cv::Mat out = directForward("detect", messi->mat, kDetectInput);
  ASSERT_EQ(out.dims, 4);
  ASSERT_EQ(out.size[2], 9);
  // min_confidence, nms_threshold, and the rows kept as this test's rows were made to give
  struct Case {
    std::string min_confidence, nms_threshold;
    std::vector<int> rows;
  };
  const std::vector<Case> cases{{"0.5", "0.4", {0, 4, 7, 2}},  // unsure 3, 6 and the filler below; 1 over 0, 5 under 7
                                {"0.5", "0.3", {0, 4, 7}},  // 2 too: a third over 0
                                {"0.5", "0.95", {0, 4, 1, 7, 2, 5}},  // the overlaps all below
                                {"0.0", "0.4", {0, 4, 7, 2, 3}}};  // unsure 3 kept; 6 under 7; the filler's 0 is not above 0
  auto h = dnn("detect", "detect", kDetectInput, "regions");
  for (const Case& c : cases) {
    SCOPED_TRACE("min_confidence " + c.min_confidence + ", nms_threshold " + c.nms_threshold);
    h->set("min_confidence", c.min_confidence);
    h->set("nms_threshold", c.nms_threshold);
    const std::vector<Detection> want = directDetections(out, size, static_cast<float>(std::stod(c.min_confidence)),
                                                         static_cast<float>(std::stod(c.nms_threshold)));
    std::vector<int> rows;
    for (const Detection& d : want) rows.push_back(d.row);
    EXPECT_EQ(rows, c.rows) << "the direct computation";

    const Message m = h->run<apex_nodes::Image>(messi);
    ASSERT_TRUE(m.as<Regions>()) << h->error();
    const Regions& got = *m.as<Regions>();
    expectCameraHeader(got.header);
    EXPECT_EQ(got.image_size, size);
    ASSERT_EQ(got.regions.size(), want.size());
    for (std::size_t k = 0; k < want.size(); ++k) {
      const Region& r = got.regions[k];
      EXPECT_EQ(r.box, want[k].box) << "row " << want[k].row;
      EXPECT_EQ(r.box & cv::Rect(cv::Point(), size), r.box) << "row " << want[k].row << " should be cut to the image";
      EXPECT_EQ(r.label, want[k].label) << "row " << want[k].row;
      EXPECT_EQ(r.confidence, double(want[k].confidence)) << "row " << want[k].row;
      EXPECT_EQ(r.area, want[k].box.area());
      EXPECT_EQ(r.centroid, cv::Point2d(want[k].box.x + want[k].box.width / 2.0, want[k].box.y + want[k].box.height / 2.0));
    }
  }

  // The output: all 9 rows, as the network gave them; no mask.
  auto raw = dnn("detect", "detect", kDetectInput, "output");
  expectImage(*raw, raw->run<apex_nodes::Image>(messi), out.reshape(1, 9), "32FC1");
  auto mask = dnn("detect", "detect", kDetectInput, "mask");
  EXPECT_TRUE(mask->run<apex_nodes::Image>(messi).isNothing());
  EXPECT_EQ(mask->error(), "");
}

TEST(DnnNetwork, SegmentSendsEachPixelsClassAsCalledDirectly) {
  const auto fruits = readDataImage("fruits.jpg");
  const cv::Mat out = directForward("segment", fruits->mat, kSegmentInput);
  ASSERT_EQ(out.dims, 4);
  const cv::Mat want = directMask(out, fruits->mat.size());
  for (int c = 0; c < 3; ++c) EXPECT_GT(cv::countNonZero(want == c), 1000) << "class " << c << " should win somewhere";

  auto h = dnn("segment", "segment", kSegmentInput, "mask");
  expectImage(*h, h->run<apex_nodes::Image>(fruits), want, "mono8");
  // The output: the scores, class after class (3 x 48 rows of 64); no regions.
  auto raw = dnn("segment", "segment", kSegmentInput, "output");
  expectImage(*raw, raw->run<apex_nodes::Image>(fruits), out.reshape(1, 3 * 48), "32FC1");
  auto regions = dnn("segment", "segment", kSegmentInput, "regions");
  EXPECT_TRUE(regions->run<apex_nodes::Image>(fruits).isNothing());
  EXPECT_EQ(regions->error(), "");

  // 300 classes: mono16.
  const cv::Size small(16, 12);
  const cv::Mat many = directMask(directForward("segment_300", fruits->mat, small), fruits->mat.size());
  double top = 0;
  cv::minMaxLoc(many, nullptr, &top);
  EXPECT_GT(top, 255) << "a class past 255 should win somewhere";
  auto h300 = dnn("segment", "segment_300", small, "mask");
  expectImage(*h300, h300->run<apex_nodes::Image>(fruits), many, "mono16");
}

TEST(DnnNetwork, AnOutputOfAnotherShapeIsRefusedNamingIt) {
  const auto messi = readDataImage("messi5.jpg");
  auto detect = dnn("detect", "classify", kDetectInput, "regions");
  expectNothing(*detect, detect->run<apex_nodes::Image>(messi),
                "the network's output is [1, 3]: task 'detect' needs [1, 1, N, 7], the rows of SSD's DetectionOutput");
  auto segment = dnn("segment", "detect", kDetectInput, "mask");
  expectNothing(*segment, segment->run<apex_nodes::Image>(messi),
                "the network's output is [1, 1, 9, 7]: task 'segment' needs [1, C, H, W], a score per class and pixel "
                "for 2 to 65536 classes");
  segment->set("model", network("classify"));
  expectNothing(*segment, segment->run<apex_nodes::Image>(messi), "the network's output is [1, 3]: task 'segment' needs");

  // The whole image only: a centre crop or regions are refused.
  detect->set("model", network("detect"));
  detect->set("crop", "true");
  expectNothing(*detect, detect->run<apex_nodes::Image>(messi),
                "task 'detect' maps its output back to the whole image, which crop would cut: set crop to false");
  detect->set("crop", "false");
  ASSERT_TRUE(detect->run<apex_nodes::Image>(messi).as<Regions>()) << detect->error();
  EXPECT_EQ(detect->error(), "");

  auto with_regions = dnn("detect", "detect", kDetectInput, "regions", {"image", "regions"});
  auto regions = std::make_shared<Regions>();
  regions->image_size = messi->mat.size();
  regions->regions.resize(1);
  expectNothing(*with_regions, with_regions->run({Message::share<apex_nodes::Image>(messi), Message::share<Regions>(regions)}),
                "task 'detect' runs on the whole image: disconnect 'regions'");
}

}  // namespace
