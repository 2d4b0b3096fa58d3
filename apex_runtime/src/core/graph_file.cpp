// Graph files: read (regular files only, within a size limit), their subgraph references
// expanded, and written atomically; the text itself is graph_text.cpp's.
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
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

Status saveGraphFile(const Graph& graph, const std::string& path) {
  if (auto st = replaceableByGraph(path); !st) return st;
  return writeFileAtomically(path, formatGraphText(graph.describe()));
}

namespace {

std::string directoryOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

/** Removes `<path>.tmp.<pid>.<n>` files left by saves that died (their process is gone). */
void removeStaleTemporaries(const std::string& path) {
  const std::string dir = directoryOf(path);
  const std::string prefix = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1) + ".tmp.";
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + prefix.size(), &end, 10);
    const bool named_by_a_save = pid > 0 && end && *end == '.';
    const bool gone = ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
    if (named_by_a_save && pid != ::getpid() && gone) ::unlink((dir + "/" + name).c_str());
  }
  ::closedir(d);
}

}  // namespace

Status writeFileAtomically(const std::string& path, const std::string& content) {
  static std::atomic<unsigned> counter{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  struct stat old {};
  const bool exists = ::stat(path.c_str(), &old) == 0;
  // The rename would replace anything, even as root: refuse what a careful user would not overwrite.
  if (exists && !S_ISREG(old.st_mode)) return Status::error("cannot write '" + path + "': not a regular file");
  if (exists && (old.st_mode & 0222) == 0) return Status::error("cannot write '" + path + "': the file is read-only");
  const mode_t mode = exists ? (old.st_mode & 07777) : 0644;  // keep a file's permissions
  removeStaleTemporaries(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) return Status::error(fileError("write", path));
  (void)::fchmod(fd, mode);  // open() applies the umask; a replaced file keeps its exact mode
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const Status st = Status::error(fileError("write", path));
      ::close(fd);
      ::unlink(tmp.c_str());
      return st;
    }
    done += static_cast<std::size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const bool closed = ::close(fd) == 0;
  if (!synced || !closed) {
    const Status st = Status::error(fileError("write", path));
    ::unlink(tmp.c_str());
    return st;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const Status st = Status::error(fileError("replace", path));
    ::unlink(tmp.c_str());
    return st;
  }
  const int dfd = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);  // the rename, durable
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return Status::ok();
}

}  // namespace apex
