// A runtime of a test's own, as a process (rosrun apex apex_runtime_node), to stop with a
// signal of the test's choosing: SIGINT for a clean stop, SIGKILL for a crash.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "apex_test/ros_client.hpp"  // waitUntil

extern char** environ;

namespace apex_test {

class RuntimeProcess {
 public:
  /** @brief A runtime named `name` (its services under /<name>), with $ROS_HOME = `ros_home`. */
  RuntimeProcess(std::string name, std::string ros_home) : name_(std::move(name)), ros_home_(std::move(ros_home)) {}
  ~RuntimeProcess() {
    if (pid_ > 0) stop(SIGKILL);
  }
  RuntimeProcess(const RuntimeProcess&) = delete;
  RuntimeProcess& operator=(const RuntimeProcess&) = delete;

  std::string ns() const { return "/" + name_; }

  void start() {
    // Everything the child needs is made before fork: the test has threads (the spinner), so the
    // child may only exec.
    std::vector<std::string> env_text{"ROS_HOME=" + ros_home_};
    for (char** e = environ; *e; ++e)
      if (std::string(*e).rfind("ROS_HOME=", 0) != 0) env_text.push_back(*e);
    std::vector<char*> env;
    for (auto& e : env_text) env.push_back(e.data());
    env.push_back(nullptr);
    std::string rosrun = "rosrun", pkg = "apex", type = "apex_runtime_node", arg = "__name:=" + name_;
    char* argv[] = {rosrun.data(), pkg.data(), type.data(), arg.data(), nullptr};
    pid_ = fork();
    if (pid_ == 0) {
      execvpe("rosrun", argv, env.data());
      _exit(127);
    }
    ASSERT_GT(pid_, 0) << "cannot start " << name_;
  }

  /** @brief Sends `sig` and waits at most 10 s for the exit; its exit code (128 + signal if a
   *  signal ended it), or -1 if it had to be killed. */
  int stop(int sig) {
    if (pid_ <= 0) return -1;
    kill(pid_, sig);
    int status = 0;
    const bool exited = waitUntil([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, 10);
    if (!exited) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
    pid_ = -1;
    if (!exited) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  std::string name_, ros_home_;
  pid_t pid_ = -1;
};

/** @brief Calls `ns`/`name` until it answers (a runtime starting, or one restarted while the
 *  master still names the killed one's address), at most `seconds`; false if it never did. */
template <class Srv>
bool callWhenUp(const std::string& service, Srv& srv, double seconds = 60) {
  return waitUntil([&] { return ros::service::call(service, srv); }, seconds);
}

}  // namespace apex_test
