// What the panel's previews and the frame trace cost the graph: the demo pipeline plays its bag
// as fast as it can; every output that carries an image or a number is previewed (as the panel
// does with Previews on and every node in view), and this node subscribes to all previews (on)
// or to none (off); or the frame trace is on (~trace). The three interleaved. Throughput: frames
// per second of the overlay node, from ~status. Run by scripts/bench through
// bench/previews.launch; writes a markdown section.
#include <apex/FrameTrace.h>
#include <apex/GetGraph.h>
#include <apex/Inspect.h>
#include <apex/RuntimeStatus.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>

#include <fstream>
#include <mutex>

#include "spread.hpp"

namespace {

std::mutex g_mutex;
double g_stamp = 0, g_firings = 0;  // of the overlay node, from the newest ~status
int g_received = 0;  // previews received

/** Frames per second of the overlay over `seconds`, from two ~status messages. */
double throughput(double seconds) {
  ros::WallDuration(1.0).sleep();  // the change settles
  double t0, f0;
  {
    std::lock_guard<std::mutex> l(g_mutex);
    t0 = g_stamp, f0 = g_firings;
  }
  ros::WallDuration(seconds).sleep();
  std::lock_guard<std::mutex> l(g_mutex);
  return g_stamp > t0 ? (g_firings - f0) / (g_stamp - t0) : 0;
}

std::string ratio(double r) {
  char text[16];
  std::snprintf(text, sizeof text, "%.2f", r);
  return text;
}

/** A subscriber that counts what it receives (and deserializes it, as the panel does). */
template <class M>
ros::Subscriber counting(ros::NodeHandle& nh, const std::string& topic) {
  const boost::function<void(const typename M::ConstPtr&)> count = [](const typename M::ConstPtr&) {
    std::lock_guard<std::mutex> l(g_mutex);
    ++g_received;
  };
  return nh.subscribe<M>(topic, 1, count);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "preview_bench");
  ros::NodeHandle nh, pnh("~");
  const std::string result = pnh.param<std::string>("result", "/dev/stdout");
  const int reps = pnh.param("repetitions", 7);
  const double seconds = pnh.param("seconds", 4.0);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const boost::function<void(const apex::RuntimeStatus::ConstPtr&)> on_status = [](const apex::RuntimeStatus::ConstPtr& s) {
    for (const auto& n : s->nodes)
      if (n.name == "overlay") {
        std::lock_guard<std::mutex> l(g_mutex);
        g_stamp = s->stamp.toSec(), g_firings = static_cast<double>(n.firings);
      }
  };
  auto status = nh.subscribe<apex::RuntimeStatus>("/apex/status", 1, on_status);
  ros::service::waitForService("/apex/get_graph", ros::Duration(60));
  apex::GetGraph graph;
  if (!ros::service::call("/apex/get_graph", graph)) return 1;
  std::vector<std::pair<std::string, std::string>> topics;  // (topic, ROS type) of every preview
  for (const auto& n : graph.response.graph.nodes)
    for (const auto& p : n.ports) {
      if (p.kind != "output" || (p.type != "apex_nodes/Image" && p.type != "int" && p.type != "double" && p.type != "bool"))
        continue;
      apex::Inspect inspect;
      inspect.request.node = n.name, inspect.request.port = p.name, inspect.request.enable = true, inspect.request.preview = true;
      if (ros::service::call("/apex/inspect", inspect) && inspect.response.success)
        topics.emplace_back(inspect.response.topic, inspect.response.message_type);
    }
  auto subscribeAll = [&] {
    std::vector<ros::Subscriber> subs;
    for (const auto& [topic, type] : topics) {
      if (type == "sensor_msgs/Image") subs.push_back(counting<sensor_msgs::Image>(nh, topic));
      else if (type == "std_msgs/Int32") subs.push_back(counting<std_msgs::Int32>(nh, topic));
      else if (type == "std_msgs/Float64") subs.push_back(counting<std_msgs::Float64>(nh, topic));
      else if (type == "std_msgs/Bool") subs.push_back(counting<std_msgs::Bool>(nh, topic));
    }
    return subs;
  };
  auto trace = [](const std::string& command) {
    apex::FrameTrace t;
    t.request.command = command;
    return ros::service::call("/apex/trace", t) && t.response.success;
  };
  throughput(2.0);  // warm up
  apex_bench::Spread off, on, traced;
  for (int r = 0; r < reps; ++r) {  // interleaved: a slow moment of the machine hits all three
    off.add(throughput(seconds));
    {
      auto subs = subscribeAll();
      on.add(throughput(seconds));
    }
    if (!trace("start")) return 1;
    traced.add(throughput(seconds));
    if (!trace("stop")) return 1;
  }
  std::ofstream out(result);
  out << "## What the panel's previews and the frame trace cost the graph\n\n"
      << "The demo pipeline (graphs/paper_pipeline.yaml) plays the demo bag as fast as it can. Every output that\n"
      << "carries an image or a number is previewed (" << topics.size()
      << " ports: what the panel's Previews ask for with every node\n"
      << "in view): at most 5 a second, images scaled to 160 px wide. A subscriber in another process takes all\n"
      << "previews (on) or none (off); or, without previews, the frame trace is on (~trace start: every firing\n"
      << "timed and kept). Interleaved, " << reps << " times " << seconds << " s each: median (min–max) frames per second\n"
      << "of the overlay node, from ~status; ratios of the medians. Targets: previews cost below 5% (ratio\n"
      << "above 0.95), the trace on at most 5%.\n\n"
      << "| off | previews on, all nodes | trace on | previews / off | trace / off |\n|---|---|---|---|---|\n"
      << "| " << off.text("%.1f") << " | " << on.text("%.1f") << " | " << traced.text("%.1f") << " | "
      << ratio(on.median() / off.median()) << "x | " << ratio(traced.median() / off.median()) << "x |\n\n"
      << "(" << g_received << " previews received during the run.)\n";
  return 0;
}
