// Files written whole or not at all: a temporary file beside the target, flushed, renamed over it,
// every step relative to the one folder opened first (so a path changed meanwhile cannot send a
// step elsewhere, or leave a temporary file behind).
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "apex/core/graph_file.hpp"

namespace apex {
namespace {

std::string fileError(const std::string& verb, const std::string& path) {
  return "cannot " + verb + " '" + path + "': " + std::strerror(errno);
}

/** A file descriptor closed when it goes. */
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  /** Closes it now; false if the close failed (a write that did not reach the disk). */
  bool close() {
    const int fd = fd_;
    fd_ = -1;
    return ::close(fd) == 0;
  }

 private:
  int fd_;
};

/** The folder `dir` opened: as the path says, or (Links::Refuse) one component at a time from
 *  "/" (or the current folder) without following a link. -1 with errno on failure (ELOOP or
 *  ENOTDIR: a link on the way). */
int openFolder(const std::string& dir, Links links) {
  constexpr int kFlags = O_RDONLY | O_DIRECTORY | O_CLOEXEC;
  if (links == Links::Follow) return ::open(dir.c_str(), kFlags);
  int fd = ::open(dir[0] == '/' ? "/" : ".", kFlags);
  for (std::size_t from = 0; fd >= 0 && from < dir.size();) {
    std::size_t to = dir.find('/', from);
    if (to == std::string::npos) to = dir.size();
    const std::string part = dir.substr(from, to - from);
    from = to + 1;
    if (part.empty() || part == ".") continue;
    const int next = ::openat(fd, part.c_str(), kFlags | O_NOFOLLOW);
    const int saved = errno;
    ::close(fd);
    errno = saved;
    fd = next;
  }
  return fd;
}

/** Removes `<name>.tmp.<pid>.<n>` files in the folder `dir` left by saves that died (their process
 *  is gone). */
void removeStaleTemporaries(int dir, const std::string& name) {
  const int fd = ::dup(dir);
  DIR* d = fd < 0 ? nullptr : ::fdopendir(fd);
  if (!d) {
    if (fd >= 0) ::close(fd);
    return;
  }
  const std::string prefix = name + ".tmp.";
  while (const dirent* e = ::readdir(d)) {
    const std::string entry = e->d_name;
    if (entry.compare(0, prefix.size(), prefix) != 0) continue;
    char* end = nullptr;
    const long pid = std::strtol(entry.c_str() + prefix.size(), &end, 10);
    const bool named_by_a_save = pid > 0 && end && *end == '.';
    const bool gone = ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
    if (named_by_a_save && pid != ::getpid() && gone) ::unlinkat(dir, entry.c_str(), 0);
  }
  ::closedir(d);
}

/** Writes all of `content` to `fd`. */
bool writeAll(int fd, const std::string& content) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

Status writeFileAtomically(const std::string& path, const std::string& content, Links links) {
  static std::atomic<unsigned> counter{0};
  const auto slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  Fd folder(openFolder(dir, links));
  if (folder.get() < 0)
    return Status::error(errno == ELOOP || errno == ENOTDIR
                             ? "cannot write '" + path + "': its folder is not where it was checked to be (a link on the way)"
                             : fileError("write", path));
  struct stat old {};
  const bool exists = ::fstatat(folder.get(), name.c_str(), &old, AT_SYMLINK_NOFOLLOW) == 0;
  // The rename would replace anything, even as root: refuse what a careful user would not overwrite.
  if (exists && !S_ISREG(old.st_mode)) return Status::error("cannot write '" + path + "': not a regular file");
  if (exists && (old.st_mode & 0222) == 0) return Status::error("cannot write '" + path + "': the file is read-only");
  const mode_t mode = exists ? (old.st_mode & 07777) : 0644;  // keep a file's permissions
  removeStaleTemporaries(folder.get(), name);
  const std::string tmp = name + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  Fd file(::openat(folder.get(), tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode));
  if (file.get() < 0) return Status::error(fileError("write", path));
  auto failed = [&](const char* verb) {
    const Status st = Status::error(fileError(verb, path));
    ::unlinkat(folder.get(), tmp.c_str(), 0);
    return st;
  };
  (void)::fchmod(file.get(), mode);  // open() applies the umask; a replaced file keeps its exact mode
  if (!writeAll(file.get(), content) || ::fsync(file.get()) != 0 || !file.close()) return failed("write");
  if (::renameat(folder.get(), tmp.c_str(), folder.get(), name.c_str()) != 0) return failed("replace");
  ::fsync(folder.get());  // the rename, durable
  return Status::ok();
}

}  // namespace apex
