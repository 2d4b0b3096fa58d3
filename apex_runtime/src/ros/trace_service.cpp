#include "trace_service.hpp"

#include <apex/FrameTrace.h>

#include <cstdio>
#include <ctime>

#include "apex/core/graph_file.hpp"
#include "apex/core/limits.hpp"
#include "request_text.hpp"

namespace apex {
namespace ros_host {
namespace {

std::string defaultName() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "trace_%Y%m%d_%H%M%S.json", &local);
  return name;
}

Status save(const Graph& graph, const FileRoots& roots, const std::string& process, FrameTrace::Request& req,
            FrameTrace::Response& res) {
  if (req.seconds < 0) return Status::error("seconds must be 0 (every firing kept) or more, not " + std::to_string(req.seconds));
  auto path = roots.check(req.path.empty() ? defaultName() : req.path, PathMode::Write);
  if (!path) return path.status();
  res.path = path.value();
  const Trace trace = graph.trace(req.seconds);
  if (trace.size() == 0)
    return Status::error(graph.tracing()
                             ? "no firing traced yet: is the graph paused, or its sources idle?"
                             : "nothing traced: start the trace first (command: start), let the graph run, then save");
  if (auto st = writeFileAtomically(path.value(), chromeTraceJson(trace, process), Links::Refuse); !st) return st;
  res.firings = static_cast<std::uint32_t>(trace.size());
  char text[96];
  std::snprintf(text, sizeof text, "saved %zu firings of %zu thread groups", trace.size(), trace.groups.size());
  res.message = std::string(text) + " to " + path.value() + ": open it in https://ui.perfetto.dev or chrome://tracing";
  return Status::ok();
}

}  // namespace

ros::ServiceServer serveTrace(ros::NodeHandle& pnh, Graph& graph, const FileRoots& roots, std::string process) {
  return advertiseChecked<FrameTrace::Request, FrameTrace::Response>(
      pnh, "trace", [&graph, &roots, process](FrameTrace::Request& req, FrameTrace::Response& res) {
        Status st = Status::ok();
        if (req.command == "start") {
          graph.setTracing(true);
          res.message = "tracing: each thread group keeps its last " + std::to_string(kTraceFirings) + " firings";
        } else if (req.command == "stop") {
          graph.setTracing(false);
          res.message = "stopped tracing: what was kept can still be saved";
        } else if (req.command == "save") {
          st = save(graph, roots, process, req, res);
        } else if (req.command != "status") {
          st = Status::error("unknown command '" + req.command + "': start, stop, save or status");
        }
        res.tracing = graph.tracing();
        if (req.command == "status") res.message = res.tracing ? "tracing" : "not tracing";
        res.success = st.isOk();
        if (!st) res.message = "trace: " + st.message();
        return true;
      });
}

}  // namespace ros_host
}  // namespace apex
