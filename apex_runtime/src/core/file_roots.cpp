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

/** weakly_canonical follows links as far as the folders exist and takes the rest as written, so
 *  in `root/missing/../link/x` the `..` would cancel `missing` on paper, and `link`, a link out of
 *  the root, would not be followed: such a path is refused (the system could not open it anyway). */
std::string dotsAfterAMissingFolder(const fs::path& absolute) {
  fs::path prefix;
  bool missing = false;
  for (const auto& part : absolute) {
    if (part == ".." && missing) return "'..' after a folder that does not exist";
    prefix /= part;
    std::error_code ec;
    if (!missing && !fs::exists(fs::symlink_status(prefix, ec))) missing = true;
  }
  return "";
}

std::string joined(const std::vector<std::string>& folders) {
  std::string out;
  for (const auto& f : folders) out += (out.empty() ? "" : ", ") + f;
  return out;
}

}  // namespace

FileRoots::FileRoots(const std::vector<std::string>& roots, PackageResolver packages) : packages_(std::move(packages)) {
  for (const auto& r : roots) add(roots_, r);
}

FileRoots& FileRoots::readOnly(const std::vector<std::string>& folders) {
  for (const auto& r : folders) add(read_only_, r);
  // A writable root inside a read-only one is read only: never offered for writing, nor for
  // relative paths
  roots_.erase(std::remove_if(roots_.begin(), roots_.end(),
                              [&](const std::string& root) {
                                return std::any_of(read_only_.begin(), read_only_.end(),
                                                   [&](const std::string& ro) { return inside(ro, root); });
                              }),
               roots_.end());
  return *this;
}

FileRoots FileRoots::anywhere(PackageResolver packages) {
  FileRoots all({"/"}, std::move(packages));
  all.relative_in_root_ = false;
  return all;
}

FileRoots& FileRoots::hint(Hint hint) {
  hint_ = std::move(hint);
  return *this;
}

void FileRoots::add(std::vector<std::string>& to, const std::string& folder) {
  auto expanded = expand(folder);
  if (!expanded || expanded.value().empty()) return;
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(expanded.value()), ec);
  if (!ec && std::find(to.begin(), to.end(), canonical.string()) == to.end()) to.push_back(canonical.string());
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

Result<std::string> FileRoots::resolve(const std::string& path, Access access) const {
  if (path.empty()) return Status::error("an empty path names no file");
  auto expanded = expand(path);
  if (!expanded) return expanded.status();
  fs::path absolute = expanded.value();
  if (absolute.is_relative())
    absolute = roots_.empty() || !relative_in_root_ ? fs::absolute(absolute) : fs::path(roots_.front()) / absolute;
  if (auto why = dotsAfterAMissingFolder(absolute); !why.empty()) return Status::error("path '" + path + "': " + why);
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(absolute, ec);
  if (ec) return Status::error("path '" + path + "': " + ec.message());
  const std::string named = "path '" + path + "'" + (p.string() == path ? "" : " ('" + p.string() + "')");
  for (const auto& root : read_only_) {
    if (!inside(root, p)) continue;
    if (access == Access::Read) return p.string();
    if (roots_.empty()) return Status::error(named + " lies in '" + root + "', whose files may be read, not written");
    return Status::error(named + " lies in '" + root + "', whose files may be read, not written: write it in " +
                         (roots_.size() > 1 ? "one of " : "") + joined(roots_) + " (a path without a folder, such as '" +
                         p.filename().string() + "', goes to " + roots_.front() + ")");
  }
  for (const auto& root : roots_)
    if (inside(root, p)) return p.string();
  const std::string folder = access == Access::Read || !fs::is_directory(p) ? p.parent_path().string() : p.string();
  const std::string allowed =
      access == Access::Read ? "read from (" + list() : "written in (" + (roots_.empty() ? "none" : joined(roots_));
  return Status::error(named + " is outside the folders files may be " + allowed + ")" +
                       (hint_ ? hint_(folder) : "; a launch file can widen them with ~file_roots"));
}

Result<std::string> FileRoots::check(const std::string& path, PathMode mode) const {
  const bool reads = mode == PathMode::Read || mode == PathMode::ReadFileOrFolder;
  auto resolved = resolve(path, reads ? Access::Read : Access::Write);
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
    case PathMode::ReadFileOrFolder:
      if (!exists) return Status::error("path '" + path + "': no such file or folder");
      if (!S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) return Status::error("path '" + path + "': not a file or a folder");
      break;
  }
  return resolved;
}

std::string FileRoots::list() const {
  if (roots_.empty() && read_only_.empty()) return "none";
  if (read_only_.empty()) return joined(roots_);
  return (roots_.empty() ? "" : joined(roots_) + "; ") + "read only: " + joined(read_only_);
}

}  // namespace apex
