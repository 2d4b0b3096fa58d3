// Ground truth from labelling tools' files (loadTruth): the same three frames written as
// apex_make_demo_bag's YAML, COCO, Pascal VOC, YOLO and labelme read as the same Truth, and score
// the same in RegionScore; a bad file of each kind is refused naming the file and the place.
#include <gmock/gmock.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <tuple>

#include "apex_nodes/truth.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::loadTruth;
using apex_nodes::Truth;
using ::testing::AllOf;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

const cv::Size kImage(320, 240);

struct Sign {
  cv::Rect box;
  std::string label;
};
struct Frame {
  std::string stamp;  // as in the image's name: seconds.nanoseconds
  std::uint64_t ns;
  std::vector<Sign> signs;
  std::string image() const { return "frame_" + stamp + ".png"; }
};

/** Two signs, one sign, none. */
const std::vector<Frame> kFrames{
    {"1700000000.100000000", 1700000000100000000, {{{20, 30, 80, 90}, "3"}, {{200, 100, 80, 90}, "7"}}},
    {"1700000000.200000000", 1700000000200000000, {{{40, 60, 64, 72}, "5"}}},
    {"1700000000.300000000", 1700000000300000000, {}}};

/** This run's files: under the test's temporary folder, removed at the end. */
fs::path root() { return fs::path(::testing::TempDir()) / ("apex_truth_formats_" + std::to_string(::getpid())); }

struct RemoveFiles : ::testing::Environment {
  void TearDown() override { fs::remove_all(root()); }
};
const auto* const kRemoveFiles = ::testing::AddGlobalTestEnvironment(new RemoveFiles);

/** A fresh folder for one test's files. */
fs::path folder(const std::string& name) {
  static int count = 0;
  const fs::path dir = root() / std::to_string(++count) / name;
  fs::create_directories(dir);
  return dir;
}

fs::path write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/** `text` with its first `from` replaced by `to`. */
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string box4(const cv::Rect& b) {
  return std::to_string(b.x) + ", " + std::to_string(b.y) + ", " + std::to_string(b.width) + ", " + std::to_string(b.height);
}

// ------------------------------------------------------------------ the five writers

fs::path writeDemoYaml(const std::vector<Frame>& frames) {
  std::string text = "frames:\n";
  for (const auto& f : frames) {
    std::string boxes, digits;
    for (const auto& s : f.signs) {
      boxes += std::string(boxes.empty() ? "" : ", ") + "[" + box4(s.box) + "]";
      digits += (digits.empty() ? "" : ", ") + s.label;
    }
    text += "  - {stamp: " + std::to_string(f.ns) + ", signs: " + std::to_string(f.signs.size()) + ", boxes: [" + boxes +
            "], digits: [" + digits + "]}\n";
  }
  return write(folder("yaml") / "truth.yaml", text);
}

/** Categories named "0".."9" with ids 10..19, so that an id is not its name. */
fs::path writeCoco(const std::vector<Frame>& frames) {
  std::string images, annotations, categories;
  int id = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    images += std::string(i ? ",\n" : "") + "    {\"id\": " + std::to_string(i + 1) + ", \"file_name\": \"" + frames[i].image() +
              "\", \"width\": 320, \"height\": 240}";
    for (const auto& s : frames[i].signs)
      annotations += std::string(annotations.empty() ? "" : ",\n") + "    {\"id\": " + std::to_string(++id) +
                     ", \"image_id\": " + std::to_string(i + 1) +
                     ", \"category_id\": " + std::to_string(10 + std::stoi(s.label)) + ", \"bbox\": [" + box4(s.box) +
                     ".0], \"area\": 1, \"iscrowd\": 0}";
  }
  for (int d = 0; d < 10; ++d)
    categories += std::string(d ? ", " : "") + "{\"id\": " + std::to_string(10 + d) + ", \"name\": \"" + std::to_string(d) +
                  "\", \"supercategory\": \"sign\"}";
  return write(folder("coco") / "instances.json", "{\n\t\"info\": {\"description\": \"signs \\/ test\"},\n  \"images\": [\n" +
                                                      images + "\n  ],\n  \"annotations\": [\n" + annotations +
                                                      "\n  ],\n  \"categories\": [" + categories + "]\n}\n");
}

std::string vocXml(const Frame& f) {
  std::string objects;
  for (const auto& s : f.signs)
    objects += "  <object>\n    <name>" + s.label + "</name>\n    <pose>Unspecified</pose>\n    <bndbox>\n      <xmin>" +
               std::to_string(s.box.x) + "</xmin>\n      <ymin>" + std::to_string(s.box.y) + "</ymin>\n      <xmax>" +
               std::to_string(s.box.br().x) + "</xmax>\n      <ymax>" + std::to_string(s.box.br().y) +
               "</ymax>\n    </bndbox>\n  </object>\n";
  return "<annotation>\n  <folder>images</folder>\n  <filename>" + f.image() +
         "</filename>\n  <size><width>320</width><height>240</height><depth>3</depth></size>\n" + objects + "</annotation>\n";
}

fs::path writeVoc(const std::vector<Frame>& frames) {
  const fs::path dir = folder("voc");
  for (const auto& f : frames) write(dir / ("frame_" + f.stamp + ".xml"), vocXml(f));
  return dir;
}

/** Beside its image, with classes.txt naming the classes "9".."0" (class 0 is the digit 9). */
fs::path writeYolo(const std::vector<Frame>& frames) {
  const fs::path dir = folder("yolo");
  write(dir / "classes.txt", "9\n8\n7\n6\n5\n4\n3\n2\n1\n0\n");
  for (const auto& f : frames) {
    cv::imwrite((dir / f.image()).string(), cv::Mat(kImage, CV_8UC3, cv::Scalar(90, 120, 150)));
    std::ostringstream lines;
    for (const auto& s : f.signs)
      lines << 9 - std::stoi(s.label) << " " << (s.box.x + s.box.width / 2.0) / kImage.width << " "
            << (s.box.y + s.box.height / 2.0) / kImage.height << " " << double(s.box.width) / kImage.width << " "
            << double(s.box.height) / kImage.height << "\n";
    write(dir / ("frame_" + f.stamp + ".txt"), lines.str());
  }
  return dir;
}

std::string labelmeJson(const Frame& f) {
  std::string shapes;
  for (const auto& s : f.signs)
    shapes += std::string(shapes.empty() ? "" : ",\n") + "    {\"label\": \"" + s.label + "\", \"points\": [[" +
              std::to_string(s.box.br().x) + ".0, " + std::to_string(s.box.br().y) + ".0], [" + std::to_string(s.box.x) + ", " +
              std::to_string(s.box.y) +
              "]], \"group_id\": null, \"description\": \"\", \"shape_type\": \"rectangle\", \"flags\": {}}";
  return "{\n  \"version\": \"5.2.1\",\n  \"flags\": {},\n  \"shapes\": [\n" + shapes +
         "\n  ],\n  \"imagePath\": \"..\\\\images\\\\" + f.image() +
         "\",\n  \"imageData\": null,\n  \"imageHeight\": 240,\n  \"imageWidth\": 320\n}\n";
}

fs::path writeLabelme(const std::vector<Frame>& frames) {
  const fs::path dir = folder("labelme");
  for (const auto& f : frames) write(dir / ("frame_" + f.stamp + ".json"), labelmeJson(f));
  return dir;
}

// ------------------------------------------------------------------ comparing

using Boxes = std::map<std::uint64_t, std::vector<std::tuple<int, int, int, int, int>>>;

Boxes boxesOf(const Truth& t) {
  Boxes out;
  for (const auto& [stamp, signs] : t.frames) {
    auto& v = out[stamp];
    for (const auto& s : signs) v.emplace_back(s.box.x, s.box.y, s.box.width, s.box.height, s.digit);
  }
  return out;
}

Boxes expected() {
  Boxes out;
  for (const auto& f : kFrames) {
    auto& v = out[f.ns];
    for (const auto& s : f.signs) v.emplace_back(s.box.x, s.box.y, s.box.width, s.box.height, s.label[0] - '0');
  }
  return out;
}

std::string errorOf(const fs::path& path) {
  try {
    loadTruth(path.string());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

apex_nodes::Regions regions(std::uint64_t stamp_ns, std::vector<cv::Rect> boxes) {
  apex_nodes::Regions r;
  r.header.stamp.fromNSec(stamp_ns);
  r.image_size = kImage;
  for (const auto& b : boxes) r.regions.push_back({b, static_cast<double>(b.area()), {}});
  return r;
}

/** RegionScore's F1 for each frame of `found` against the truth at `truth`. */
std::vector<double> scores(const fs::path& truth, const std::vector<apex_nodes::Regions>& found) {
  NodeHarness h("apex_nodes/RegionScore", {"regions"}, "f1");
  h.set("truth", truth.string());
  std::vector<double> f1;
  for (const auto& r : found) {
    const Message m = h.run({Message::make(r)});
    f1.push_back(m.isNothing() ? -1 : *m.as<double>());
  }
  return f1;
}

const std::vector<fs::path>& allFormats() {
  static const std::vector<fs::path> paths{writeDemoYaml(kFrames), writeCoco(kFrames), writeVoc(kFrames), writeYolo(kFrames),
                                           writeLabelme(kFrames)};
  return paths;
}

}  // namespace

TEST(TruthFormats, EveryFormatGivesTheSameFramesBoxesAndDigits) {
  for (const auto& path : allFormats()) {
    SCOPED_TRACE(path.string());
    const Truth t = loadTruth(path.string());
    EXPECT_EQ(boxesOf(t), expected());
    EXPECT_TRUE(t.has_digits);
    EXPECT_TRUE(t.scene.empty());  // boxes in the image's frame
    EXPECT_EQ(t.rotation, 0);
  }
}

TEST(TruthFormats, RegionScoreScoresTheSameRegionsTheSameWithEveryFormat) {
  // frame 1: one sign found, one missed, one false region (F1 1/2); frame 2: found a little off
  // (F1 1); frame 3: a region where there is nothing (F1 0)
  const std::vector<apex_nodes::Regions> found{regions(kFrames[0].ns, {{22, 31, 80, 90}, {0, 0, 10, 10}}),
                                               regions(kFrames[1].ns + 300, {{42, 58, 64, 72}}),
                                               regions(kFrames[2].ns, {{5, 5, 20, 20}})};
  for (const auto& path : allFormats()) {
    SCOPED_TRACE(path.string());
    EXPECT_EQ(scores(path, found), (std::vector<double>{0.5, 1.0, 0.0}));
  }
}

TEST(TruthFormats, OnePerImageFileAloneIsItsFrame) {
  const fs::path voc = writeVoc(kFrames), yolo = writeYolo(kFrames), labelme = writeLabelme(kFrames);
  const Boxes all = expected();
  const Boxes first{*all.begin()};
  EXPECT_EQ(boxesOf(loadTruth((voc / ("frame_" + kFrames[0].stamp + ".xml")).string())), first);
  EXPECT_EQ(boxesOf(loadTruth((yolo / ("frame_" + kFrames[0].stamp + ".txt")).string())), first);
  EXPECT_EQ(boxesOf(loadTruth((labelme / ("frame_" + kFrames[0].stamp + ".json")).string())), first);
}

TEST(TruthFormats, ImagesNamedByNanosecondsAndLabelsThatAreNotDigits) {
  // a stamp in nanoseconds; "sign" is a sign without a digit, so the truth has no digits
  const Frame f{"", 1700000000250000000, {{{10, 20, 30, 40}, "sign"}, {{100, 100, 50, 50}, "4"}}};
  const std::string json = replaced(labelmeJson(f), "frame_.png", "1700000000250000000.png");
  const Truth t = loadTruth(write(folder("ns") / "labels.json", json).string());
  EXPECT_EQ(boxesOf(t), (Boxes{{f.ns, {{10, 20, 30, 40, -1}, {100, 100, 50, 50, 4}}}}));
  EXPECT_FALSE(t.has_digits);
  // seconds with fewer decimals, a .jpg
  const std::string xml = replaced(vocXml(f), "frame_.png", "cam_1700000000.25.jpg");
  EXPECT_EQ(boxesOf(loadTruth(write(folder("seconds") / "cam.xml", xml).string())), boxesOf(t));
  // YOLO without classes.txt: the class number is the label
  const fs::path dir = folder("yolo_numbers");
  cv::imwrite((dir / "1700000000250000000.png").string(), cv::Mat(kImage, CV_8U, cv::Scalar(0)));
  write(dir / "1700000000250000000.txt", "4 0.5 0.5 0.25 0.5\n");
  EXPECT_EQ(boxesOf(loadTruth(dir.string())), (Boxes{{f.ns, {{120, 60, 80, 120, 4}}}}));
}

TEST(TruthFormats, SampleExportNeedsADigitOnEverySign) {
  const Frame f{"", 1700000000250000000, {{{10, 20, 30, 40}, "sign"}}};
  const fs::path truth =
      write(folder("not_digits") / "labels.json", replaced(labelmeJson(f), "frame_.png", "1700000000250000000.png"));
  NodeHarness h("apex_nodes/SampleExport", {"image", "regions"}, "written");
  h.set("truth", truth.string());
  h.set("directory", folder("samples").string());
  auto image = std::make_shared<apex_nodes::Image>();
  image->header.stamp.fromNSec(f.ns);
  image->encoding = "bgr8";
  image->mat = cv::Mat(kImage, CV_8UC3, cv::Scalar(0));
  const Message written = h.run({Message::share<apex_nodes::Image>(image), Message::make(regions(f.ns, {{10, 20, 30, 40}}))});
  EXPECT_TRUE(written.isNothing());
  EXPECT_THAT(h.error(), AllOf(HasSubstr("'" + truth.string() + "'"), HasSubstr("labels must all be 0..9")));
}

// ------------------------------------------------------------------ errors name the file

TEST(TruthFormats, AMalformedFileOfEachFormatIsRefusedNamingTheFileAndThePlace) {
  const fs::path yaml = write(folder("bad") / "truth.yaml", "frames:\n  - {stamp: 1, boxes: [[1, 2, 3]]\n");
  EXPECT_THAT(errorOf(yaml), AllOf(HasSubstr("'" + yaml.string() + "'"), HasSubstr("line")));

  const std::string json = read(writeCoco(kFrames));
  const fs::path coco = write(folder("bad") / "coco.json", replaced(json, "[200, 100, 80, 90.0]", "[200, 100, 80]"));
  EXPECT_THAT(errorOf(coco), AllOf(HasSubstr("'" + coco.string() + "'"), HasSubstr("annotations[1].bbox")));
  const fs::path word = write(folder("bad") / "coco.json", replaced(json, "[200, 100, 80, 90.0]", "[200, \"a\", 80, 90]"));
  EXPECT_THAT(errorOf(word), HasSubstr("annotations[1].bbox: 'a' is not a number"));
  const fs::path cut = write(folder("bad") / "cut.json", json.substr(0, json.size() / 2));
  EXPECT_THAT(errorOf(cut), AllOf(HasSubstr("'" + cut.string() + "'"), HasSubstr("line")));

  const fs::path voc = write(folder("bad") / "frame.xml", replaced(vocXml(kFrames[0]), "</bndbox>", ""));
  EXPECT_THAT(errorOf(voc), AllOf(HasSubstr("'" + voc.string() + "'"), HasSubstr("line "), HasSubstr("not well-formed")));
  const fs::path voc_x = write(folder("bad") / "frame.xml", replaced(vocXml(kFrames[0]), "<xmax>", "<xmax>x"));
  EXPECT_THAT(errorOf(voc_x), AllOf(HasSubstr("'" + voc_x.string() + "'"), HasSubstr("line 11: <xmax> 'x100' is not a number")));

  const fs::path yolo = writeYolo(kFrames) / ("frame_" + kFrames[0].stamp + ".txt");
  write(yolo, "6 0.1 0.2 0.1 0.1\n2 0.5 0.5 0.2\n");
  EXPECT_THAT(errorOf(yolo.parent_path()), AllOf(HasSubstr("'" + yolo.string() + "'"), HasSubstr("line 2:")));
  write(yolo, "6 0.1 0.2 1.5 0.1\n");
  EXPECT_THAT(errorOf(yolo), HasSubstr("line 1: '6 0.1 0.2 1.5 0.1': the centre and size are fractions"));
  fs::remove(yolo.parent_path() / kFrames[0].image());
  write(yolo, "6 0.1 0.2 0.1 0.1\n");
  EXPECT_THAT(errorOf(yolo), HasSubstr("no image frame_" + kFrames[0].stamp + ".png"));

  const fs::path labelme = write(folder("bad") / "frame.json", replaced(labelmeJson(kFrames[1]), "rectangle", "circle"));
  EXPECT_THAT(errorOf(labelme), AllOf(HasSubstr("'" + labelme.string() + "'"), HasSubstr("shapes[0]: a circle")));
}

TEST(TruthFormats, ImagesNotNamedByStampAndMixedFoldersAreRefused) {
  Frame numbered = kFrames[0];
  numbered.stamp = "12";  // ImageExport's frame_12.png: a count, not a stamp
  const fs::path voc = writeVoc({numbered}) / "frame_12.xml";
  EXPECT_THAT(errorOf(voc), AllOf(HasSubstr("'" + voc.string() + "'"), HasSubstr("line 3: <filename>"),
                                  HasSubstr("'frame_12.png' holds no stamp")));
  const fs::path mixed = writeLabelme(kFrames);
  write(mixed / "frame_1700000000.4.xml", vocXml(kFrames[0]));
  EXPECT_THAT(errorOf(mixed), AllOf(HasSubstr("'" + mixed.string() + "'"), HasSubstr(".json and .xml files")));
  const fs::path twice = writeLabelme(kFrames);
  write(twice / "copy.json", labelmeJson(kFrames[2]));
  EXPECT_THAT(errorOf(twice), HasSubstr("a second image of the frame at 1700000000300000000 ns"));
  EXPECT_THAT(errorOf(folder("empty")), HasSubstr("a folder without labels"));
  const fs::path neither = write(folder("bad") / "other.json", "{\"name\": 1}");
  EXPECT_THAT(errorOf(neither), HasSubstr("neither COCO"));
}
