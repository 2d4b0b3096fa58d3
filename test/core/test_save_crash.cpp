// A save killed with SIGKILL at a random moment leaves the old file or the whole new
// one, never a mix; the temporary files of killed saves are removed by the next save.
// (Its own test binary: the child process is forked before any thread exists.)
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <random>

#include "apex/core/graph_file.hpp"
#include "apex_test/graph_file_helpers.hpp"

using namespace apex_test;

namespace {

/** The text of a chain of `n` gains, each with gain `g`. */
std::string chainText(int n, int g) {
  GraphDescription d;
  for (int i = 0; i < n; ++i) {
    NodeDescription node;
    node.name = "gain" + std::to_string(i), node.type = "test/Gain";
    node.parameters = {{"gain", std::to_string(g)}};
    d.nodes.push_back(node);
    if (i > 0) d.connections.push_back({"gain" + std::to_string(i - 1), "out", node.name, "in", 0});
  }
  return formatGraphText(d);
}

/** Waits (at most `ms` per event) until `count` files named like a save's temporary have been
 *  created in the watched folder. */
bool waitForTemporaries(int events, int count, int ms) {
  alignas(inotify_event) char buffer[4096];
  while (count > 0) {
    pollfd p{events, POLLIN, 0};
    if (::poll(&p, 1, ms) <= 0) return false;
    const ssize_t n = ::read(events, buffer, sizeof buffer);
    for (ssize_t at = 0; at < n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(buffer + at);
      if (e->len > 0 && std::string(e->name).find(".tmp.") != std::string::npos) --count;
      at += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
    }
  }
  return true;
}

/** Forgets the events so far. */
void drain(int events) {
  alignas(inotify_event) char buffer[4096];
  while (::read(events, buffer, sizeof buffer) > 0) {
  }
}

TEST(SaveCrash, AKilledSaveLeavesTheOldOrTheWholeNewFile) {
  TempDir dir;
  const std::string path = dir.file("big.yaml");
  const std::string a = chainText(1500, 2);  // ~150 KB
  std::string b;  // the same with the first gain changed: what the child saves in turn
  {
    Graph g(testRegistry());
    ASSERT_TRUE(g.load(parseGraphText(a).value()));
    ASSERT_TRUE(g.setParameter("gain0", "gain", "3"));
    b = formatGraphText(g.describe());
  }
  ASSERT_TRUE(writeFileAtomically(path, a));
  const int events = ::inotify_init1(IN_NONBLOCK);
  ASSERT_GE(events, 0);
  ASSERT_GE(::inotify_add_watch(events, dir.path.c_str(), IN_CREATE), 0);
  std::mt19937 rng(20261123);
  int killed_mid_write = 0;
  const char* env = std::getenv("APEX_SAVE_CRASH_ROUNDS");  // fewer under the (slow) sanitizers
  const int rounds = env && *env ? std::atoi(env) : 20;
  for (int round = 0; round < rounds; ++round) {
    int progress[2];
    ASSERT_EQ(::pipe(progress), 0);
    drain(events);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {  // saves the two versions in turn until killed; a byte on the pipe as each save starts
      ::close(progress[0]);
      Graph g(testRegistry());
      if (!g.load(parseGraphText(a).value())) ::_exit(3);
      for (int i = 0;; ++i) {
        if (!g.setParameter("gain0", "gain", i % 2 ? "2" : "3")) ::_exit(3);
        if (::write(progress[1], "s", 1) != 1 || !saveGraphFile(g, path)) ::_exit(3);
      }
    }
    ::close(progress[1]);
    // The moment: as the child starts its 1st to 4th save, and in every other round as that
    // save's temporary file appears (mid-write), waiting on the events themselves.
    const int saves = std::uniform_int_distribution<int>(1, 4)(rng);
    const bool mid_write = round % 2 == 1;
    char byte;
    if (mid_write) {
      ASSERT_TRUE(waitForTemporaries(events, saves, 10000)) << "round " << round << ": no temporary file appeared";
    } else {
      for (int i = 0; i < saves; ++i) ASSERT_EQ(::read(progress[0], &byte, 1), 1) << "the saving process stopped";
    }
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    ::close(progress[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the saving process stopped by itself, status " << status;
    const std::string text = readFile(path);
    ASSERT_TRUE(text == a || text == b) << "round " << round << ": the file is neither version (" << text.size() << " bytes)";
    Graph check(testRegistry());
    ASSERT_TRUE(loadGraphFile(check, path)) << "round " << round;
    killed_mid_write += dir.entries().size() > 1 ? 1 : 0;  // a temporary was left: killed while writing
  }
  ::close(events);
  ASSERT_TRUE(writeFileAtomically(path, a));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"big.yaml"}) << "temporaries of killed saves were left";
  std::printf("save crash: %d of %d kills left a temporary file (removed by the next save)\n", killed_mid_write, rounds);
}

}  // namespace
