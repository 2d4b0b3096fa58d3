// apex_bench_images' cases of DnnNetwork: the node against the calls it makes (blobFromImage, setInput,
// forward), on two networks the bench writes as ONNX with python3-onnx, having none to ship: a small
// convolutional classifier (3x64x64 in, Conv 8 3x3, Relu, MaxPool 2, Flatten, Gemm to 10, Softmax;
// weights from Python's random, seeded) and, for the task detect, 100 seeded random rows of SSD's
// DetectionOutput passed through a 3x300x300 network whatever the pixels (the decoding and NMSBoxes
// are what it measures beside the blob).
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "image_cases.hpp"

namespace apex_bench {
namespace {

using apex_nodes::Regions;

const char* const kScript = R"(
import random, sys
import onnx
from onnx import helper, TensorProto

rng = random.Random(11)


def weights(name, dims, sigma):
    n = 1
    for d in dims:
        n *= d
    return helper.make_tensor(name, TensorProto.FLOAT, dims, [rng.gauss(0.0, sigma) for _ in range(n)])


graph = helper.make_graph(
    [helper.make_node("Conv", ["image", "conv_w", "conv_b"], ["conv"], kernel_shape=[3, 3], pads=[1, 1, 1, 1]),
     helper.make_node("Relu", ["conv"], ["relu"]),
     helper.make_node("MaxPool", ["relu"], ["pool"], kernel_shape=[2, 2], strides=[2, 2]),
     helper.make_node("Flatten", ["pool"], ["flat"], axis=1),
     helper.make_node("Gemm", ["flat", "fc_w", "fc_b"], ["scores"], transB=1),
     helper.make_node("Softmax", ["scores"], ["probabilities"], axis=1)],
    "bench_classifier",
    [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3, 64, 64])],
    [helper.make_tensor_value_info("probabilities", TensorProto.FLOAT, [1, 10])],
    [weights("conv_w", [8, 3, 3, 3], 0.2), weights("conv_b", [8], 0.1),
     weights("fc_w", [10, 8 * 32 * 32], 0.01), weights("fc_b", [10], 0.1)])
model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
onnx.checker.check_model(model)
onnx.save(model, sys.argv[1])

# the detector: rows of image_id, class_id (1 to 3), confidence, x1, y1, x2, y2 (relative, 0..1)
boxes = random.Random(12)
rows = []
for _ in range(100):
    x, y = boxes.uniform(0.0, 0.8), boxes.uniform(0.0, 0.8)
    rows.append([0, boxes.randrange(1, 4), boxes.random(), x, y, x + boxes.uniform(0.05, 0.2), y + boxes.uniform(0.05, 0.2)])
graph = helper.make_graph(
    [helper.make_node("Slice", ["image", "starts", "ends"], ["corner"]),
     helper.make_node("Mul", ["corner", "zero"], ["nought"]),
     helper.make_node("Add", ["nought", "rows"], ["detections"])],
    "bench_detector",
    [helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3, 300, 300])],
    [helper.make_tensor_value_info("detections", TensorProto.FLOAT, [1, 1, len(rows), 7])],
    [helper.make_tensor("starts", TensorProto.INT64, [4], [0, 0, 0, 0]),
     helper.make_tensor("ends", TensorProto.INT64, [4], [1, 1, len(rows), 7]),
     helper.make_tensor("zero", TensorProto.FLOAT, [], [0.0]),
     helper.make_tensor("rows", TensorProto.FLOAT, [1, 1, len(rows), 7], [v for r in rows for v in r])])
model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
onnx.checker.check_model(model)
onnx.save(model, sys.argv[2])
)";

const std::string kClassifier = "/tmp/apex_bench_dnn.onnx", kDetector = "/tmp/apex_bench_dnn_detect.onnx";

/** Writes the networks' files (kClassifier, kDetector) by the script above; false if it could not. */
bool writeBenchNetworks() {
  const std::string script = "/tmp/apex_bench_dnn.py";
  std::ofstream(script) << kScript;
  const std::string command = "/usr/bin/python3 " + script + " " + kClassifier + " " + kDetector;
  return std::system(command.c_str()) == 0;
}

/** What DnnNetwork's task detect does after forward: the rows above 0.5 as boxes of an image of
 *  `size`, NMSBoxes 0.4 class by class, the most confident first. */
std::vector<apex_nodes::Region> detections(const cv::Mat& out, const cv::Size& size) {
  const cv::Mat rows = out.reshape(1, out.size[2]);
  std::map<int, std::vector<apex_nodes::Region>> by_class;
  for (int i = 0; i < rows.rows; ++i) {
    const float* d = rows.ptr<float>(i);
    if (!(d[2] > 0.5f)) continue;
    apex_nodes::Region r;
    r.box = cv::Rect(cv::Point(cvRound(d[3] * size.width), cvRound(d[4] * size.height)),
                     cv::Point(cvRound(d[5] * size.width), cvRound(d[6] * size.height))) &
            cv::Rect(cv::Point(), size);
    r.label = cvRound(d[1]), r.confidence = d[2];
    if (!r.box.empty()) by_class[r.label].push_back(r);
  }
  std::vector<apex_nodes::Region> kept;
  for (const auto& [label, regions] : by_class) {
    std::vector<cv::Rect> boxes;
    std::vector<float> scores;
    for (const auto& r : regions) boxes.push_back(r.box), scores.push_back(static_cast<float>(r.confidence));
    std::vector<int> keep;
    cv::dnn::NMSBoxes(boxes, scores, 0.5f, 0.4f, keep);
    for (int k : keep) kept.push_back(regions[k]);
  }
  std::stable_sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.confidence > b.confidence; });
  return kept;
}

/** The Otsu mask's blobs of 400 pixels or more, at most 16: the regions DnnNetwork classifies. */
std::shared_ptr<Regions> blobRegions(const Inputs& in) {
  auto regions = std::make_shared<Regions>();
  regions->header = in.bgr->header;
  regions->image_size = in.bgr->mat.size();
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(in.binary->mat, labels, stats, centroids);
  for (int i = 1; i < n && regions->regions.size() < 16; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < 400) continue;
    apex_nodes::Region r;
    r.box = cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3));
    regions->regions.push_back(r);
  }
  return regions;
}

}  // namespace

std::vector<NodeCase> dnnCases(const Inputs& in) {
  std::vector<NodeCase> c;
  if (!writeBenchNetworks()) {
    c.push_back(notMeasured("DnnNetwork", "bgr8", "blobFromImage; setInput, forward",
                            "python3-onnx cannot write the bench's network (scripts/install_deps)"));
    return c;
  }
  cv::dnn::Net net = cv::dnn::readNetFromONNX(kClassifier);  // the node's defaults: OpenCV's layers on the CPU
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  const Params params{
      {"model", kClassifier}, {"input_width", "64"}, {"input_height", "64"}, {"scale", num(1.0 / 255)}, {"swap_rb", "true"}};
  const std::string network = "a conv net 3x64x64 → 10 (ONNX, written here)";
  c.push_back(imageCase("DnnNetwork (whole image)", "apex_nodes/DnnNetwork", "bgr8; " + network, {in.bgr}, params, "regions",
                        sinkType<Regions>(), "blobFromImage 64x64, 1/255, RGB; setInput, forward",
                        [net, out = cv::Mat()](const cv::Mat& image) mutable {
                          net.setInput(cv::dnn::blobFromImage(image, 1.0 / 255, cv::Size(64, 64), cv::Scalar(), true, false));
                          out = net.forward();
                        }));
  const auto regions = blobRegions(in);
  const cv::Mat bgr = in.bgr->mat;
  c.push_back(fixedCase(
      "DnnNetwork (regions)", "apex_nodes/DnnNetwork",
      "bgr8, " + std::to_string(regions->regions.size()) + " Otsu blobs ≥ 400 px; " + network, feedType<Image, Regions>(),
      {"image", "regions"}, {msg(in.bgr), msg(regions)}, params, "regions", sinkType<Regions>(),
      "per region: blobFromImage 64x64, 1/255, RGB; setInput, forward", [net, bgr, regions, out = cv::Mat()]() mutable {
        for (const auto& r : regions->regions) {
          net.setInput(cv::dnn::blobFromImage(bgr(r.box), 1.0 / 255, cv::Size(64, 64), cv::Scalar(), true, false));
          out = net.forward();
        }
      }));
  cv::dnn::Net detector = cv::dnn::readNetFromONNX(kDetector);
  detector.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  detector.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  const Params detect{{"task", "detect"},        {"model", kDetector}, {"input_width", "300"},   {"input_height", "300"},
                      {"scale", num(1.0 / 255)}, {"swap_rb", "true"},  {"min_confidence", "0.5"}};
  c.push_back(
      imageCase("DnnNetwork (detect)", "apex_nodes/DnnNetwork", "bgr8; 100 SSD rows of 3 classes through a 3x300x300 network",
                {in.bgr}, detect, "regions", sinkType<Regions>(),
                "blobFromImage 300x300, 1/255, RGB; setInput, forward; rows > 0.5, NMSBoxes 0.4 per class",
                [detector, kept = std::vector<apex_nodes::Region>()](const cv::Mat& image) mutable {
                  detector.setInput(cv::dnn::blobFromImage(image, 1.0 / 255, cv::Size(300, 300), cv::Scalar(), true, false));
                  kept = detections(detector.forward(), image.size());
                }));
  return c;
}

}  // namespace apex_bench
