// OpenCV's object detectors as Regions: CascadeDetector (Haar/LBP), HOGPeopleDetector, QRCodeDetector.
#include <cmath>
#include <fstream>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
const char* const kCategory = "detection";

void require8Bit(const Image& in, const std::string& channels) {
  requireImage(in, channels);
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
}

/** The image in gray, by its encoding's channel order: its own pixels if it is (to read only),
 *  else converted into `scratch` (the node's, reused) and that returned. */
cv::Mat grayOf(const Image& in, cv::Mat& scratch) {
  if (in.mat.channels() == 1) return in.mat;
  const bool rgb = in.encoding.rfind("rgb", 0) == 0;
  if (in.mat.channels() == 4) cv::cvtColor(in.mat, scratch, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
  else cv::cvtColor(in.mat, scratch, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
  return scratch;
}

Region boxRegion(const cv::Rect& box, int label = -1, double confidence = 0) {
  Region r;
  r.box = box;
  r.area = box.area();
  r.centroid = cv::Point2d(box.x + (box.width - 1) / 2.0, box.y + (box.height - 1) / 2.0);
  r.label = label;
  r.confidence = confidence;
  return r;
}

std::shared_ptr<Regions> regionsOf(const Image& in) {
  auto out = std::make_shared<Regions>();
  out->header = in.header;
  out->image_size = in.mat.size();
  return out;
}

/** A size parameter as a cv::Size; negative values are refused, naming the parameter. */
cv::Size sizeOf(const apex::Pair& p, const std::string& name) {
  if (p.first < 0 || p.second < 0)
    throw std::invalid_argument(name + " [" + std::to_string(p.first) + ", " + std::to_string(p.second) + "] is negative");
  return cv::Size(cvRound(p.first), cvRound(p.second));
}
}  // namespace

class CascadeDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray, bgr8 or rgb8 (made gray)"};
  static inline const apex::OutputPort<Regions> kRegions{"regions", "one box per object (label -1, no confidence)"};
  static inline const apex::ParamDecl<std::string> kCascade =
      param::path("cascade")
          .init("/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml")
          .describe("a cascade classifier file (OpenCV's Haar or LBP XML; package opencv-data has some)");
  static inline const apex::ParamDecl<double> kScale =
      param::number("scale_factor").range(1.01, 3.0).step(0.01).init(1.1).describe("how much the image shrinks per scale");
  static inline const apex::ParamDecl<int> kNeighbors =
      param::integer("min_neighbors").range(0, 100).step(1).init(3).describe("overlapping hits an object needs");
  static inline const apex::ParamDecl<apex::Pair> kMinSize = param::pair("min_size").describe("width, height in pixels; 0: none");
  static inline const apex::ParamDecl<apex::Pair> kMaxSize = param::pair("max_size").describe("width, height in pixels; 0: none");
  static inline const apex::ParamDecl<bool> kEqualize =
      param::flag("equalize_hist").init(true).describe("equalise the gray image's histogram first (cv::equalizeHist)");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds objects (e.g. faces) with a Haar or LBP cascade classifier (cv::CascadeClassifier)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kRegions)
        .param(kCascade)
        .param(kScale)
        .param(kNeighbors)
        .param(kMinSize)
        .param(kMaxSize)
        .param(kEqualize);
  }
  void setup() override {
    if (!classifier_ && error_.empty()) load();  // unless a value set with the node was read already
  }
  void parameterChanged(const std::string& name) override {
    if (name == kCascade.name()) load();  // a bad file is an error now, and at every frame until a good one is set
  }
  void process() override {
    if (!error_.empty()) throw std::invalid_argument(error_);
    if (!classifier_) load();
    const Image& in = *image_.get();
    require8Bit(in, "134");
    cv::Mat gray = grayOf(in, gray_);
    if (equalize_.get()) {
      cv::equalizeHist(gray, equalized_);  // not into gray: it may be the frame's own pixels
      gray = equalized_;
    }
    std::vector<cv::Rect> found;
    classifier_->detectMultiScale(gray, found, scale_.get(), neighbors_.get(), 0, sizeOf(min_size_.get(), kMinSize.name()),
                                  sizeOf(max_size_.get(), kMaxSize.name()));
    auto out = regionsOf(in);
    for (const auto& box : found) out->regions.push_back(boxRegion(box));
    regions_.publish(std::move(out));
  }

 private:
  void load() {
    const std::string& path = cascade_.get();
    classifier_.reset();
    error_.clear();
    if (path.empty()) error_ = "no cascade: set 'cascade' to a cascade classifier file (OpenCV's XML)";
    else if (!std::ifstream(path)) error_ = "cannot read the cascade '" + path + "'";
    if (error_.empty()) {
      auto classifier = std::make_unique<cv::CascadeClassifier>();
      bool ok = false;
      try {
        ok = classifier->load(path) && !classifier->empty();
      } catch (const cv::Exception&) {  // FileStorage's parse error: a damaged file
      }
      if (ok) classifier_ = std::move(classifier);
      else error_ = "the cascade '" + path + "' is not a cascade classifier OpenCV can read (Haar or LBP XML)";
    }
    if (!error_.empty()) throw std::invalid_argument(error_);
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Param<std::string> cascade_{this, kCascade};
  apex::Param<double> scale_{this, kScale};
  apex::Param<int> neighbors_{this, kNeighbors};
  apex::Param<apex::Pair> min_size_{this, kMinSize};
  apex::Param<apex::Pair> max_size_{this, kMaxSize};
  apex::Param<bool> equalize_{this, kEqualize};
  std::unique_ptr<cv::CascadeClassifier> classifier_;
  std::string error_;  // why the cascade set could not be read
  cv::Mat gray_, equalized_;  // a colour frame's gray, and the gray equalised: reused
};

class HOGPeopleDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour"};
  static inline const apex::OutputPort<Regions> kRegions{
      "regions", "one box per person (label 0), confidence 1 / (1 + e^-w) of the SVM's weight w: 0.5 at hit_threshold 0"};
  static inline const apex::ParamDecl<double> kHitThreshold =
      param::number("hit_threshold").range(-5.0, 5.0).step(0.05).init(0.0).describe("the SVM's margin a window needs");
  static inline const apex::ParamDecl<int> kWinStride =
      param::integer("win_stride").range(8, 64).step(8).init(8).describe("pixels between windows, both ways");
  static inline const apex::ParamDecl<int> kPadding =
      param::integer("padding").range(0, 64).step(8).init(0).describe("pixels added around the image, both ways");
  static inline const apex::ParamDecl<double> kScale =
      param::number("scale").range(1.01, 2.0).step(0.01).init(1.05).describe("how much the window grows per scale");
  static inline const apex::ParamDecl<int> kGroupThreshold =
      param::integer("group_threshold").range(0, 20).step(1).init(2).describe("overlapping hits a person needs");
  static inline const apex::ParamDecl<bool> kMeanShift = param::flag("use_meanshift_grouping");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds upright people (HOG with OpenCV's default people detector, 64x128 windows)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kRegions)
        .param(kHitThreshold)
        .param(kWinStride)
        .param(kPadding)
        .param(kScale)
        .param(kGroupThreshold)
        .param(kMeanShift);
  }
  HOGPeopleDetector() { hog_.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector()); }
  void process() override {
    const Image& in = *image_.get();
    require8Bit(in, "134");
    cv::Mat image = in.mat;
    if (image.channels() == 4) {  // HOG takes 1 or 3
      cv::cvtColor(in.mat, bgr_, cv::COLOR_BGRA2BGR);
      image = bgr_;
    }
    std::vector<cv::Rect> found;
    std::vector<double> weights;
    const cv::Size stride(win_stride_.get(), win_stride_.get()), padding(padding_.get(), padding_.get());
    hog_.detectMultiScale(image, found, weights, hit_threshold_.get(), stride, padding, scale_.get(), group_threshold_.get(),
                          mean_shift_.get());
    auto out = regionsOf(in);
    for (std::size_t i = 0; i < found.size(); ++i)
      out->regions.push_back(boxRegion(found[i], 0, i < weights.size() ? 1 / (1 + std::exp(-weights[i])) : 0.0));
    regions_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Param<double> hit_threshold_{this, kHitThreshold};
  apex::Param<int> win_stride_{this, kWinStride};
  apex::Param<int> padding_{this, kPadding};
  apex::Param<double> scale_{this, kScale};
  apex::Param<int> group_threshold_{this, kGroupThreshold};
  apex::Param<bool> mean_shift_{this, kMeanShift};
  cv::HOGDescriptor hog_;
  cv::Mat bgr_;  // a 4-channel frame without its alpha, reused
};

class QRCodeDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit gray or colour"};
  static inline const apex::OutputPort<Regions> kRegions{"regions", "the code's box, if one is found (label -1)"};
  static inline const apex::OutputPort<std::string> kText{
      "text", "what the code says; empty if none is found, it cannot be read, or OpenCV was built without a decoder"};
  static apex::Manifest manifest() {
    return apex::Manifest("Finds a QR code and reads it (cv::QRCodeDetector::detectAndDecode)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kRegions)
        .output(kText);
  }
  void setup() override {
    if (!canDecode())
      log(apex::LogLevel::Warn, "this OpenCV was built without QR decoding (quirc): codes are found, 'text' stays empty");
  }
  void process() override {
    const Image& in = *image_.get();
    require8Bit(in, "134");
    const cv::Mat gray = grayOf(in, gray_);
    std::vector<cv::Point2f> corners;
    std::string text;
    if (canDecode()) text = detector_.detectAndDecode(gray, corners);
    else detector_.detect(gray, corners);  // decoding would only print that it cannot, every frame
    auto out = regionsOf(in);
    if (corners.size() == 4) {
      Region r = boxRegion(cv::boundingRect(corners));
      r.area = cv::contourArea(corners);
      r.centroid = (cv::Point2d(corners[0]) + cv::Point2d(corners[1]) + cv::Point2d(corners[2]) + cv::Point2d(corners[3])) / 4;
      out->regions.push_back(r);
    }
    regions_.publish(std::move(out));
    text_.publish(std::move(text));
  }

 private:
  /** Whether this OpenCV decodes QR codes (Debian's is built without quirc): one code it made, read back. */
  static bool canDecode() {
    static const bool yes = [] {
      try {
        cv::Mat code, big;
        cv::QRCodeEncoder::create()->encode("apex", code);
        cv::resize(code, big, cv::Size(), 8, 8, cv::INTER_NEAREST);
        cv::copyMakeBorder(big, big, 32, 32, 32, 32, cv::BORDER_CONSTANT, cv::Scalar(255));
        return cv::QRCodeDetector().detectAndDecode(big) == "apex";
      } catch (const cv::Exception&) {
        return false;
      }
    }();
    return yes;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Output<std::string> text_{this, kText};
  cv::QRCodeDetector detector_;
  cv::Mat gray_;  // a colour frame's gray, reused
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::CascadeDetector, "apex_nodes/CascadeDetector");
APEX_REGISTER_NODE(apex_nodes::HOGPeopleDetector, "apex_nodes/HOGPeopleDetector");
APEX_REGISTER_NODE(apex_nodes::QRCodeDetector, "apex_nodes/QRCodeDetector");
