// The services that read and write files: save and load, path parameters, the file roots, and
// limits as a file and a service see them (the rest: test_ros_services.cpp; one binary, one
// services.test).
#include "services_fixture.hpp"

using namespace services_test;

namespace {

// Every graph the package ships loads with the node libraries as they are now, with no warning
// (a node type renamed, a port or parameter gone would make one): the library may grow and change
// its code, never what a saved graph means.
TEST_F(Services, EveryShippedGraphLoads) {
  const std::string folder = ros::package::getPath("apex") + "/graphs";
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml") continue;
    apex::LoadGraph::Request load;
    load.path = entry.path().string();
    auto res = call<apex::LoadGraph>("load_graph", load);
    EXPECT_TRUE(res.success) << load.path << ": " << res.message;
    EXPECT_TRUE(res.warnings.empty()) << load.path << ": " << (res.warnings.empty() ? "" : res.warnings[0]);
    ++n;
  }
  EXPECT_GE(n, 10) << "graphs in " << folder;
}

TEST_F(Services, SaveAndLoadAreSafe) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  apex::SaveGraph::Request save;
  save.path = tempPath("saved.yaml");
  ASSERT_TRUE(call<apex::SaveGraph>("save_graph", save).success);
  save.path = "/nonexistent_dir/g.yaml";
  auto res = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("/nonexistent_dir/g.yaml"));

  const std::string before = graphText();
  apex::LoadGraph::Request load;
  load.path = tempPath("missing.yaml");
  refused(call<apex::LoadGraph>("load_graph", load), before, "cannot read");
  load.path = tempPath("malformed.yaml");
  writeFile(load.path, "apex_graph: 1\nnodes:\n  - name: a\n    type: [oops\n");
  refused(call<apex::LoadGraph>("load_graph", load), before, "line 5");
  writeFile(load.path,
            "apex_graph: 1\nnodes:\n  - {name: a, type: apex_nodes/Relay}\nconnections:\n  - {from: a/out, to: a/in}\n");
  refused(call<apex::LoadGraph>("load_graph", load), before, "line 5: cannot connect a/out -> a/in");

  load.path = tempPath("unknown.yaml");
  writeFile(load.path, "apex_graph: 1\nnodes:\n  - {name: old, type: retired/Thing, parameters: {k: 3}}\n");
  auto loaded = call<apex::LoadGraph>("load_graph", load);
  ASSERT_TRUE(loaded.success) << loaded.message;
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("unknown type 'retired/Thing'"));
  EXPECT_EQ(call<apex::GetGraph>("get_graph").graph.nodes.at(0).state, "placeholder");

  load.path = tempPath("saved.yaml");
  ASSERT_TRUE(call<apex::LoadGraph>("load_graph", load).success);
  EXPECT_EQ(call<apex::GetGraph>("get_graph").graph.nodes.at(0).name, "clock");
}

TEST_F(Services, SaveAndLoadTouchOnlyRegularFiles) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  const std::string before = graphText();
  apex::LoadGraph::Request load;
  load.path = tempPath("pipe.yaml");
  ASSERT_EQ(::mkfifo(load.path.c_str(), 0644), 0);
  const auto t0 = ros::WallTime::now();
  refused(call<apex::LoadGraph>("load_graph", load), before, "not a regular file");  // waited for a writer forever
  load.path = "/dev/zero";  // read without end; now outside the roots as well
  refused(call<apex::LoadGraph>("load_graph", load), before, "'/dev/zero'");
  EXPECT_LT((ros::WallTime::now() - t0).toSec(), 2.0);
  EXPECT_EQ(call<apex::GetGraph>("get_graph").graph.nodes.size(), 1u) << "the service threads are free";

  apex::SaveGraph::Request save;
  save.path = tempPath("pipe.yaml");
  auto res = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("not a regular file"));
  save.path = tempPath("locked.yaml");
  writeFile(save.path, "apex_graph: 2\n# kept\n");  // a graph: only its mode stops the save
  ASSERT_EQ(::chmod(save.path.c_str(), 0444), 0);
  res = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("read-only"));
  ::unlink(tempPath("pipe.yaml").c_str());
  ::unlink(tempPath("locked.yaml").c_str());
}

TEST_F(Services, PathsFromServicesStayInTheRoots) {  // services.test: ~file_roots [/tmp]
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  const std::string before = graphText();
  apex::SaveGraph::Request save;
  for (const std::string path : {"/etc/apex_probe.yaml", "/tmp/../etc/apex_probe.yaml", "/root/apex_probe.yaml"}) {
    save.path = path;
    auto res = call<apex::SaveGraph>("save_graph", save);
    EXPECT_FALSE(res.success) << path;
    EXPECT_THAT(res.message, HasSubstr("is outside the folders files may be written in (/tmp, ")) << path;
    const std::string folder = path.find("/root") == 0 ? "/root" : "/etc";  // what the user is told to allow
    EXPECT_THAT(res.message, HasSubstr("; to allow it, add its folder to the parameter /apex/file_roots "
                                       "(roslaunch apex runtime.launch file_roots:=" +
                                       folder + ")"))
        << path;
  }
  const std::string link = tempPath("etc_link");
  ASSERT_EQ(::symlink("/etc", link.c_str()), 0);
  save.path = link + "/apex_probe.yaml";
  EXPECT_THAT(call<apex::SaveGraph>("save_graph", save).message, HasSubstr("'/etc/apex_probe.yaml'"));
  struct stat st {};
  EXPECT_NE(::stat("/etc/apex_probe.yaml", &st), 0) << "created outside the roots";
  ::unlink(link.c_str());

  apex::LoadGraph::Request load;
  load.path = "/etc/passwd";
  auto loaded = call<apex::LoadGraph>("load_graph", load);
  EXPECT_FALSE(loaded.success);
  EXPECT_THAT(loaded.message, HasSubstr("outside"));
  EXPECT_THAT(loaded.message, Not(HasSubstr("root:")));  // nothing of the file is echoed
  EXPECT_EQ(graphText(), before);

  // path parameters: through set_parameter, add_node and the files load_graph reads
  ASSERT_TRUE(addNode("apex_nodes/ImageExport", "export").success);
  apex::SetParameter::Request set;
  set.node = "export", set.parameter = "directory", set.value = "/etc";
  auto res = call<apex::SetParameter>("set_parameter", set);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("node 'export': parameter 'directory': path '/etc' is outside"));
  EXPECT_EQ(res.value, "/tmp/apex_export");
  set.value = "/tmp/apex_no_such_folder/../apex_other";  // the system could not open it either
  EXPECT_THAT(call<apex::SetParameter>("set_parameter", set).message,
              HasSubstr("path '/tmp/apex_no_such_folder/../apex_other': '..' after a folder that does not exist"));
  ::mkdir("/tmp/apex_export", 0755);
  set.value = "/tmp/apex_export/../apex_other";
  res = call<apex::SetParameter>("set_parameter", set);
  EXPECT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.value, "/tmp/apex_other") << "passed on resolved";
  set.parameter = "prefix", set.value = "../../../../tmp/x/trav";
  EXPECT_THAT(call<apex::SetParameter>("set_parameter", set).message, HasSubstr("is a file name, not a path"));
  auto bag = addNode("apex_nodes/BagReader", "bag", "{file: /etc/shadow}");
  EXPECT_FALSE(bag.success);
  EXPECT_THAT(bag.message, HasSubstr("parameter 'file': path '/etc/shadow' is outside"));
  bag = addNode("BagReader", "bag", "{file: /etc/shadow}");  // its name alone: the same type, the same rule
  EXPECT_FALSE(bag.success);
  EXPECT_THAT(bag.message, HasSubstr("parameter 'file': path '/etc/shadow' is outside"));
  ASSERT_TRUE(addNode("apex_nodes/BagReader", "bag", "").success);
  set.node = "bag", set.parameter = "file", set.value = tempPath("no_such.bag");
  EXPECT_THAT(call<apex::SetParameter>("set_parameter", set).message, HasSubstr("no such file"));
  load.path = tempPath("reads_shadow.yaml");
  writeFile(load.path, "apex_graph: 1\nnodes:\n  - {name: b, type: apex_nodes/BagReader, parameters: {file: /etc/shadow}}\n");
  loaded = call<apex::LoadGraph>("load_graph", load);
  EXPECT_FALSE(loaded.success);
  EXPECT_THAT(loaded.message, HasSubstr("line 3: node 'b': parameter 'file': path '/etc/shadow' is outside"));
  ::unlink(load.path.c_str());
}

TEST_F(Services, ATruthIsAFileOrALabellingToolsFolder) {  // Pascal VOC, YOLO, labelme: a file per image
  ASSERT_TRUE(addNode("apex_nodes/RegionScore", "score").success);
  const std::string labels = tempPath("labels");
  ::mkdir(labels.c_str(), 0755);
  apex::SetParameter::Request set;
  set.node = "score", set.parameter = "truth", set.value = labels;
  auto res = call<apex::SetParameter>("set_parameter", set);
  EXPECT_TRUE(res.success) << res.message;
  set.value = tempPath("no_labels");
  res = call<apex::SetParameter>("set_parameter", set);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("no such file or folder"));
  set.value = "/etc";
  EXPECT_THAT(call<apex::SetParameter>("set_parameter", set).message, HasSubstr("is outside"));
  const auto info = call<apex::GetGraph>("get_graph").graph.nodes.at(0).parameters;
  const auto truth = std::find_if(info.begin(), info.end(), [](const auto& p) { return p.name == "truth"; });
  ASSERT_NE(truth, info.end());
  EXPECT_EQ(truth->path_mode, "read_file_or_folder");
  ::rmdir(labels.c_str());
}

TEST_F(Services, ARelativePathGoesToTheFirstRootAndShippedGraphsAreReadOnly) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  apex::SaveGraph::Request save;
  save.path = "apex_services_relative_" + std::to_string(getpid()) + ".yaml";  // ~file_roots [/tmp]: in /tmp
  auto saved = call<apex::SaveGraph>("save_graph", save);
  ASSERT_TRUE(saved.success) << saved.message;
  EXPECT_EQ(saved.path, "/tmp/" + save.path);
  struct stat st {};
  EXPECT_EQ(::stat(saved.path.c_str(), &st), 0);
  apex::LoadGraph::Request load;
  load.path = save.path;
  auto loaded = call<apex::LoadGraph>("load_graph", load);
  EXPECT_TRUE(loaded.success) << loaded.message;
  EXPECT_EQ(loaded.path, saved.path);
  ::unlink(saved.path.c_str());

  // The package's own graphs are read, never written (a user's tuning must not replace demo.yaml)
  const std::string shipped = ros::package::getPath("apex") + "/graphs/demo.yaml";
  std::ifstream in(shipped);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  save.path = shipped;
  saved = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(saved.success);
  EXPECT_THAT(saved.message, HasSubstr("/graphs', whose files may be read, not written: write it in one of /tmp, "));
  EXPECT_THAT(saved.message, HasSubstr("(a path without a folder, such as 'demo.yaml', goes to /tmp)"));
  std::ifstream again(shipped);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>()), text);
  load.path = "package://apex/graphs/demo.yaml";
  loaded = call<apex::LoadGraph>("load_graph", load);
  EXPECT_TRUE(loaded.success) << loaded.message;
  EXPECT_EQ(loaded.path, shipped);
}

TEST_F(Services, NoFileIsDestroyedAndALimitIsRefusedByTheServiceAsByAFile) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock").success);
  apex::SaveGraph::Request save;
  save.path = tempPath("run3.bag");
  const std::string bag = "#ROSBAG V2.0\nE\x01\x02 recorded data";
  writeFile(save.path, bag);
  auto saved = call<apex::SaveGraph>("save_graph", save);
  EXPECT_FALSE(saved.success);
  EXPECT_THAT(saved.message, HasSubstr("cannot save over '" + save.path + "': it is not a graph file"));
  std::ifstream in(save.path);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()), bag);
  ::unlink(save.path.c_str());

  // thread groups are threads: 256 at most, through add_node as through a file
  for (int i = 1; i < 256; ++i) ASSERT_TRUE(addNode("apex_nodes/Relay", "", "", "group_" + std::to_string(i)).success) << i;
  auto over = addNode("apex_nodes/Relay", "one_more", "", "group_256");
  EXPECT_FALSE(over.success);
  EXPECT_THAT(over.message, HasSubstr("the graph has 256 thread groups, the limit"));
  save.path = tempPath("at_the_limit.yaml");
  ASSERT_TRUE(call<apex::SaveGraph>("save_graph", save).success);
  apex::LoadGraph::Request load;
  load.path = save.path;
  auto loaded = call<apex::LoadGraph>("load_graph", load);
  EXPECT_TRUE(loaded.success) << loaded.message;  // what it saved, it loads
  ::unlink(save.path.c_str());
}

}  // namespace
