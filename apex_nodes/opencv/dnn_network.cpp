// DnnNetwork: runs a network OpenCV's dnn module reads (cv::dnn::readNet tells the format by the
// files' extensions: ONNX .onnx, Caffe .caffemodel with its .prototxt, TensorFlow .pb with an
// optional .pbtxt, Darknet .weights with its .cfg) and reads its output as the task says:
// - classify: each region's crop, or the whole image, runs through the network alone, so that a
//   network whose batch is fixed at one takes it too. The label is the index of the crop's largest
//   output, the confidence that value: a probability when the network ends in a softmax.
// - detect: the whole image runs once; the output is SSD's DetectionOutput rows, made boxes of the
//   image with non-maximum suppression per class (dnn_outputs.hpp).
// - segment: the whole image runs once; the output is a score per class and pixel, made a mask of
//   class indices the image's size (dnn_outputs.hpp).
// Each becomes a blob as blobFromImage makes it (resized to the input size, the mean subtracted,
// scaled). Detect and segment take no regions and no centre crop: their output is mapped back to
// the whole image, which a crop would not cover.
// The network is read when first needed, and again when the file changes or a parameter it is read
// with is set (ModelFile); a missing or unreadable file is an error naming it.

#include <algorithm>
#include <memory>
#include <opencv2/dnn.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/model_file.hpp"
#include "dnn_outputs.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** A network as read from its files, set to run on a backend and target. */
struct DnnModel {
  mutable cv::dnn::Net net;  // a run changes its buffers, not what was read

  static DnnModel read(const std::string& model, const std::string& config, cv::dnn::Backend backend, cv::dnn::Target target) {
    DnnModel m;
    try {
      m.net = cv::dnn::readNet(model, config);
    } catch (const cv::Exception& e) {
      throw std::invalid_argument("the model '" + model + "'" + (config.empty() ? "" : " (with '" + config + "')") +
                                  " cannot be read by OpenCV's dnn: " + e.err);
    }
    if (m.net.empty()) throw std::invalid_argument("the model '" + model + "' holds no network");
    m.net.setPreferableBackend(backend);
    m.net.setPreferableTarget(target);
    return m;
  }
};

/** The region a whole image is, for a node given no regions. */
Region wholeImage(const cv::Size& size) {
  Region r;
  r.box = cv::Rect(cv::Point(0, 0), size);
  r.area = size.area();
  r.centroid = cv::Point2d(size.width / 2.0, size.height / 2.0);
  return r;
}

}  // namespace

class DnnNetwork : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit or float pixels, of the channels the network takes"};
  static inline const apex::InputPort<Regions> kRegions{
      "regions", "classify: if connected, each region's crop is classified, else the whole image; detect, segment: none", true};
  static inline const apex::OutputPort<Regions> kLabelled{
      "regions",
      "classify: the regions (or one, the whole image) with label (the largest output's index; -1 below min_confidence "
      "or outside the image) and confidence (that output); detect: a region per box kept, in the image's pixels, label "
      "the class id, confidence the row's, the most confident first; segment: Nothing"};
  static inline const apex::OutputPort<Image> kOutput{
      "output",
      "the network's output, 32FC1: classify: a row per region (zeros for one outside the image), its values in order; "
      "detect: its N x 7 rows, all of them; segment: C x H rows of W, each class's scores in turn"};
  static inline const apex::OutputPort<Image> kMask{
      "mask",
      "segment: each pixel's class (the index of its largest score), mono8 (mono16 past 256 classes), resized to the "
      "image by nearest neighbour; Nothing in the other tasks"};
  enum class Task { kClassify, kDetect, kSegment };
  static inline const apex::ChoiceDecl<Task> kTask =
      param::choice<Task>(
          "task", {{"classify", Task::kClassify, "any output; sends a label per crop, or for the whole image, on regions"},
                   {"detect", Task::kDetect,
                    "the output [1, 1, N, 7] of SSD's DetectionOutput, rows of image_id, class_id, confidence, x1, y1, "
                    "x2, y2 (the corners relative to the input, 0..1); sends the boxes in the whole image above "
                    "min_confidence, after non-maximum suppression per class, on regions"},
                   {"segment", Task::kSegment,
                    "the output [1, C, H, W], a score per class and pixel (C from 2); sends each pixel's class on mask"}})
          .describe("what the network's output is");
  static inline const apex::ParamDecl<std::string> kModel =
      param::path("model")
          .describe("the network: .onnx, .caffemodel, .pb or .weights (readNet tells the format by the extension)")
          .mode(apex::PathMode::Read)
          .files({"*.onnx", "*.caffemodel", "*.pb", "*.weights"});
  static inline const apex::ParamDecl<std::string> kConfig =
      param::path("config")
          .describe("the model's description where its format has one: .prototxt (Caffe), .pbtxt (TensorFlow), .cfg (Darknet)")
          .mode(apex::PathMode::Read)
          .files({"*.prototxt", "*.pbtxt", "*.cfg"});
  static inline const apex::ParamDecl<int> kWidth =
      param::integer("input_width").range(1, 4096).init(224).describe("pixels: each crop is resized to the network's input");
  static inline const apex::ParamDecl<int> kHeight = param::integer("input_height").range(1, 4096).init(224).describe("pixels");
  static inline const apex::ParamDecl<std::vector<double>> kMean = param::list("mean").init({0, 0, 0}).describe(
      "subtracted from each channel, in the blob's channel order (after swap_rb), before scaling; up to 4 numbers");
  static inline const apex::ParamDecl<double> kScale =
      param::number("scale").range(0.0, 1000.0).step(0.0001).init(1.0).describe("each value times it (1/255: 0.00392157)");
  static inline const apex::ParamDecl<bool> kSwapRb =
      param::flag("swap_rb").describe("swap the first and third channels: BGR images for a network trained on RGB");
  static inline const apex::ParamDecl<bool> kCrop = param::flag("crop").describe(
      "classify: resize keeping the aspect ratio and cut out the middle; else (and always in detect, segment) stretch to "
      "the input size");
  static inline const apex::ChoiceDecl<cv::dnn::Backend> kBackend =
      param::choice<cv::dnn::Backend>(
          "backend", {{"opencv", cv::dnn::DNN_BACKEND_OPENCV,
                       "OpenCV's own layers, the one Debian's OpenCV has (built without CUDA, OpenVINO, Vulkan or Halide)"}})
          .describe("what runs the layers");
  static inline const apex::ChoiceDecl<cv::dnn::Target> kTarget =
      param::choice<cv::dnn::Target>(
          "target", {{"cpu", cv::dnn::DNN_TARGET_CPU},
                     {"opencl", cv::dnn::DNN_TARGET_OPENCL, "a GPU through OpenCL; OpenCV falls back to the CPU without one"},
                     {"opencl_fp16", cv::dnn::DNN_TARGET_OPENCL_FP16, "the same in half precision"}})
          .describe("the device");
  static inline const apex::ParamDecl<double> kMinConfidence =
      param::number("min_confidence")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.0)
          .describe("classify: a region whose largest output is less gets label -1; detect: a box is kept only above it");
  static inline const apex::ParamDecl<double> kNmsThreshold =
      param::number("nms_threshold")
          .range(0.0, 1.0)
          .step(0.01)
          .init(0.4)
          .describe("detect: a box overlapping a more confident one of its class by more (intersection over union) is dropped");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Classifies an image or each region's crop, detects boxes (SSD) or segments an image with a network "
               "OpenCV's dnn reads (ONNX, Caffe, TensorFlow, Darknet)")
        .inCategory("learning")
        .input(kImage)
        .input(kRegions)
        .output(kLabelled)
        .output(kOutput)
        .output(kMask)
        .param(kTask)
        .param(kModel)
        .param(kConfig)
        .param(kWidth)
        .param(kHeight)
        .param(kMean)
        .param(kScale)
        .param(kSwapRb)
        .param(kCrop)
        .param(kBackend)
        .param(kTarget)
        .param(kMinConfidence)
        .param(kNmsThreshold);
  }
  void parameterChanged(const std::string& name) override {
    for (const std::string& read_with : {kModel.name(), kConfig.name(), kBackend.name(), kTarget.name()})
      if (name == read_with) model_.forget();
  }
  void process() override {
    const Image& image = *image_.get();
    requireImage(image);
    if (image.mat.depth() != CV_8U && image.mat.depth() != CV_32F)
      throw std::invalid_argument("cannot run a network on '" + image.encoding +
                                  "' images: blobFromImage takes 8-bit or float pixels");
    if (mean_.get().size() > 4)
      throw std::invalid_argument("mean has " + std::to_string(mean_.get().size()) + " numbers: give one per channel, up to 4");
    const Task task = task_.get();
    if (task != Task::kClassify && regions_.has())
      throw std::invalid_argument("task '" + task_.text() +
                                  "' runs on the whole image: disconnect 'regions' (they are for classify)");
    if (task != Task::kClassify && crop_.get())
      throw std::invalid_argument("task '" + task_.text() +
                                  "' maps its output back to the whole image, which crop would cut: set crop to false");
    const DnnModel& model = load();
    switch (task) {  // every task a case: -Wswitch names one left out
      case Task::kClassify:
        return classify(image, model);
      case Task::kDetect:
        return detect(image, model);
      case Task::kSegment:
        return segment(image, model);
    }
  }

 private:
  /** Labels each region's crop, or the whole image, by its largest output. */
  void classify(const Image& image, const DnnModel& model) {
    auto out = std::make_shared<Regions>();
    if (const auto in = regions_.get()) {
      *out = *in;
    } else {
      out->header = image.header, out->image_size = image.mat.size();
      out->regions = {wholeImage(image.mat.size())};
    }
    const cv::Rect frame(0, 0, image.mat.cols, image.mat.rows);
    const int n = static_cast<int>(out->regions.size());
    cv::Mat rows;  // a row per region, sized at the first output
    for (int i = 0; i < n; ++i) {
      Region& r = out->regions[i];
      r.label = -1, r.confidence = 0;
      const cv::Rect box = r.box & frame;
      if (box.empty()) continue;
      const cv::Mat values = forward(model, image.mat(box)).reshape(1, 1);
      if (rows.empty()) rows = cv::Mat::zeros(n, values.cols, CV_32F);
      values.copyTo(rows.row(i));
      const float* v = values.ptr<float>();
      const int best = static_cast<int>(std::max_element(v, v + values.cols) - v);
      r.confidence = v[best];
      if (v[best] >= min_confidence_.get()) r.label = best;
    }
    if (!rows.empty()) output_.publish(resultOf(image, rows, "32FC1"));
    regions_out_.publish(std::move(out));
  }
  /** The boxes of the image's detections (detectionsOf), and the rows they came from. */
  void detect(const Image& image, const DnnModel& model) {
    const cv::Mat rows = forward(model, image.mat);
    auto out = std::make_shared<Regions>();
    out->header = image.header, out->image_size = image.mat.size();
    out->regions =
        detectionsOf(rows, image.mat.size(), static_cast<float>(min_confidence_.get()), static_cast<float>(nms_threshold_.get()));
    if (rows.size[2] > 0) output_.publish(resultOf(image, rows.reshape(1, rows.size[2]), "32FC1"));
    regions_out_.publish(std::move(out));
  }
  /** The image's class mask (classMask), and the scores it came from. */
  void segment(const Image& image, const DnnModel& model) {
    const cv::Mat scores = forward(model, image.mat);
    cv::Mat mask = classMask(scores, image.mat.size());
    const std::string encoding = mask.depth() == CV_8U ? "mono8" : "mono16";
    output_.publish(resultOf(image, scores.reshape(1, scores.size[1] * scores.size[2]), "32FC1"));
    mask_.publish(resultOf(image, std::move(mask), encoding));
  }
  /** The network's output for `pixels` (a crop or the whole image) as floats, in the output's own
   *  shape; a copy, as the next run reuses the net's buffers. */
  cv::Mat forward(const DnnModel& model, const cv::Mat& pixels) const {
    const std::vector<double>& m = mean_.get();
    cv::Scalar mean;
    for (std::size_t c = 0; c < m.size(); ++c) mean[static_cast<int>(c)] = m[c];
    const cv::Size size(width_.get(), height_.get());
    cv::Mat out;
    try {
      model.net.setInput(cv::dnn::blobFromImage(pixels, scale_.get(), size, mean, swap_rb_.get(), crop_.get()));
      out = model.net.forward();
    } catch (const cv::Exception& e) {
      throw std::invalid_argument("the network '" + model_path_.get() + "' cannot run on a " + std::to_string(pixels.cols) + "x" +
                                  std::to_string(pixels.rows) + " crop of " + std::to_string(pixels.channels()) +
                                  " channels at " + std::to_string(size.width) + "x" + std::to_string(size.height) + ": " +
                                  e.err);
    }
    cv::Mat values;
    out.convertTo(values, CV_32F);  // a copy, also when already float
    return values;
  }
  const DnnModel& load() {
    const std::string& path = model_path_.get();
    if (path.empty()) throw std::invalid_argument("no model: set 'model' to a network file (.onnx, .caffemodel, .pb, .weights)");
    bool fresh = false;
    const DnnModel& model = model_.get(
        path, [&](const std::string& p) { return DnnModel::read(p, config_.get(), backend_.get(), target_.get()); }, fresh);
    if (fresh) log(apex::LogLevel::Info, "loaded the network '" + path + "'");
    return model;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Regions> regions_out_{this, kLabelled};
  apex::Output<Image> output_{this, kOutput};
  apex::Output<Image> mask_{this, kMask};
  apex::Choice<Task> task_{this, kTask};
  apex::Param<std::string> model_path_{this, kModel};
  apex::Param<std::string> config_{this, kConfig};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
  apex::Param<std::vector<double>> mean_{this, kMean};
  apex::Param<double> scale_{this, kScale};
  apex::Param<bool> swap_rb_{this, kSwapRb};
  apex::Param<bool> crop_{this, kCrop};
  apex::Choice<cv::dnn::Backend> backend_{this, kBackend};
  apex::Choice<cv::dnn::Target> target_{this, kTarget};
  apex::Param<double> min_confidence_{this, kMinConfidence};
  apex::Param<double> nms_threshold_{this, kNmsThreshold};
  ModelFile<DnnModel> model_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::DnnNetwork, "apex_nodes/DnnNetwork");
