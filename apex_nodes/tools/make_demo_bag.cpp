// Writes the demo's bag: camera frames of dark number signs on textured
// backgrounds, seen by a camera mounted on its side (as in the paper's SICK
// Robot Day setup), and a point cloud per frame; plus the ground truth.
//   apex_make_demo_bag OUT.bag TRUTH.yaml [frames] [--frames N] [--seed N] [--difficulty easy|medium|hard]
//                      [--backgrounds synthetic|real]
// Each sign's digit is drawn in one of five fonts, with its own size, stroke, slant and turn
// (the truth lists the digits), so that reading it takes a trained classifier.
// Deterministic: the same files for the same options. Hard frames add uneven
// light, shadows, blur, noise, faint and partly hidden signs, and dark shapes
// that are not signs: data on which the shipped parameters do poorly and tuned
// ones do well. Medium frames are the easy scene as a robot's camera sees it: the same
// signs at full contrast, some partly hidden, among the dark shapes, with the light, blur
// and noise of hard frames (on photographs, faint signs are beyond any of our detectors). With --backgrounds real, each frame's
// background is a crop of one of opencv-doc's photographs (demo_backgrounds.hpp; $APEX_OPENCV_DATA overrides its folder) instead
// of the texture; the signs, digits and clouds stay those of the same seed's synthetic frames.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>
#include <cv_bridge/cv_bridge.h>
#include <rosbag/bag.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "demo_backgrounds.hpp"

namespace {

constexpr int kWidth = 640, kHeight = 480;  // the scene upright; the camera sees it turned
constexpr int kCameraRotation = 90;  // degrees clockwise: the recorded image is the scene turned

struct Options {
  std::string bag, truth;
  int frames = 40;
  std::uint64_t seed = 20261121;  // the demo's: its checks expect these exact frames
  enum class Difficulty { Easy, Medium, Hard } difficulty = Difficulty::Easy;
  bool real = false;  // backgrounds: opencv-doc's photographs instead of the generated texture
};

using apex_tools::number;

/** Two paths and an optional frame count, with options anywhere among them. */
Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> plain;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      plain.push_back(arg);
      continue;
    }
    std::string value;
    const auto eq = arg.find('=');  // --seed=7 as well as --seed 7
    if (eq != std::string::npos) value = arg.substr(eq + 1), arg.resize(eq);
    if (arg != "--seed" && arg != "--frames" && arg != "--difficulty" && arg != "--backgrounds")
      throw std::invalid_argument("unknown option '" + arg + "'");
    if (eq == std::string::npos) {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      value = argv[++i];
    }
    if (arg == "--seed") o.seed = number("--seed", value, 0, std::numeric_limits<std::uint64_t>::max());
    if (arg == "--frames") o.frames = static_cast<int>(number("--frames", value, 1, 100000));
    if (arg == "--difficulty") {
      if (value != "easy" && value != "medium" && value != "hard")
        throw std::invalid_argument("--difficulty is easy, medium or hard, not '" + value + "'");
      o.difficulty = value == "hard"     ? Options::Difficulty::Hard
                     : value == "medium" ? Options::Difficulty::Medium
                                         : Options::Difficulty::Easy;
    }
    if (arg == "--backgrounds") {
      if (value != "synthetic" && value != "real")
        throw std::invalid_argument("--backgrounds is synthetic or real, not '" + value + "'");
      o.real = value == "real";
    }
  }
  if (plain.size() < 2 || plain.size() > 3)
    throw std::invalid_argument("needs OUT.bag and TRUTH.yaml, and at most a frame count");
  o.bag = plain[0];
  o.truth = plain[1];
  if (plain.size() == 3) o.frames = static_cast<int>(number("the frame count", plain[2], 1, 100000));
  return o;
}

cv::Mat background(cv::RNG& rng) {
  cv::Mat bg(kHeight, kWidth, CV_8UC3);
  const int base = rng.uniform(150, 200);
  for (int y = 0; y < kHeight; ++y)  // a soft gradient ...
    bg.row(y).setTo(cv::Scalar(base + y / 12, base + y / 16, base + y / 10));
  cv::Mat noise(bg.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, -18, 18);  // ... some grain ...
  cv::add(bg, noise, bg, cv::noArray(), CV_8UC3);
  for (int i = 0; i < 12; ++i) {  // ... and a few light scratches
    const cv::Point a(rng.uniform(0, kWidth), rng.uniform(0, kHeight)), b(rng.uniform(0, kWidth), rng.uniform(0, kHeight));
    cv::line(bg, a, b, cv::Scalar::all(rng.uniform(200, 250)), 1, cv::LINE_AA);
  }
  return bg;
}

/** Up to `count` non-overlapping sign boxes, kept apart by a margin. */
std::vector<cv::Rect> placeSigns(cv::RNG& rng, int count) {
  std::vector<cv::Rect> boxes;
  for (int tries = 0; tries < 400 && static_cast<int>(boxes.size()) < count; ++tries) {
    const int w = rng.uniform(60, 110), h = rng.uniform(60, 110);
    const cv::Rect box(rng.uniform(20, kWidth - w - 20), rng.uniform(20, kHeight - h - 20), w, h);
    const cv::Rect grown(box.x - 25, box.y - 25, box.width + 50, box.height + 50);
    bool free = true;
    for (const auto& b : boxes) free &= (b & grown).empty();
    if (free) boxes.push_back(box);
  }
  return boxes;
}

/** How a sign's digit is drawn: from a random stream of its own (`style` in main), so that the
 *  signs, their digits and everything else in a frame are the same as without styles. */
struct GlyphStyle {
  int font;
  double height;  // of the sign's
  int stroke;  // pixels at a sign 80 pixels high
  double shear;  // slant: x moves by shear * (centre - y)
  double angle;  // degrees
};

GlyphStyle randomStyle(cv::RNG& style) {
  static const int kFonts[] = {cv::FONT_HERSHEY_SIMPLEX, cv::FONT_HERSHEY_DUPLEX, cv::FONT_HERSHEY_COMPLEX,
                               cv::FONT_HERSHEY_TRIPLEX, cv::FONT_HERSHEY_SCRIPT_SIMPLEX};
  GlyphStyle s;
  s.font = kFonts[style.uniform(0, 5)];
  s.height = style.uniform(0.5, 0.75);
  s.stroke = style.uniform(2, 6);
  s.shear = style.uniform(-0.25, 0.25);
  s.angle = style.uniform(-6.0, 6.0);
  return s;
}

/** The digit as a mask of the box's size (255: ink), slanted and turned about its centre, and
 *  kept 12% of the box away from every edge (the sign stays one dark blob around it). */
cv::Mat glyph(const cv::Size& box, int number, const GlyphStyle& s) {
  cv::Mat mask(box, CV_8U, cv::Scalar(0));
  const std::string text = std::to_string(number);
  const int stroke = std::max(1, cvRound(s.stroke * box.height / 80.0));
  const double scale = cv::getFontScaleFromHeight(s.font, cvRound(box.height * s.height), stroke);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, s.font, scale, stroke, &baseline);
  cv::putText(mask, text, {(box.width - size.width) / 2, (box.height + size.height) / 2}, s.font, scale, 255, stroke,
              cv::LINE_AA);
  const cv::Point2f centre(box.width / 2.f, box.height / 2.f);
  cv::Mat turn = cv::getRotationMatrix2D(centre, s.angle, 1.0);
  turn.at<double>(0, 1) += s.shear;
  turn.at<double>(0, 2) -= s.shear * centre.y;
  cv::warpAffine(mask, mask, turn, box);
  const int margin = cvRound(0.12 * std::min(box.width, box.height));
  const cv::Rect inside(margin, margin, box.width - 2 * margin, box.height - 2 * margin), ink = cv::boundingRect(mask);
  if (ink.empty() || (ink & inside) == ink) return mask;
  const double f = std::min(static_cast<double>(inside.width) / ink.width, static_cast<double>(inside.height) / ink.height);
  const cv::Point2d from(ink.x + ink.width / 2.0, ink.y + ink.height / 2.0), to(centre);
  const cv::Mat fit = (cv::Mat_<double>(2, 3) << f, 0, to.x - f * from.x, 0, f, to.y - f * from.y);
  cv::warpAffine(mask, mask, fit, box);
  return mask;
}

void drawNumber(cv::Mat& img, const cv::Rect& box, int number, const cv::Scalar& colour, cv::RNG& style) {
  const cv::Mat mask = glyph(box.size(), number, randomStyle(style));
  cv::Mat sign = img(box);
  for (int y = 0; y < sign.rows; ++y)
    for (int x = 0; x < sign.cols; ++x) {
      const double a = mask.at<uchar>(y, x) / 255.0;  // anti-aliased edges blend
      auto& p = sign.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) p[c] = cv::saturate_cast<uchar>(p[c] * (1 - a) + colour[c] * a);
    }
}

void drawSign(cv::Mat& img, const cv::Rect& box, int number, cv::RNG& rng, cv::RNG& style) {
  cv::rectangle(img, box, cv::Scalar::all(rng.uniform(15, 45)), cv::FILLED);
  drawNumber(img, box, number, cv::Scalar::all(235), style);
}

// ---- hard frames -------------------------------------------------------------------------

/** A sign only somewhat darker than the background around it, its number barely lighter. */
void drawFaintSign(cv::Mat& img, const cv::Rect& box, int number, cv::RNG& rng, cv::RNG& style) {
  const cv::Scalar around = cv::mean(img(box));
  cv::rectangle(img, box, around * rng.uniform(0.5, 0.78), cv::FILLED);
  drawNumber(img, box, number, around * rng.uniform(0.9, 1.1), style);
}

/** A light board in front of one side of the sign, reaching past it: 15-35% of the sign
 *  hidden, the truth box unchanged. */
void occlude(cv::Mat& img, const cv::Rect& box, cv::RNG& rng) {
  const int side = rng.uniform(0, 4);  // left, right, top, bottom
  const int across = cvRound((side < 2 ? box.width : box.height) * rng.uniform(0.15, 0.35));
  const int past = rng.uniform(10, 40);  // beyond the sign's edge
  cv::Rect hide;
  switch (side) {
    case 0:
      hide = {box.x - past, box.y - 8, past + across, box.height + 16};
      break;
    case 1:
      hide = {box.br().x - across, box.y - 8, across + past, box.height + 16};
      break;
    case 2:
      hide = {box.x - 8, box.y - past, box.width + 16, past + across};
      break;
    default:
      hide = {box.x - 8, box.br().y - across, box.width + 16, across + past};
      break;
  }
  cv::rectangle(img, hide, cv::Scalar::all(rng.uniform(170, 230)), cv::FILLED);
}

/** Draws `shape(mask, grow)` into `mask` if, drawn grown by `gap`, it stays clear of `taken`
 *  (the signs and the shapes so far, grown the same): distractors that no kernel up to
 *  about `gap` can join to a sign or to each other, so that good parameters can reject each. */
template <typename Shape>
void placeApart(cv::Mat& mask, cv::Mat& taken, int gap, const Shape& shape) {
  cv::Mat grown(mask.size(), CV_8U, cv::Scalar(0));
  shape(grown, gap);
  if (cv::countNonZero(grown & taken)) return;
  taken |= grown;
  shape(mask, 0);
}

/** Dark things that are not signs: long strokes (a cable, a crack) and round spots (dirt, bolts). */
void drawDistractors(cv::Mat& img, const std::vector<cv::Rect>& boxes, cv::RNG& rng) {
  constexpr int kGap = 12;  // any two dark things stay twice this apart
  cv::Mat mask(img.size(), CV_8U, cv::Scalar(0)), taken = mask.clone();
  for (const auto& b : boxes)
    cv::rectangle(taken, cv::Rect(b.x - kGap, b.y - kGap, b.width + 2 * kGap, b.height + 2 * kGap), 255, cv::FILLED);
  const int strokes = rng.uniform(2, 6);
  for (int i = 0; i < strokes; ++i) {
    const cv::Point a(rng.uniform(0, kWidth), rng.uniform(0, kHeight));
    const double angle = rng.uniform(0.0, CV_PI), length = rng.uniform(150.0, 350.0);
    const cv::Point b(a.x + cvRound(length * std::cos(angle)), a.y + cvRound(length * std::sin(angle)));
    const int thickness = rng.uniform(3, 7);
    placeApart(mask, taken, kGap, [&](cv::Mat& m, int grow) { cv::line(m, a, b, 255, thickness + 2 * grow, cv::LINE_AA); });
  }
  const int spots = rng.uniform(4, 14);
  for (int i = 0; i < spots; ++i) {
    const cv::Point c(rng.uniform(0, kWidth), rng.uniform(0, kHeight));
    const int r = rng.uniform(4, 24);
    placeApart(mask, taken, kGap, [&](cv::Mat& m, int grow) { cv::circle(m, c, r + grow, 255, cv::FILLED, cv::LINE_AA); });
  }
  cv::Mat dark = img * rng.uniform(0.35, 0.6);
  dark.copyTo(img, mask);
}

/** Light falling unevenly: a strong gradient across the scene and a few soft dark shadows. */
cv::Mat lighting(cv::RNG& rng) {
  const double angle = rng.uniform(0.0, 2 * CV_PI), dim = rng.uniform(0.4, 0.6), bright = rng.uniform(1.0, 1.15);
  const double dx = std::cos(angle), dy = std::sin(angle);
  const double lo = std::min(0.0, dx * kWidth) + std::min(0.0, dy * kHeight);
  const double hi = std::max(0.0, dx * kWidth) + std::max(0.0, dy * kHeight);
  cv::Mat light(kHeight, kWidth, CV_32F);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      light.at<float>(y, x) = static_cast<float>(dim + (bright - dim) * ((dx * x + dy * y - lo) / (hi - lo)));
  cv::Mat shade(light.size(), CV_32F, cv::Scalar(1.0));
  const int shadows = rng.uniform(1, 4);
  for (int i = 0; i < shadows; ++i) {
    const cv::Point centre(rng.uniform(0, kWidth), rng.uniform(0, kHeight));
    const cv::Size axes(rng.uniform(50, 170), rng.uniform(40, 140));
    cv::ellipse(shade, centre, axes, rng.uniform(0.0, 180.0), 0, 360, cv::Scalar(rng.uniform(0.4, 0.65)), cv::FILLED);
  }
  cv::GaussianBlur(shade, shade, cv::Size(), rng.uniform(12.0, 30.0));  // soft edges, some softer than others
  return light.mul(shade);
}

/** What the camera makes of the scene: uneven light, defocus, sensor noise. */
void photograph(cv::Mat& scene, cv::RNG& rng) {
  cv::Mat light, f;
  cv::cvtColor(lighting(rng), light, cv::COLOR_GRAY2BGR);
  scene.convertTo(f, CV_32FC3);
  f = f.mul(light);
  cv::GaussianBlur(f, f, cv::Size(), rng.uniform(1.0, 2.2));
  cv::Mat noise(f.size(), CV_32FC3);
  rng.fill(noise, cv::RNG::NORMAL, 0, rng.uniform(3.0, 6.0));
  f += noise;
  f.convertTo(scene, CV_8UC3);
}

/** A hard frame's signs drawn faint (medium: as easy frames draw them), some partly hidden,
 *  among distractors, photographed badly. */
void drawHardFrame(cv::Mat& scene, const std::vector<cv::Rect>& boxes, const std::vector<int>& numbers, bool faint, cv::RNG& rng,
                   cv::RNG& style) {
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (faint) drawFaintSign(scene, boxes[i], numbers[i], rng, style);
    else drawSign(scene, boxes[i], numbers[i], rng, style);
  }
  for (const auto& b : boxes)
    if (rng.uniform(0.0, 1.0) < 0.3) occlude(scene, b, rng);
  drawDistractors(scene, boxes, rng);
  photograph(scene, rng);
}

/** A floor plane, two boxes standing on it, and far clutter beyond 3 m. */
sensor_msgs::PointCloud2 cloud(cv::RNG& rng, const std_msgs::Header& header) {
  pcl::PointCloud<pcl::PointXYZ> c;
  for (int i = 0; i < 12000; ++i)
    c.push_back(pcl::PointXYZ(rng.uniform(-2.f, 2.f), 0.8f + rng.gaussian(0.005), rng.uniform(0.3f, 5.f)));
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 3000; ++i)
      c.push_back(
          pcl::PointXYZ(-0.8f + 1.2f * b + rng.uniform(0.f, 0.4f), rng.uniform(0.4f, 0.8f), 1.5f + rng.uniform(0.f, 0.4f)));
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(c, msg);
  msg.header = header;
  return msg;
}

/** The frame's background. The texture is drawn from `rng` even when a photo replaces it, so
 *  that `rng` goes on as for synthetic frames: the same seed gives the same signs, digits and
 *  clouds on either kind. With `photos`, a crop of one (from `crops`), and `where` says which. */
cv::Mat frameBackground(cv::RNG& rng, cv::RNG& crops, const std::vector<apex_tools::BackgroundPhoto>& photos,
                        std::string& where) {
  cv::Mat scene = background(rng);
  if (photos.empty()) return scene;
  const apex_tools::BackgroundCrop crop = apex_tools::pickCrop(photos, scene.size(), crops);
  photos[crop.photo].image(crop.rect).copyTo(scene);
  where = "photo: " + photos[crop.photo].name + ", x: " + std::to_string(crop.rect.x) + ", y: " + std::to_string(crop.rect.y);
  return scene;
}

const char* difficultyName(const Options& opt) {
  switch (opt.difficulty) {
    case Options::Difficulty::Hard:
      return "hard";
    case Options::Difficulty::Medium:
      return "medium";
    default:
      return "easy";
  }
}

void writeTruthHeader(std::ostream& truth, const Options& opt) {
  truth << "# ground truth of " << opt.bag << ": per image frame, the signs in the upright scene\n"
        << "image_topic: /camera/image_raw\ncloud_topic: /camera/points\n"
        << "scene_size: [" << kWidth << ", " << kHeight << "]\ncamera_rotation: " << kCameraRotation << "\n"
        << "difficulty: " << difficultyName(opt) << "\n"
        << (opt.real ? "backgrounds: real\n" : "") << "seed: " << opt.seed << "\nframes:\n";
}

/** A frame's line: its signs' boxes and digits, and (real backgrounds) where its background was
 *  cut, in the photo as scaled (demo_backgrounds.hpp). */
void writeFrameTruth(std::ostream& truth, const ros::Time& stamp, const std::vector<cv::Rect>& boxes,
                     const std::vector<int>& numbers, const std::string& where) {
  truth << "  - {stamp: " << stamp.toNSec() << ", signs: " << boxes.size() << ", boxes: [";
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const auto& b = boxes[i];
    truth << (i ? ", " : "") << "[" << b.x << ", " << b.y << ", " << b.width << ", " << b.height << "]";
  }
  truth << "], digits: [";  // the number on each sign, in the order of the boxes
  for (std::size_t i = 0; i < numbers.size(); ++i) truth << (i ? ", " : "") << numbers[i];
  truth << "]";
  if (!where.empty()) truth << ", background: {" << where << "}";
  truth << "}\n";
}

/** The background photos when `opt` asks for them (none otherwise); read before any file is
 *  written, so that a missing one leaves no bag. Throws std::runtime_error naming the file. */
std::vector<apex_tools::BackgroundPhoto> photosFor(const Options& opt) {
  if (!opt.real) return {};
  return apex_tools::loadBackgroundPhotos(apex_tools::opencvDataDir(), {kWidth, kHeight});
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  std::vector<apex_tools::BackgroundPhoto> photos;
  try {
    opt = parse(argc, argv);
  } catch (const std::invalid_argument& e) {
    std::cerr << "apex_make_demo_bag: " << e.what()
              << "\nusage: apex_make_demo_bag OUT.bag TRUTH.yaml [frames] [--frames N] [--seed N] [--difficulty easy|medium|hard]"
                 " [--backgrounds synthetic|real]\n";
    return 2;
  }
  try {
    photos = photosFor(opt);
  } catch (const std::runtime_error& e) {
    std::cerr << "apex_make_demo_bag: " << e.what() << "\n";
    return 1;
  }
  cv::RNG rng(opt.seed);
  cv::RNG style(opt.seed * 2654435761ULL + 12345);  // the digits' fonts, sizes, slants: a stream apart
  cv::RNG crops(opt.seed * 0x9E3779B97F4A7C15ULL + 777);  // which photo, where: a stream apart too
  rosbag::Bag bag;
  try {
    bag.open(opt.bag, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    std::cerr << "apex_make_demo_bag: cannot write '" << opt.bag << "': " << e.what() << "\n";
    return 1;
  }
  std::ofstream truth(opt.truth);
  writeTruthHeader(truth, opt);
  const ros::Time start(1700000000, 0);
  const bool easy = opt.difficulty == Options::Difficulty::Easy;
  for (int f = 0; f < opt.frames; ++f) {
    std_msgs::Header header;
    header.seq = f;
    header.stamp = start + ros::Duration(0.1 * f);
    header.frame_id = "camera";
    std::string where;
    cv::Mat scene = frameBackground(rng, crops, photos, where);
    const auto boxes = placeSigns(rng, 1 + f % 4);
    std::vector<int> numbers;
    for (const auto& b : boxes) {
      numbers.push_back(rng.uniform(0, 10));
      if (easy) drawSign(scene, b, numbers.back(), rng, style);  // easy: the RNG calls the demo's checks rely on
    }
    writeFrameTruth(truth, header.stamp, boxes, numbers, where);
    if (!easy) drawHardFrame(scene, boxes, numbers, opt.difficulty == Options::Difficulty::Hard, rng, style);
    cv::Mat seen;
    cv::rotate(scene, seen, cv::ROTATE_90_CLOCKWISE);  // the camera lies on its side
    bag.write("/camera/image_raw", header.stamp, cv_bridge::CvImage(header, "bgr8", seen).toImageMsg());
    std_msgs::Header cloud_header = header;
    cloud_header.stamp += ros::Duration(0.005);  // the depth sensor, 5 ms later: one frame in a 20 ms sync window
    bag.write("/camera/points", cloud_header.stamp, cloud(rng, cloud_header));
  }
  bag.close();
  std::cout << "wrote " << opt.frames << (easy ? "" : std::string(" ") + difficultyName(opt)) << " frames"
            << (opt.real ? " on photographs" : "") << " to " << opt.bag << " and the ground truth to " << opt.truth << "\n";
  return truth ? 0 : 1;
}
