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

  /** @brief No roots: every path is refused. */
  FileRoots() = default;
  /** @brief `roots` are resolved like paths (package://, $(find pkg), ~) and may not exist yet. */
  explicit FileRoots(const std::vector<std::string>& roots, PackageResolver packages = {});

  /** @brief The absolute path `path` names — `package://pkg/x`, `$(find pkg)/x` and `~/x`
   *  understood, `..` and symlinks resolved — if it lies in one of the roots; otherwise an
   *  error naming the path and the roots. Touches nothing on disk but reading links. */
  Result<std::string> resolve(const std::string& path) const;

  /** @brief resolve(), and what `mode` needs: Read an existing regular file, Write a regular
   *  file or nothing in an existing folder, Directory a folder or nothing yet. */
  Result<std::string> check(const std::string& path, PathMode mode) const;

  /** @brief The roots as resolved, e.g. "/home/u/.ros/apex, /opt/apex/graphs". */
  std::string list() const;
  const std::vector<std::string>& roots() const { return roots_; }

 private:
  Result<std::string> expand(const std::string& path) const;
  std::vector<std::string> roots_;
  PackageResolver packages_;
};

}  // namespace apex
