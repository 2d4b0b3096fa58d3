// A save killed with SIGKILL at a random moment leaves the old file or the whole new
// one, never a mix; the temporary files of killed saves are removed by the next save.
// (Its own test binary: the child process is forked before any thread exists.)
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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
  std::mt19937 rng(20261123);
  int killed_mid_write = 0;
  for (int round = 0; round < 20; ++round) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {  // saves the two versions in turn until killed
      Graph g(testRegistry());
      if (!g.load(parseGraphText(a).value())) ::_exit(3);
      for (int i = 0;; ++i)
        if (!g.setParameter("gain0", "gain", i % 2 ? "2" : "3") || !saveGraphFile(g, path)) ::_exit(3);
    }
    ::usleep(std::uniform_int_distribution<int>(20000, 200000)(rng));
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the saving process stopped by itself, status " << status;
    const std::string text = readFile(path);
    ASSERT_TRUE(text == a || text == b) << "round " << round << ": the file is neither version (" << text.size() << " bytes)";
    Graph check(testRegistry());
    ASSERT_TRUE(loadGraphFile(check, path)) << "round " << round;
    killed_mid_write += dir.entries().size() > 1 ? 1 : 0;  // a temporary was left: killed while writing
  }
  ASSERT_TRUE(writeFileAtomically(path, a));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"big.yaml"}) << "temporaries of killed saves were left";
  std::printf("save crash: %d of 20 kills left a temporary file (removed by the next save)\n", killed_mid_write);
}

}  // namespace
