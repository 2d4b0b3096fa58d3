#include "profile_service.hpp"

#include <apex/GetNodeProfile.h>

#include "request_text.hpp"

namespace apex {
namespace ros_host {
namespace {

void fill(const std::vector<HistogramBucket>& bars, std::vector<double>& lower, std::vector<double>& upper,
          std::vector<std::uint64_t>& counts) {
  for (const auto& b : bars) lower.push_back(b.lower_ns / 1e6), upper.push_back(b.upper_ns / 1e6), counts.push_back(b.count);
}

}  // namespace

ros::ServiceServer serveProfile(ros::NodeHandle& pnh, const Graph& graph) {
  return advertiseChecked<GetNodeProfile::Request, GetNodeProfile::Response>(
      pnh, "node_profile", [&graph](GetNodeProfile::Request& req, GetNodeProfile::Response& res) {
        auto profile = graph.nodeProfile(req.node);
        res.success = profile.isOk();
        if (!profile) {
          res.message = "node_profile: " + profile.message();
          return true;
        }
        const auto& p = profile.value();
        res.window_s = p.window_s;
        fill(p.time, res.time_lower_ms, res.time_upper_ms, res.time_counts);
        fill(p.latency, res.latency_lower_ms, res.latency_upper_ms, res.latency_counts);
        res.firings = p.firings, res.timed_firings = p.timed_firings, res.timed_ms = p.timed_ns / 1e6;
        res.message = p.latency.empty() ? "no latency: no frame stamped within the last hour reached it in the window" : "";
        return true;
      });
}

}  // namespace ros_host
}  // namespace apex
