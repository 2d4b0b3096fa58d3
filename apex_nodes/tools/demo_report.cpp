// The demo's summary: starts playback once it listens, counts the regions found
// per frame (through ~inspect of COUNT_NODE/count), compares them with the ground
// truth, and prints per-node timing from ~status. OK: every frame processed, and every
// frame's count right (on photographs, a truth with `backgrounds: real`: 95% of them).
//   apex_demo_report TRUTH.yaml [source: bag|topic] [COUNT_NODE]
#include <algorithm>
#include <apex/Inspect.h>
#include <apex/RuntimeStatus.h>
#include <apex/SetParameter.h>
#include <ros/ros.h>
#include <std_msgs/Int32.h>
#include <std_srvs/SetBool.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>

namespace {

template <class Srv>
bool call(const std::string& name, Srv& srv) {
  if (!ros::service::waitForService(name, ros::Duration(30))) {
    std::fprintf(stderr, "demo: %s did not appear\n", name.c_str());
    return false;
  }
  return ros::service::call(name, srv);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex_demo_report");
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: apex_demo_report TRUTH.yaml [bag|topic] [COUNT_NODE]\n"
                 "  COUNT_NODE: the node whose count output is compared (default blobs;\n"
                 "              in the demo graph camera_detector/regions)\n");
    return 2;
  }
  const std::string source = argc > 2 ? argv[2] : "bag";
  const std::string blobs = argc > 3 ? argv[3] : "blobs";
  std::vector<int> truth;
  bool photographs = false;  // no detector is perfect on photographs: 95% of the frames right will do
  try {
    const YAML::Node file = YAML::LoadFile(argv[1]);
    for (const auto& f : file["frames"]) truth.push_back(f["signs"].as<int>());
    photographs = file["backgrounds"] && file["backgrounds"].as<std::string>() == "real";
  } catch (const YAML::Exception& e) {
    std::fprintf(stderr, "demo: cannot read the ground truth '%s': %s\n", argv[1], e.what());
    return 1;
  }
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();

  std::mutex m;
  std::condition_variable cv;
  std::vector<int> found;
  apex::RuntimeStatus status;
  auto counts = nh.subscribe<std_msgs::Int32>("/apex/inspect/" + blobs + "/count", 100, [&](const std_msgs::Int32::ConstPtr& c) {
    std::lock_guard<std::mutex> l(m);
    found.push_back(c->data);
    cv.notify_all();
  });
  auto statuses = nh.subscribe<apex::RuntimeStatus>("/apex/status", 1, [&](const apex::RuntimeStatus::ConstPtr& s) {
    std::lock_guard<std::mutex> l(m);
    status = *s;
  });
  apex::Inspect inspect;
  inspect.request.node = blobs, inspect.request.port = "count", inspect.request.enable = true;
  if (!call("/apex/inspect", inspect) || !inspect.response.success) {
    std::fprintf(stderr, "demo: cannot inspect %s/count: %s\n", blobs.c_str(), inspect.response.message.c_str());
    return 1;
  }
  // Start playback only now, so no frame passes before we listen.
  while (counts.getNumPublishers() == 0 && ros::ok()) ros::WallDuration(0.01).sleep();
  if (source == "bag") {
    apex::SetParameter play;
    play.request.node = "bag", play.request.parameter = "playing", play.request.value = "true";
    if (!call("/apex/set_parameter", play) || !play.response.success) {
      std::fprintf(stderr, "demo: cannot start the bag: %s\n", play.response.message.c_str());
      return 1;
    }
  } else {
    std_srvs::SetBool resume;
    resume.request.data = false;  // rosbag play: pause_playback(false)
    if (!call("/player/pause_playback", resume)) return 1;
  }
  std::unique_lock<std::mutex> l(m);
  const bool all = cv.wait_for(l, std::chrono::seconds(120), [&] { return found.size() >= truth.size() || !ros::ok(); });
  cv.wait_for(l, std::chrono::milliseconds(700));  // one more ~status (2 Hz) with every frame counted

  int matching = 0, expected = 0, seen = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    expected += truth[i];
    if (i < found.size()) seen += found[i], matching += found[i] == truth[i];
  }
  const int needed = photographs ? static_cast<int>(std::ceil(0.95 * truth.size())) : static_cast<int>(truth.size());
  std::printf("\n=== APEX demo: the sign detector (graphs/camera_detector.yaml) on %zu frames%s\n", truth.size(),
              photographs ? " of photographs" : "");
  std::printf("frames processed:   %zu of %zu%s\n", found.size(), truth.size(), all ? "" : " (timed out)");
  std::printf("regions found:      %d, ground truth %d; frames with the right count: %d of %zu (needs %d)\n", seen, expected,
              matching, truth.size(), needed);
  int width = 14;  // inner nodes of subgraphs have longer names: camera_detector/threshold
  for (const auto& n : status.nodes) width = std::max(width, static_cast<int>(n.name.size()));
  // latency: from the frame's stamp (the bag restamps each frame as it sends it) to the firing's end
  std::printf("%-*s %9s %10s %10s %14s %10s\n", width, "node", "firings", "mean ms", "max ms", "latency p50/p95", "state");
  for (const auto& n : status.nodes) {
    char latency[32] = "-";
    if (n.latency_p50_ms >= 0) std::snprintf(latency, sizeof latency, "%.1f/%.1f", n.latency_p50_ms, n.latency_p95_ms);
    std::printf("%-*s %9lu %10.3f %10.3f %14s %10s\n", width, n.name.c_str(), static_cast<unsigned long>(n.firings), n.mean_ms,
                n.max_ms, latency, n.state.c_str());
  }
  for (const auto& g : status.groups)
    std::printf("thread group %-10s load %5.1f%%, %lu firings\n", g.name.c_str(), 100 * g.load,
                static_cast<unsigned long>(g.firings));
  const bool ok = all && matching >= needed;
  std::printf("demo: %s\n", ok ? "OK" : "FAILED");
  std::fflush(stdout);
  return ok ? 0 : 1;
}
