// The folders that paths arriving from outside may name. ROS 1 has no
// authentication: anyone who reaches the master can call save_graph or set a
// parameter, so every path that comes in through a service is resolved and
// checked against these roots before anything is opened or created.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "apex/core/param.hpp"
#include "apex/core/result.hpp"

namespace apex {

class FileRoots {
 public:
  /** Where a package lives ("" if unknown): the ROS host passes ros::package::getPath. */
  using PackageResolver = std::function<std::string(const std::string& package)>;
  /** What a refusal adds to say how to allow a folder, e.g. "; add it to ~file_roots". */
  using Hint = std::function<std::string(const std::string& folder)>;
  enum class Access { Read, Write };

  /** @brief No roots: every path is refused. */
  FileRoots() = default;
  /** @brief Folders files may be read and written in, the first taking relative paths. They are
   *  resolved like paths (package://, $(find pkg), ~) and may not exist yet. */
  explicit FileRoots(const std::vector<std::string>& roots, PackageResolver packages = {});
  /** @brief Adds folders whose files may be read, never written, even where they lie inside a
   *  writable root (a package's shipped graphs); a writable root inside one becomes read only. */
  FileRoots& readOnly(const std::vector<std::string>& folders);
  /** @brief Every path, expanded and resolved; a relative one from the current folder (what the
   *  operator's launch names: trusted). */
  static FileRoots anywhere(PackageResolver packages);
  /** @brief Sets what a path outside the roots is told (default: "; a launch file can widen them
   *  with ~file_roots"). */
  FileRoots& hint(Hint hint);

  /** @brief The absolute path `path` names — `package://pkg/x`, `$(find pkg)/x` and `~/x`
   *  understood, a relative path taken inside the first writable root, `..` and symlinks
   *  resolved (a `..` after a folder that does not exist is refused) — if `access` is allowed there; otherwise an error naming
   * the path, the roots and how to allow it. Touches nothing on disk but reading links. */
  Result<std::string> resolve(const std::string& path, Access access = Access::Read) const;

  /** @brief resolve(), and what `mode` needs: Read an existing regular file, Write a regular
   *  file or nothing in an existing folder, Directory a folder or nothing yet (both writable). */
  Result<std::string> check(const std::string& path, PathMode mode) const;

  /** @brief The roots as resolved, e.g. "/home/u/.ros/apex, /data; read only: /opt/apex/graphs". */
  std::string list() const;
  const std::vector<std::string>& roots() const { return roots_; }
  const std::vector<std::string>& readOnlyRoots() const { return read_only_; }

 private:
  Result<std::string> expand(const std::string& path) const;
  void add(std::vector<std::string>& to, const std::string& folder);
  std::vector<std::string> roots_, read_only_;
  bool relative_in_root_ = true;  // a relative path: inside the first root, or (anywhere) the current folder
  PackageResolver packages_;
  Hint hint_;
};

}  // namespace apex
