// Graph files: read (regular files only, within a size limit), their subgraph references
// expanded, and saved (file_write.cpp writes); the text itself is graph_text.cpp's.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "apex/core/graph_file.hpp"
#include "apex/core/node_names.hpp"
#include "yaml_text.hpp"

namespace apex {
namespace {

std::string fileError(const std::string& verb, const std::string& path) {
  return "cannot " + verb + " '" + path + "': " + std::strerror(errno);
}

}  // namespace

Result<std::string> readGraphFile(const std::string& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; only regular files are read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Status::error(fileError("read", path));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return Status::error("cannot read '" + path + "': not a regular file");
  }
  if (st.st_size > kMaxGraphFileBytes) {
    ::close(fd);
    return Status::error("cannot read '" + path + "': " + std::to_string(st.st_size) + " bytes, over the limit of " +
                         std::to_string(kMaxGraphFileBytes) + " for a graph file");
  }
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(fd, &text[done], text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the file shrank meanwhile: parse what is there
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  text.resize(done);
  return text;
}

std::string joinReference(const std::string& ref, const std::string& from) {
  const bool as_is =
      ref.empty() || ref[0] == '/' || ref[0] == '~' || ref.rfind("package://", 0) == 0 || ref.rfind("$(find ", 0) == 0;
  if (as_is) return ref;
  const auto slash = from.rfind('/');
  return slash == std::string::npos ? ref : from.substr(0, slash + 1) + ref;
}

namespace {

std::string at(const std::string& file, int line) {
  return "'" + file + "', " + (line > 0 ? "line " + std::to_string(line) + ": " : "");
}

Status expandFile(NodeDescription& node, const std::string& file, const GraphFileOptions& options,
                  std::vector<std::string>& chain);

/** Fills in the file-backed subgraphs of `d` (read from `file`) and checks its nodes; `chain`
 *  holds the files being read, outermost first, to refuse a file that includes itself. */
Status expand(GraphDescription& d, const std::string& file, const GraphFileOptions& options, std::vector<std::string>& chain) {
  for (auto& node : d.nodes) {
    if (node.type != kSubgraphType) {
      if (options.check)
        if (auto st = options.check(node); !st) return Status::error(at(file, node.line) + st.message());
      continue;
    }
    const std::string where = at(file, node.line) + subgraphLabel(node.name);
    if (node.source.empty()) {  // inline: its nodes are in this file
      auto inner = std::make_shared<GraphDescription>(*node.subgraph);
      if (auto st = expand(*inner, file, options, chain); !st) return st;
      node.subgraph = inner;
    } else if (auto st = expandFile(node, file, options, chain); !st) {
      return st;
    }
    if (options.check)  // a subgraph's own parameters: now that its exports are known
      if (auto st = options.check(node); !st) return Status::error(where + ": " + st.message());
  }
  return Status::ok();
}

Status expandFile(NodeDescription& node, const std::string& file, const GraphFileOptions& options,
                  std::vector<std::string>& chain) {
  const std::string where = at(file, node.line) + subgraphLabel(node.name);
  std::string path = joinReference(node.source, file);
  if (options.open) {
    auto opened = options.open(path);
    if (!opened) return Status::error(where + ": " + opened.message());
    path = opened.value();
  } else if (path.rfind("package://", 0) == 0 || path.rfind("$(find ", 0) == 0) {
    return Status::error(where + ": '" + node.source + "' names a ROS package, which only the ROS runtime resolves");
  }
  if (std::find(chain.begin(), chain.end(), path) != chain.end()) {
    std::string loop;
    for (const auto& f : chain) loop += "'" + f + "' -> ";
    return Status::error(where + ": the file includes itself (" + loop + "'" + path + "')");
  }
  if (chain.size() > static_cast<std::size_t>(kMaxSubgraphDepth))
    return Status::error(where + ": subgraph files nested deeper than " + std::to_string(kMaxSubgraphDepth) + " levels");
  auto text = readGraphFile(path);
  if (!text) return Status::error(where + ": " + text.message());
  auto inner = parseGraphText(text.value());
  if (!inner) return Status::error(where + ": '" + path + "', " + inner.message());
  chain.push_back(path);
  auto st = expand(inner.value(), path, options, chain);
  chain.pop_back();
  if (!st) return Status::error(where + ": " + st.message());
  node.subgraph = std::make_shared<GraphDescription>(std::move(inner.value()));
  return Status::ok();
}

}  // namespace

Result<GraphDescription> readGraphDescription(const std::string& path, const GraphFileOptions& options) {
  auto read = readGraphFile(path);
  if (!read) return read.status();
  auto description = parseGraphText(read.value());
  if (!description) return Status::error("'" + path + "', " + description.message());
  std::vector<std::string> chain{path};
  if (auto st = expand(description.value(), path, options, chain); !st) return st;
  return description;
}

Result<LoadReport> loadGraphFile(Graph& graph, const std::string& path, const GraphFileOptions& options) {
  auto description = readGraphDescription(path, options);
  if (!description) return description.status();
  auto report = graph.load(description.value());
  if (!report) return Status::error("'" + path + "', " + report.message());
  LoadReport named = report.value();
  for (auto& w : named.warnings) w = "'" + path + "', " + w;
  return named;
}

namespace {

/** A file a graph may replace: none yet, an empty one, or a graph file (a YAML mapping with
 *  `apex_graph`). Anything else — a bag, an image, notes — is the user's and stays. */
Status replaceableByGraph(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) return Status::ok();  // else refused later
  const std::string refused = "cannot save over '" + path + "': it is not a graph file";
  auto text = readGraphFile(path);
  if (!text) return Status::error(refused + " (" + text.message() + "); it is left as it is: save under another name");
  if (detail::isGraphText(text.value())) return Status::ok();
  return Status::error(refused + " (no 'apex_graph:' in it); it is left as it is: save under another name");
}

}  // namespace

Status saveGraphFile(const Graph& graph, const std::string& path, Links links) {
  if (auto st = replaceableByGraph(path); !st) return st;
  return writeFileAtomically(path, formatGraphText(graph.describe()), links);
}

}  // namespace apex
