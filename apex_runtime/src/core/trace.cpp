#include "apex/core/trace.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

namespace apex {

std::size_t Trace::size() const {
  std::size_t n = 0;
  for (const auto& g : groups) n += g.firings.size();
  return n;
}

namespace {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string micros(std::int64_t ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%" PRId64 ".%03d", ns / 1000, static_cast<int>(ns % 1000));
  return buf;
}

std::string stampText(std::int64_t ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%" PRId64 ".%09" PRId64, ns / 1000000000, ns % 1000000000);
  return buf;
}

/** A time inside the firing, for the flow events that bind to it: its middle (at its start, it
 *  would also be the end of the firing before, which a viewer may bind to instead). */
std::int64_t inside(const TraceFiring& f) { return f.start_ns + std::max<std::int64_t>(f.end_ns - f.start_ns, 0) / 2; }

/** Where a firing is: its thread group (tid = index + 1) and its place there. */
struct At {
  std::size_t group, index;
};

// The flows: per frame, its firings in the order they started, cut where a node comes again.
std::vector<std::vector<At>> flows(const Trace& trace) {
  std::map<std::int64_t, std::vector<At>> by_frame;
  for (std::size_t g = 0; g < trace.groups.size(); ++g)
    for (std::size_t i = 0; i < trace.groups[g].firings.size(); ++i)
      if (trace.groups[g].firings[i].frame != 0) by_frame[trace.groups[g].firings[i].frame].push_back({g, i});
  auto firing = [&](const At& a) -> const TraceFiring& { return trace.groups[a.group].firings[a.index]; };
  std::vector<std::vector<At>> out;
  for (auto& [frame, all] : by_frame) {
    std::stable_sort(all.begin(), all.end(), [&](const At& a, const At& b) { return firing(a).start_ns < firing(b).start_ns; });
    std::vector<At> flow;
    std::set<std::string> seen;
    for (const At& a : all) {
      if (firing(a).starts_frame || !seen.insert(firing(a).node).second) {
        if (flow.size() > 1) out.push_back(flow);
        flow.clear();
        seen = {firing(a).node};
      }
      flow.push_back(a);
    }
    if (flow.size() > 1) out.push_back(flow);
  }
  return out;
}

}  // namespace

std::string chromeTraceJson(const Trace& trace, const std::string& process) {
  std::string out = "{\"displayTimeUnit\":\"ms\",\"otherData\":{\"start_wall_ns\":\"" + std::to_string(trace.start_wall_ns) +
                    "\"},\n\"traceEvents\":[\n";
  out += "{\"ph\":\"M\",\"name\":\"process_name\",\"pid\":1,\"tid\":0,\"args\":{\"name\":" + jsonString(process) + "}}";
  const std::string pid = ",\"pid\":1,\"tid\":";
  for (std::size_t g = 0; g < trace.groups.size(); ++g) {
    const std::string tid = std::to_string(g + 1);
    out += ",\n{\"ph\":\"M\",\"name\":\"thread_name\"" + pid + tid +
           ",\"args\":{\"name\":" + jsonString("thread group " + trace.groups[g].name) + "}}";
    for (const auto& f : trace.groups[g].firings) {
      out += ",\n{\"ph\":\"X\",\"name\":" + jsonString(f.node) + ",\"cat\":" + jsonString(f.type) + pid + tid +
             ",\"ts\":" + micros(f.start_ns) + ",\"dur\":" + micros(std::max<std::int64_t>(f.end_ns - f.start_ns, 0));
      if (f.frame != 0) out += ",\"args\":{\"frame\":\"" + stampText(f.frame) + "\"}";
      out += "}";
    }
  }
  std::size_t id = 0;
  for (const auto& flow : flows(trace)) {
    ++id;
    for (std::size_t k = 0; k < flow.size(); ++k) {
      const TraceFiring& f = trace.groups[flow[k].group].firings[flow[k].index];
      const char* ph = k == 0 ? "s" : k + 1 == flow.size() ? "f" : "t";
      out += ",\n{\"ph\":\"" + std::string(ph) + "\",\"name\":\"frame\",\"cat\":\"frame\",\"id\":" + std::to_string(id) + pid +
             std::to_string(flow[k].group + 1) + ",\"ts\":" + micros(inside(f)) + (k + 1 == flow.size() ? ",\"bp\":\"e\"" : "") +
             ",\"args\":{\"frame\":\"" + stampText(f.frame) + "\"}}";
    }
  }
  return out + "\n]}\n";
}

}  // namespace apex
