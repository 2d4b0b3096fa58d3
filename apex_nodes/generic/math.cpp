// Add, Throttle and TimeSync.
#include <ros/time.h>

#include <chrono>
#include <cmath>

#include "apex/ros/node_plugin.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

class Add : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Adds two numbers").input<double>("a").input<double>("b").output<double>("sum");
  }
  void process() override { publish("sum", *input<double>("a") + *input<double>("b")); }
};

class Throttle : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Passes at most `rate` messages per second; sends Nothing for the others")
        .input<apex::Any>("in")
        .output<apex::Any>("out")
        .param(apex::param::range("rate", 0.01, 1000.0, 0.01, 5.0).describe("messages per second"));
  }
  void process() override {
    const auto now = std::chrono::steady_clock::now();
    if (passed_once_ && std::chrono::duration<double>(now - last_).count() < 1.0 / param<double>("rate")) return;
    passed_once_ = true;
    last_ = now;
    publishMessage("out", inputMessage("in"));
  }

 private:
  bool passed_once_ = false;
  std::chrono::steady_clock::time_point last_;
};

class TimeSync : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Passes a pair on only if their stamps lie within a tolerance; else Nothing on both")
        .input<apex::Any>("a", "an image, cloud, regions, clusters or scan")
        .input<apex::Any>("b")
        .output<apex::Any>("a")
        .output<apex::Any>("b")
        .param(apex::param::range("tolerance", 0.0, 10.0, 0.001, 0.05).describe("seconds"));
  }
  void process() override {
    const auto a = headerOf(inputMessage("a")), b = headerOf(inputMessage("b"));
    if (!a || !b)
      throw std::invalid_argument("cannot read a stamp from a " + (a ? inputMessage("b") : inputMessage("a")).typeName());
    if (std::abs((a->stamp - b->stamp).toSec()) > param<double>("tolerance")) return;
    publishMessage("a", inputMessage("a"));
    publishMessage("b", inputMessage("b"));
  }
};

}  // namespace apex_nodes

APEX_EXPORT_NODE(apex_nodes, Add, apex_nodes::Add);
APEX_EXPORT_NODE(apex_nodes, Throttle, apex_nodes::Throttle);
APEX_EXPORT_NODE(apex_nodes, TimeSync, apex_nodes::TimeSync);
