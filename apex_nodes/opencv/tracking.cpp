// Tracker: follows one object from frame to frame with one of OpenCV's single-object trackers
// (cv::TrackerKCF and cv::TrackerCSRT of the contrib tracking module, cv::TrackerMIL of the video
// module). It starts on a box — the first region of its `regions` input when a frame brings one (a
// detector's, on the frames it runs), else the parameters' x, y, width, height — and then moves the
// box each frame to where the object went, or says it lost it. Its region chains on: KalmanFilter
// smooths its path, DrawRegions draws it.
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"
#include "constant_velocity.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Tracker : public apex::Node {
 public:
  enum class Method { kKcf, kCsrt, kMil };
  static inline const apex::InputPort<Image> kImage{"image", "8-bit: bgr8, rgb8 or mono8; every frame of one size"};
  static inline const apex::InputPort<Regions> kStart{
      "regions", "if connected: a frame with a region (re)starts the tracker on the first one's box; a frame without tracks on",
      true};
  static inline const apex::OutputPort<Regions> kRegions{
      "regions", "the tracked box as one region (its middle the centroid, label -1); none when the object is lost"};
  static inline const apex::OutputPort<bool> kFound{"found", "whether the object was found in this frame"};
  static inline const apex::ChoiceDecl<Method> kMethod =
      param::choice<Method>(
          "method",
          {{"kcf", Method::kKcf, "kernelized correlation filters: fast; says when it loses the object"},
           {"csrt", Method::kCsrt, "correlation filters with channel and spatial reliability: slower, follows size changes"},
           {"mil", Method::kMil, "multiple instance learning (video module): seldom says the object is lost"}})
          .describe("OpenCV's tracker");
  static inline const apex::ParamDecl<int> kX = param::integer("x").range(0, 10000).step(1).init(0).describe(
      "the start box's left edge, pixels (when no region starts it)");
  static inline const apex::ParamDecl<int> kY =
      param::integer("y").range(0, 10000).step(1).init(0).describe("the start box's top edge, pixels (when no region starts it)");
  static inline const apex::ParamDecl<int> kWidth = param::integer("width").range(1, 10000).step(1).init(64).describe("pixels");
  static inline const apex::ParamDecl<int> kHeight =
      param::integer("height").range(1, 10000).step(1).init(128).describe("pixels");
  static inline const apex::ParamDecl<int> kSeed =
      param::integer("seed")
          .range(0, 1000000000)
          .step(1)
          .init(1)
          .describe(
              "mil: set in OpenCV's random generator (cv::setRNGSeed) and C's (std::srand) before it starts, as it "
              "draws its features and samples from them: a start on the same frames gives the same track");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Follows one object from frame to frame (OpenCV's KCF, CSRT or MIL tracker): its box, or none when lost")
        .inCategory("motion")
        .keepsState("the tracker's model of its object: a re-run of the held frame tracks it from where it was last")
        .input(kImage)
        .input(kStart)
        .output(kRegions)
        .output(kFound)
        .param(kMethod)
        .param(kX)
        .param(kY)
        .param(kWidth)
        .param(kHeight)
        .param(kSeed)
        .slot("restart", &Tracker::restart, "starts again on the next frame, from the parameters' box");
  }
  /** Any parameter's change starts again from the parameters' box (a new method, a new box). */
  void parameterChanged(const std::string&) override { restart(); }
  /** A new pass of a sequence starts as the first did: each pass gives the same track. */
  void endOfSequence() override {
    tracker_.release();
    from_parameters_ = false;
    endSequence();
  }
  void restart() {
    tracker_.release();
    from_parameters_ = true;
  }

  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "13");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    if (tracker_ && in.mat.size() != size_) restart();  // another camera or size: the model no longer fits
    const cv::Mat frame = bgrOrGray(in);
    const auto start = start_.get();  // Nothing while unconnected; a detector's Regions, perhaps empty
    cv::Rect box;
    bool found = false;
    if (start && !start->regions.empty()) {
      box = begin(frame, start->regions.front().box, in);
      found = true;
    } else if (from_parameters_ || (!tracker_ && !start)) {
      box = begin(frame, cv::Rect(x_.get(), y_.get(), width_.get(), height_.get()), in);
      found = true;
    } else if (tracker_) {
      found = tracker_->update(frame, box);  // the box is left as it was when the object is lost
    }
    auto out = regions_buffer_.next();
    out->header = in.header;
    out->image_size = in.mat.size();
    out->regions.clear();
    if (found) {
      Region r;
      r.box = box;
      r.area = box.area();
      r.centroid = middleOf(box);
      out->regions.push_back(r);
    }
    regions_.publish(out);
    found_.publish(found);
  }

 private:
  /** Starts a new tracker on the part of `wanted` inside the frame; returns that box. */
  cv::Rect begin(const cv::Mat& frame, const cv::Rect& wanted, const Image& in) {
    const cv::Rect box = inside(wanted, in);
    if (method_.get() == Method::kMil) {
      cv::setRNGSeed(seed_.get());  // this thread's: MIL's sampler copies it
      std::srand(static_cast<unsigned>(seed_.get()));  // MIL's Haar features are drawn with rand()
    }
    cv::Ptr<cv::Tracker> tracker;
    switch (method_.get()) {
      case Method::kKcf:
        tracker = cv::TrackerKCF::create();
        break;
      case Method::kCsrt:
        tracker = cv::TrackerCSRT::create();
        break;
      case Method::kMil:
        tracker = cv::TrackerMIL::create();
        break;
    }
    tracker->init(frame, box);  // if it throws, the tracker before goes on
    tracker_ = tracker;
    size_ = frame.size();
    from_parameters_ = false;
    return box;
  }

  /** The part of `wanted` inside the image; refused when it leaves fewer than kMinSide pixels a side
   *  in it, or fewer than kMinSide beside it: a tracker learns its object against the background around. */
  static cv::Rect inside(const cv::Rect& wanted, const Image& in) {
    constexpr int kMinSide = 4;
    const cv::Rect box = wanted & cv::Rect(0, 0, in.mat.cols, in.mat.rows);
    const std::string words = "the box " + std::to_string(wanted.x) + "," + std::to_string(wanted.y) + " " +
                              std::to_string(wanted.width) + "x" + std::to_string(wanted.height);
    if (box.width < kMinSide || box.height < kMinSide)
      throw std::invalid_argument(words + " has less than 4x4 pixels in the image " + imageWords(in));
    if (box.width > in.mat.cols - kMinSide || box.height > in.mat.rows - kMinSide)
      throw std::invalid_argument(words + " leaves less than 4 pixels of the image " + imageWords(in) +
                                  " beside it: a tracker tells its object from the background around it");
    return box;
  }

  /** The frame as the trackers take it: its own pixels if bgr8 or gray, rgb8 made bgr (KCF's colour
   *  names read OpenCV's order). */
  cv::Mat bgrOrGray(const Image& in) {
    if (in.mat.channels() == 1 || in.encoding.rfind("rgb", 0) != 0) return in.mat;
    cv::cvtColor(in.mat, bgr_, cv::COLOR_RGB2BGR);
    return bgr_;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> start_{this, kStart};
  apex::Output<Regions> regions_{this, kRegions};
  apex::Output<bool> found_{this, kFound};
  apex::Choice<Method> method_{this, kMethod};
  apex::Param<int> x_{this, kX};
  apex::Param<int> y_{this, kY};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
  apex::Param<int> seed_{this, kSeed};
  cv::Ptr<cv::Tracker> tracker_;  // none until it starts, and after a restart
  cv::Size size_;  // the frames' it started on
  bool from_parameters_ = false;  // restart: the next frame starts from the parameters' box
  cv::Mat bgr_;  // an rgb8 frame made bgr, reused
  Reused<Regions> regions_buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Tracker, "apex_nodes/Tracker");
