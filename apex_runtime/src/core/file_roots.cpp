#include "apex/core/file_roots.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace apex {
namespace fs = std::filesystem;

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

/** `p` is `root` or below it, component by component ("/a/bc" is not below "/a/b"). */
bool inside(const fs::path& root, const fs::path& p) {
  auto r = root.begin(), q = p.begin();
  for (; r != root.end(); ++r, ++q) {
    if (r->empty() && std::next(r) == root.end()) break;  // a trailing separator
    if (q == p.end() || *r != *q) return false;
  }
  return true;
}

}  // namespace

FileRoots::FileRoots(const std::vector<std::string>& roots, PackageResolver packages) : packages_(std::move(packages)) {
  for (const auto& r : roots) {
    auto expanded = expand(r);
    if (!expanded) continue;
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(fs::absolute(expanded.value()), ec);
    if (!ec && std::find(roots_.begin(), roots_.end(), canonical.string()) == roots_.end())
      roots_.push_back(canonical.string());
  }
}

Result<std::string> FileRoots::expand(const std::string& path) const {
  auto package = [&](const std::string& name, const std::string& rest) -> Result<std::string> {
    const std::string base = packages_ ? packages_(name) : "";
    if (base.empty()) return Status::error("path '" + path + "': unknown package '" + name + "'");
    return base + rest;
  };
  if (startsWith(path, "package://")) {
    const std::string tail = path.substr(10);
    const auto slash = tail.find('/');
    return package(tail.substr(0, slash), slash == std::string::npos ? "" : tail.substr(slash));
  }
  if (startsWith(path, "$(find ")) {
    const auto close = path.find(')');
    if (close == std::string::npos) return Status::error("path '" + path + "': '$(find' without ')'");
    return package(path.substr(7, close - 7), path.substr(close + 1));
  }
  if (path == "~" || startsWith(path, "~/")) {
    const char* home = std::getenv("HOME");
    if (!home || !*home) return Status::error("path '" + path + "': HOME is not set");
    return std::string(home) + path.substr(1);
  }
  return path;
}

Result<std::string> FileRoots::resolve(const std::string& path) const {
  if (path.empty()) return Status::error("an empty path names no file");
  auto expanded = expand(path);
  if (!expanded) return expanded.status();
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(expanded.value()), ec);
  if (ec) return Status::error("path '" + path + "': " + ec.message());
  for (const auto& root : roots_)
    if (inside(root, p)) return p.string();
  return Status::error("path '" + path + "'" + (p.string() == path ? "" : " ('" + p.string() + "')") +
                       " is outside the folders files may be read or written in (" + list() +
                       "); a launch file can widen them with ~file_roots");
}

Result<std::string> FileRoots::check(const std::string& path, PathMode mode) const {
  auto resolved = resolve(path);
  if (!resolved) return resolved;
  const std::string& p = resolved.value();
  struct stat st {};
  const bool exists = ::stat(p.c_str(), &st) == 0;
  switch (mode) {
    case PathMode::Read:
      if (!exists) return Status::error("path '" + path + "': no such file");
      if (!S_ISREG(st.st_mode)) return Status::error("path '" + path + "': not a regular file");
      break;
    case PathMode::Write: {
      if (exists && !S_ISREG(st.st_mode)) return Status::error("path '" + path + "': not a regular file");
      struct stat dir {};
      const std::string folder = fs::path(p).parent_path().string();
      if (::stat(folder.c_str(), &dir) != 0 || !S_ISDIR(dir.st_mode))
        return Status::error("path '" + path + "': the folder '" + folder + "' does not exist");
      break;
    }
    case PathMode::Directory:
      if (exists && !S_ISDIR(st.st_mode)) return Status::error("path '" + path + "': not a folder");
      break;
  }
  return resolved;
}

std::string FileRoots::list() const {
  if (roots_.empty()) return "none";
  std::string out;
  for (const auto& r : roots_) out += (out.empty() ? "" : ", ") + r;
  return out;
}

}  // namespace apex
