// What a save or a load may touch on disk: only regular files, never a read-only one,
// never waiting on a FIFO or reading a device; temporary files of dead saves go away.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "apex/core/graph_file.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

using namespace apex_test;

namespace {

TEST(GraphFileDisk, ARegularFileIsReplacedWholeAndKeepsItsMode) {
  TempDir dir;
  const std::string path = dir.file("g.yaml");
  writeFile(path, "old");
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  ASSERT_TRUE(writeFileAtomically(path, "new"));
  EXPECT_EQ(readFile(path), "new");
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"g.yaml"});
}

TEST(GraphFileDisk, ASaveReplacesAGraphOrAnEmptyFileAndNothingElse) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(g.addNode("test/Relay", "r"));
  const std::string bag = dir.file("run3.bag"), notes = dir.file("notes.yaml"), empty = dir.file("empty.yaml");
  const std::string bag_bytes = std::string("#ROSBAG V2.0\n") + std::string(4096, '\0') + "\x01\x02 data";
  writeFile(bag, bag_bytes);
  writeFile(notes, "todo: [tune c, record a bag]\n");  // YAML, but not a graph
  writeFile(empty, "");
  for (const auto& path : {bag, notes}) {
    auto st = saveGraphFile(g, path);
    ASSERT_FALSE(st) << path;
    EXPECT_TRUE(Contains(st.message(), {"cannot save over '" + path + "': it is not a graph file",
                                        "it is left as it is: save under another name"}));
  }
  EXPECT_EQ(readFile(bag), bag_bytes);
  EXPECT_EQ(readFile(notes), "todo: [tune c, record a bag]\n");
  EXPECT_TRUE(saveGraphFile(g, empty));
  EXPECT_TRUE(saveGraphFile(g, empty)) << "a graph file is replaced";
  EXPECT_TRUE(Contains(readFile(empty), {"apex_graph:", "name: r"}));
  const std::string big = dir.file("big.bag");  // past what a graph file may be: not read, refused
  writeFile(big, "x");
  ASSERT_EQ(::truncate(big.c_str(), kMaxGraphFileBytes + 1), 0);
  EXPECT_TRUE(Contains(saveGraphFile(g, big).message(), {"it is not a graph file", "over the limit"}));
}

TEST(GraphFileDisk, AReadOnlyFileIsNotReplacedEvenByRoot) {
  TempDir dir;
  const std::string path = dir.file("g.yaml");
  writeFile(path, "old");
  ASSERT_EQ(::chmod(path.c_str(), 0444), 0);
  auto st = writeFileAtomically(path, "new");
  EXPECT_FALSE(st);
  EXPECT_TRUE(Contains(st.message(), {"'" + path + "'", "read-only"}));
  EXPECT_EQ(readFile(path), "old");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"g.yaml"});
}

TEST(GraphFileDisk, ADeviceOrFifoIsNeverReplaced) {
  TempDir dir;
  const std::string fifo = dir.file("pipe.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  auto st = writeFileAtomically(fifo, "new");
  EXPECT_TRUE(Contains(st.message(), {"not a regular file"}));
  struct stat s {};
  ASSERT_EQ(::stat(fifo.c_str(), &s), 0);
  EXPECT_TRUE(S_ISFIFO(s.st_mode)) << "the FIFO was replaced";
  // (the same check refuses /dev/full, which a save used to replace by a regular file;
  // not tried here, so that a regression cannot break the machine the tests run on)
}

TEST(GraphFileDisk, LoadingAFifoOrADeviceIsRefusedAtOnce) {
  TempDir dir;
  const std::string fifo = dir.file("pipe.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  Graph g(testRegistry());
  const auto t0 = std::chrono::steady_clock::now();
  for (const std::string& path : {fifo, std::string("/dev/zero"), std::string("/dev/urandom")}) {
    auto r = loadGraphFile(g, path);  // waited for a writer forever, or read without end
    ASSERT_FALSE(r);
    EXPECT_TRUE(Contains(r.message(), {"'" + path + "'", "not a regular file"}));
  }
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
}

TEST(GraphFileDisk, AFileOverTheSizeLimitIsRefusedUnread) {
  TempDir dir;
  const std::string path = dir.file("huge.yaml");
  writeFile(path, "");
  ASSERT_EQ(::truncate(path.c_str(), kMaxGraphFileBytes + 1), 0);  // sparse: nothing to read
  Graph g(testRegistry());
  auto r = loadGraphFile(g, path);
  ASSERT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"over the limit of " + std::to_string(kMaxGraphFileBytes)}));
}

/** The most memory this process has held (VmHWM) in MiB, or -1 where Linux does not say. */
long peakMib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6)) / 1024;
  return -1;
}
/** From here on, the peak counts from what the process holds now. */
void resetPeak() { std::ofstream("/proc/self/clear_refs") << "5"; }

TEST(GraphFileDisk, AFileOfBracketsOrDeepMapsCostsLittleMemoryToRefuse) {
  // 4 MiB of "[" took the runtime from 143 MB to 1,078 MB, and yaml-cpp kept it.
  TempDir dir;
  Graph g(testRegistry());
  std::string maps, dashes;
  while (maps.size() < (4u << 20)) maps += "{a: ";
  while (dashes.size() < (4u << 20)) dashes += "- ";
  for (const auto& text : {std::string(4u << 20, '['), maps, dashes}) {
    const std::string path = dir.file("hostile.yaml");
    writeFile(path, text);
    resetPeak();
    const long before = peakMib();
    auto r = loadGraphFile(g, path);
    ASSERT_FALSE(r);
    EXPECT_TRUE(Contains(r.message(), {"line 1", "nested deeper than 32 levels"}));
    EXPECT_TRUE(Contains(saveGraphFile(g, path).message(), {"it is not a graph file"}));
    const long peak = peakMib();
    if (before < 0 || peak < 0) GTEST_SKIP() << "no VmHWM in /proc/self/status";
    EXPECT_LT(peak - before, 64) << "MiB for a load and a save of " << text.substr(0, 8) << "... (file, copies and all)";
    EXPECT_EQ(readFile(path), text) << "left as it was";
  }
}

TEST(GraphFileDisk, ASaveThroughAFolderSwappedForALinkNeverLandsOutsideNorLeavesATemporary) {
  // A folder inside the roots swapped for a link to one outside while saves ran: they once wrote
  // there, and left 931 temporary files outside and 1,092 inside in a minute.
  TempDir dir;
  const std::string outside = dir.file("outside"), inner = dir.file("root/d"), aside = dir.file("root/d.real");
  fs::create_directories(inner);
  fs::create_directories(outside);
  Graph g(testRegistry());
  ASSERT_TRUE(g.addNode("test/Relay", "r"));
  std::atomic<bool> done{false};
  std::thread swapper([&] {
    while (!done) {
      std::error_code ec;
      fs::rename(inner, aside, ec);
      fs::create_directory_symlink(outside, inner, ec);
      fs::remove(inner, ec);  // the link
      fs::rename(aside, inner, ec);
    }
  });
  int saved = 0, refused = 0;
  for (int i = 0; i < 400; ++i) ++(saveGraphFile(g, inner + "/x.yaml", Links::Refuse) ? saved : refused);
  done = true;
  swapper.join();
  std::vector<std::string> outside_files, temporaries;
  for (const auto& e : fs::recursive_directory_iterator(dir.path)) {
    const std::string name = e.path().filename().string();
    if (e.path().string().rfind(outside + "/", 0) == 0) outside_files.push_back(name);
    if (name.find(".tmp.") != std::string::npos) temporaries.push_back(e.path().string());
  }
  EXPECT_TRUE(outside_files.empty()) << outside_files.size() << " files outside, e.g. " << outside_files.front() << " (" << saved
                                     << " saves, " << refused << " refused)";
  EXPECT_TRUE(temporaries.empty()) << temporaries.size() << " temporaries left, e.g. " << temporaries.front();
  EXPECT_EQ(saved + refused, 400);
}

TEST(GraphFileDisk, TemporariesOfASaveThatDiedAreRemovedByTheNextSave) {
  TempDir dir;
  const std::string path = dir.file("g.yaml");
  const pid_t child = ::fork();  // a process id that is surely gone afterwards
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child);
  const std::string stale = path + ".tmp." + std::to_string(child) + ".0";
  const std::string live = path + ".tmp." + std::to_string(::getppid()) + ".0";  // a live process: kept
  writeFile(stale, "half");
  writeFile(live, "busy");
  writeFile(dir.file("g.yaml.tmp.notes"), "a user's file");  // not named by a save: kept
  ASSERT_TRUE(writeFileAtomically(path, "new"));
  EXPECT_EQ(dir.entries(),
            (std::vector<std::string>{"g.yaml", "g.yaml.tmp." + std::to_string(::getppid()) + ".0", "g.yaml.tmp.notes"}));
}

}  // namespace
