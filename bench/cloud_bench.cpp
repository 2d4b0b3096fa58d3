// Clouds with their fields: a 300k-point XYZRGB cloud as a subscriber receives it (its message's
// bytes), through an APEX node, to what a publisher sends (bytes), against the same PCL calls
// in a loop as a pcl_conversions user writes them (sensor_msgs -> typed cloud -> filter ->
// sensor_msgs). Also each cloud node's own cost against its PCL call on a typed cloud; then every
// cloud node type against its PCL call (cloud_bench_nodes.cpp).
//   apex_bench_clouds [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <pcl/filters/crop_box.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl_conversions/pcl_conversions.h>

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <random>

#include "apex/core/graph.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/ros_cloud.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

using namespace apex;
using apex_nodes::Cloud;
using Clock = std::chrono::steady_clock;
using Rgb = pcl::PointCloud<pcl::PointXYZRGB>;
using apex_bench::Spread;

namespace {

Rgb colouredCloud(int n) {
  Rgb c;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-2.f, 2.f);
  for (int i = 0; i < n; ++i) {
    pcl::PointXYZRGB p(std::uint8_t(i % 255), std::uint8_t((i / 3) % 255), 7);
    p.x = u(rng), p.y = u(rng), p.z = 3.f + u(rng);
    c.push_back(p);
  }
  return c;
}

template <class M>
std::vector<std::uint8_t> bytesOf(const M& m) {
  std::vector<std::uint8_t> out(ros::serialization::serializationLength(m));
  ros::serialization::OStream s(out.data(), static_cast<std::uint32_t>(out.size()));
  ros::serialization::serialize(s, m);
  return out;
}

template <class M>
void read(std::vector<std::uint8_t>& bytes, M& m) {
  ros::serialization::IStream s(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(s, m);
}

/** Sends one cloud per notifyNewData. */
class CloudSource : public Node {
 public:
  static Manifest manifest() { return Manifest().output<Cloud>("cloud").driven(); }
  void process() override { publish<Cloud>("cloud", next); }
  std::shared_ptr<const Cloud> next;
};

/** Serialises what arrives, as a publisher does for a subscriber in another process. */
class CloudSink : public Node {
 public:
  static Manifest manifest() { return Manifest().input<Cloud>("cloud"); }
  void process() override {
    const std::size_t n = serialise ? bytesOf(*input<Cloud>("cloud")).size() : 0;
    std::lock_guard<std::mutex> l(m);
    size = n;
    ++count;
    cv.notify_all();
  }
  void waitFor(long n) {
    std::unique_lock<std::mutex> l(m);
    cv.wait(l, [&] { return count >= n; });
  }
  std::mutex m;
  std::condition_variable cv;
  long count = 0;
  std::size_t size = 0;
  std::atomic<bool> serialise{true};
};

NodeRegistry& registry() {
  return apex_bench::pluginRegistry([](NodeRegistry& r) {
    (void)r.add<CloudSource>("bench/CloudSource");
    (void)r.add<CloudSink>("bench/CloudSink");
  });
}

/** One APEX node between the source and the sink, measured per cloud (one in flight): from the
 *  message's bytes (read into a Cloud, as the subscriber does) to the result's bytes. */
struct ApexChain {
  Graph g{registry()};
  CloudSource* src;
  CloudSink* sink;
  long sent = 0;
  ApexChain(const std::string& type, const std::vector<std::pair<std::string, std::string>>& params) {
    (void)g.addNode("bench/CloudSource", "src");
    (void)g.addNode(type, "node");
    (void)g.addNode("bench/CloudSink", "sink");
    for (const auto& [p, v] : params)
      if (auto r = g.setParameter("node", p, v); !r) std::fprintf(stderr, "%s\n", r.message().c_str());
    (void)g.connect("src", "cloud", "node", "cloud");
    (void)g.connect("node", "cloud", "sink", "cloud");
    src = static_cast<CloudSource*>(g.nodeObject("src"));
    sink = static_cast<CloudSink*>(g.nodeObject("sink"));
    g.start();
  }
  double run(std::vector<std::uint8_t>& bytes) {  // ms
    const auto t0 = Clock::now();
    auto cloud = boost::make_shared<Cloud>();
    read(bytes, *cloud);
    apex_nodes::checkCloud(*cloud);  // as PointCloudSubscriber: shared, checked
    src->next = std::shared_ptr<const Cloud>(cloud.get(), [cloud](const Cloud*) {});
    src->notifyNewData();
    sink->waitFor(++sent);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }
  /** The node alone (and two hops): a cloud already received, nothing serialised. */
  double runNode(const std::shared_ptr<const Cloud>& cloud) {
    sink->serialise = false;
    src->next = cloud;
    const auto t0 = Clock::now();
    src->notifyNewData();
    sink->waitFor(++sent);
    sink->serialise = true;
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }
};

/** The pcl_conversions user's loop: message -> typed cloud -> filter -> message -> bytes. */
template <class Filter>
double loopRun(std::vector<std::uint8_t>& bytes, Filter filter) {
  const auto t0 = Clock::now();
  sensor_msgs::PointCloud2 in;
  read(bytes, in);
  auto typed = std::make_shared<Rgb>();
  pcl::fromROSMsg(in, *typed);
  Rgb out;
  filter(typed, out);
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(out, msg);
  msg.header = in.header;
  volatile std::size_t n = bytesOf(msg).size();
  (void)n;
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/** The PCL call alone on a typed cloud (no messages): what the node adds to it. */
template <class Filter>
double callRun(const Rgb::ConstPtr& typed, Filter filter) {
  const auto t0 = Clock::now();
  Rgb out;
  filter(typed, out);
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Case {
  const char* type;
  std::vector<std::pair<std::string, std::string>> params;
  std::function<void(const Rgb::ConstPtr&, Rgb&)> pcl;
};

}  // namespace

namespace apex_bench {
void cloudNodeTable(bool quick);  // cloud_bench_nodes.cpp
}

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const int points = 300000, reps = quick ? 5 : 15;
  const Rgb cloud = colouredCloud(points);
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(cloud, msg);
  msg.header.frame_id = "camera";
  auto bytes = bytesOf(msg);
  const auto typed = std::make_shared<const Rgb>(cloud);
  const std::shared_ptr<const Cloud> received = apex_nodes::makeCloud(msg.header, cloud);

  const std::vector<Case> cases = {
      {"apex_nodes/VoxelGrid",
       {{"leaf_size", "0.05"}},
       [](const Rgb::ConstPtr& in, Rgb& out) {
         pcl::VoxelGrid<pcl::PointXYZRGB> f;
         f.setInputCloud(in);
         f.setLeafSize(0.05f, 0.05f, 0.05f);
         f.filter(out);
       }},
      {"apex_nodes/PassThrough",
       {{"field", "z"}, {"limits", "[2.0, 4.0]"}},
       [](const Rgb::ConstPtr& in, Rgb& out) {
         pcl::PassThrough<pcl::PointXYZRGB> f;
         f.setInputCloud(in);
         f.setFilterFieldName("z");
         f.setFilterLimits(2.f, 4.f);
         f.filter(out);
       }},
      {"apex_nodes/CropBox",
       {{"x", "[-1, 1]"}, {"y", "[-1, 1]"}, {"z", "[2, 4]"}},
       [](const Rgb::ConstPtr& in, Rgb& out) {
         pcl::CropBox<pcl::PointXYZRGB> f;
         f.setInputCloud(in);
         f.setMin(Eigen::Vector4f(-1, -1, 2, 1));
         f.setMax(Eigen::Vector4f(1, 1, 4, 1));
         f.filter(out);
       }},
  };
  std::printf("## Clouds with their fields: %d points, x, y, z, rgb\n\n", points);
  std::printf("Subscriber → node → publisher: from the message's bytes to the result's bytes, one cloud in\n");
  std::printf("flight. APEX reads the bytes straight into its cloud (every field), the node computes on x, y, z\n");
  std::printf("and keeps whole points (VoxelGrid: through PCL's typed filter), the sink serialises. The loop does\n");
  std::printf("what a pcl_conversions user writes: bytes → sensor_msgs → fromROSMsg → typed filter → toROSMsg\n");
  std::printf("→ bytes. The node's own cost: the node alone (a cloud already received, two hops, nothing\n");
  std::printf("serialised) against its PCL call on a typed cloud: what keeping every field costs a node.\n");
  std::printf("Interleaved, %d repetitions: median (min–max) ms.\n\n", reps);
  std::printf(
      "| node | loop ms | APEX ms | APEX / loop | PCL call ms | node alone ms | node / call |\n|---|---|---|---|---|---|---|\n");
  for (const auto& c : cases) {
    ApexChain chain(c.type, c.params);
    Spread loop, apex, call, node;
    chain.run(bytes), loopRun(bytes, c.pcl), callRun(typed, c.pcl), chain.runNode(received);  // warm up
    for (int r = 0; r < reps; ++r) {
      loop.add(loopRun(bytes, c.pcl));
      apex.add(chain.run(bytes));
      call.add(callRun(typed, c.pcl));
      node.add(chain.runNode(received));
    }
    chain.g.stop();
    std::printf("| %s | %s | %s | %.2fx | %s | %s | %.2fx |\n", c.type + 11, loop.text("%.1f").c_str(), apex.text("%.1f").c_str(),
                apex.median() / loop.median(), call.text("%.1f").c_str(), node.text("%.1f").c_str(),
                node.median() / call.median());
  }
  std::printf("\n");
  apex_bench::cloudNodeTable(quick);
  return 0;
}
