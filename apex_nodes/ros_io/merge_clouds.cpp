// MergeClouds: clouds from several sensors as one cloud in one frame, each moved by tf2 at its own
// stamp from the node's own buffer (TfListener, tf_listener.hpp, as TfLookup's); the merging itself
// is mergeClouds (cloud_transform.hpp).
#include <memory>

#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_transform.hpp"
#include "tf_listener.hpp"

namespace apex_nodes {
namespace param = apex::param;

class MergeClouds : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloud0{"cloud_0", "a cloud; the inputs are cloud_0, cloud_1, ..."};
  static inline const apex::InputPort<Cloud> kCloud1{"cloud_1"};
  static inline const apex::OutputPort<Cloud> kCloud{"cloud", "every input's points in `frame`, stamped as the newest input"};
  static inline const apex::ParamDecl<int> kInputs =
      param::integer("inputs").range(2, 8).step(1).init(2).describe("how many clouds: cloud_0, cloud_1, ...").shapesInterface();
  static inline const apex::ParamDecl<std::string> kFrame =
      param::text("frame").describe("the merged cloud's frame; empty: the inputs' own, which must be one");
  static inline const apex::ParamDecl<double> kTimeout = tfTimeoutParam("seconds to wait for each transform");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Merges clouds into one in `frame`, each moved by tf2 at its own stamp. Fields: all, if every input has "
               "the same; else those every input has (x, y, z always)")
        .inCategory("ROS I/O")
        .input(kCloud0)
        .input(kCloud1)
        .output(kCloud)
        .param(kInputs)
        .param(kFrame)
        .param(kTimeout)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          for (int i = 0; i < p.get<int>(kInputs.name()); ++i)
            m.input<Cloud>("cloud_" + std::to_string(i), i == 0 ? kCloud0.description : "");
          return apex::Status::ok();
        });
  }
  void setup() override {
    tf_ = std::make_unique<TfListener>(*this);
  }  // without ROS no transform arrives: clouds in `frame` only
  void process() override {
    std::vector<std::shared_ptr<const Cloud>> clouds;
    for (const auto& port : interface().inputs) clouds.push_back(input<Cloud>(port.name));
    const double timeout = timeout_.get();
    cloud_.publish(mergeClouds(
        clouds, frame_.get(),
        [&](const std::string& target, const std::string& source, const ros::Time& stamp) -> Eigen::Affine3f {
          tf_->waitFor(target, source, stamp, timeout);
          return toEigen(tf_->buffer().lookupTransform(target, source, stamp).transform);
        },
        points_.next()));
  }

 private:
  apex::Output<Cloud> cloud_{this, kCloud};
  apex::Param<std::string> frame_{this, kFrame};
  apex::Param<double> timeout_{this, kTimeout};
  std::unique_ptr<TfListener> tf_;  // from setup(): on the runtime's node handle
  Reused<Blob> points_;  // the merged points, refilled once nobody holds the last ones
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MergeClouds, "apex_nodes/MergeClouds");
