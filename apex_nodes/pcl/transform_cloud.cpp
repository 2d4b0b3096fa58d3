// TransformCloud: moves a cloud into another frame with a tf2 transform: x, y, z and the normals,
// if it has them; every other field as it was.
#include "apex/core/registry.hpp"
#include "apex_nodes/cloud_transform.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

class TransformCloud : public apex::Node {
 public:
  static inline const apex::InputPort<Cloud> kCloudIn{"cloud"};
  static inline const apex::InputPort<geometry_msgs::TransformStamped> kTransform{"transform"};
  static inline const apex::OutputPort<Cloud> kCloudOut{"cloud"};
  static apex::Manifest manifest() {
    return apex::Manifest("Transforms a cloud into the transform's frame (e.g. from TfLookup)")
        .inCategory("clouds")
        .input(kCloudIn)
        .input(kTransform)
        .output(kCloudOut);
  }
  void process() override {
    auto in = cloud_in_.get();
    const auto& t = *transform_.get();
    requirePoints(*in);
    if (!t.child_frame_id.empty() && t.child_frame_id != in->header.frame_id)
      throw std::invalid_argument("the transform maps frame '" + t.child_frame_id + "', the cloud is in '" + in->header.frame_id +
                                  "'");
    auto out = cloudResult(*in, transformPoints(*in->points, toEigen(t.transform), points_.next()));
    out->header.frame_id = t.header.frame_id;
    cloud_out_.publish(out);
  }

 private:
  apex::Input<Cloud> cloud_in_{this, kCloudIn};
  apex::Input<geometry_msgs::TransformStamped> transform_{this, kTransform};
  apex::Output<Cloud> cloud_out_{this, kCloudOut};
  Reused<Blob> points_;  // the moved points, refilled once nobody holds the last ones
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TransformCloud, "apex_nodes/TransformCloud");
