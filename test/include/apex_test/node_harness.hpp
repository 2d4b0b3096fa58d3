// Runs one node type, loaded through pluginlib as the runtime loads it, on
// messages a test gives it: source → node → sink, one message at a time.
#pragma once

#include <gtest/gtest.h>

#include <deque>

#include "apex_test/test_nodes.hpp"
#include "plugin_types.hpp"  // apex_runtime/src/ros

namespace apex_test {

/** A driven source of any messages, fed by the test. */
class MessageFeeder : public Node {
 public:
  static Manifest manifest() { return Manifest().output<Any>("out").driven(); }
  void feed(Message m) {
    {
      std::lock_guard<std::mutex> l(m_);
      queue_.push_back(std::move(m));
    }
    notifyNewData();
  }
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    if (queue_.empty()) return;
    publishMessage("out", queue_.front());
    queue_.pop_front();
    if (!queue_.empty()) notifyNewData();
  }

 private:
  std::mutex m_;
  std::deque<Message> queue_;
};

/** The plugin types once per process (their libraries stay loaded). */
inline const NodeRegistry& pluginRegistry() {
  static NodeRegistry* registry = [] {
    auto* r = new NodeRegistry(testRegistry());
    static auto* types = new apex::ros_host::PluginTypes;  // never unloaded: node code lives in its libraries
    for (const auto& e : types->registerAll(*r)) ADD_FAILURE() << e;
    EXPECT_TRUE(r->add<MessageFeeder>("test/MessageFeeder"));
    return r;
  }();
  return *registry;
}

class NodeHarness {
 public:
  /** `type` with inputs fed in order from `inputs` and its `output` collected; `ports`:
   *  parameters set first, e.g. {{"inputs", "3"}} for a node whose ports follow them. */
  NodeHarness(const std::string& type, std::vector<std::string> inputs, const std::string& output,
              const std::vector<std::pair<std::string, std::string>>& ports = {})
      : graph_(pluginRegistry()), inputs_(std::move(inputs)) {
    add(graph_, type, "node");
    for (const auto& [param, value] : ports) set(param, value);
    for (std::size_t i = 0; i < inputs_.size(); ++i) {
      add(graph_, "test/MessageFeeder", "in" + std::to_string(i));
      link(graph_, "in" + std::to_string(i), "out", "node", inputs_[i]);
    }
    add(graph_, "test/Collector", "sink");
    link(graph_, "node", output, "sink", "in");
    graph_.start();
  }
  Graph& graph() { return graph_; }
  void set(const std::string& param, const std::string& value) {
    auto r = graph_.setParameter("node", param, value);
    ASSERT_TRUE(r) << r.message();
  }
  /** Feeds one message per input and returns what the node sent (Nothing on error). */
  Message run(const std::vector<Message>& messages) {
    auto* sink = object<Collector>(graph_, "sink");
    const auto before = sink->size();
    for (std::size_t i = 0; i < messages.size(); ++i) object<MessageFeeder>(graph_, "in" + std::to_string(i))->feed(messages[i]);
    EXPECT_TRUE(sink->waitFor(before + 1)) << "the node sent nothing";
    EXPECT_TRUE(graph_.waitIdle(kWait));
    const auto sent = sink->messages();
    return sent.size() > before ? sent.back() : Message();  // Nothing when the node sent nothing in time
  }
  template <class T>
  Message run(std::shared_ptr<const T> payload) {
    return run(std::vector<Message>{Message::share<T>(payload)});
  }
  std::string error() { return graph_.nodeStats().at(0).error; }

 private:
  Graph graph_;
  std::vector<std::string> inputs_;
};

}  // namespace apex_test
