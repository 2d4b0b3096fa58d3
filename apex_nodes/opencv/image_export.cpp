// ImageExport: writes images, or the crops of regions, to a directory (e.g. training samples).
#include <sys/stat.h>

#include <opencv2/imgcodecs.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"

namespace apex_nodes {
namespace param = apex::param;

class ImageExport : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image"};
  static inline const apex::InputPort<Regions> kRegions{"regions", "if connected: one file per region crop", true};
  static inline const apex::OutputPort<std::string> kPath{"path", "the last file written"};
  static inline const apex::ParamDecl<std::string> kDirectory =
      param::path("directory").init("/tmp/apex_export").mode(apex::PathMode::Directory);
  static inline const apex::ParamDecl<std::string> kPrefix =
      param::text("prefix").init("frame").describe("the start of each file's name").fileName();
  static inline const apex::ParamDecl<bool> kOverwrite =
      param::flag("overwrite").describe("replace files already there (another run's)");
  static apex::Manifest manifest() {
    return apex::Manifest("Writes each image, or each region's crop, as a PNG file")
        .inCategory("ROS I/O")
        .keepsState("the files it writes: a re-run writes the held frame again")
        .input(kImage)
        .input(kRegions)
        .output(kPath)
        .param(kDirectory)
        .param(kPrefix)
        .param(kOverwrite);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in);
    const std::string dir = directory_.get();
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw std::invalid_argument("directory '" + dir + "' does not exist");
    const std::string stem = dir + "/" + prefix_.get() + "_" + std::to_string(count_++);
    std::string last;
    if (auto regions = regions_.get()) {
      int i = 0;
      for (const auto& r : regions->regions)
        write(last = stem + "_" + std::to_string(i++) + ".png", in.mat(r.box & cv::Rect(0, 0, in.mat.cols, in.mat.rows)));
    } else {
      write(last = stem + ".png", in.mat);
    }
    path_.publish(last);
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<std::string> path_{this, kPath};
  apex::Param<std::string> directory_{this, kDirectory};
  apex::Param<std::string> prefix_{this, kPrefix};
  apex::Param<bool> overwrite_{this, kOverwrite};

  /** Numbers only grow, so a file already at `path` is never one of this node's: another run's,
   *  or the user's, replaced only with `overwrite`. */
  void write(const std::string& path, const cv::Mat& mat) {
    struct stat st {};
    if (!overwrite_.get() && ::lstat(path.c_str(), &st) == 0)
      throw std::runtime_error("'" + path + "' exists (not written by this node): left as it is; set 'overwrite' to " +
                               "replace such files, or choose another prefix or directory");
    if (!cv::imwrite(path, mat)) throw std::runtime_error("cannot write '" + path + "'");
  }
  int count_ = 0;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageExport, "apex_nodes/ImageExport");
