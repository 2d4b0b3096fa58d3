// Add, Throttle and TimeSync.
#include <ros/time.h>

#include <chrono>
#include <cmath>

#include "apex/core/registry.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

class Add : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Adds two numbers").input<double>("a").input<double>("b").output<double>("sum");
  }
  void process() override { sum_.publish(*a_.get() + *b_.get()); }

 private:
  apex::Input<double> a_{this, "a"};
  apex::Input<double> b_{this, "b"};
  apex::Output<double> sum_{this, "sum"};
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
    if (passed_once_ && std::chrono::duration<double>(now - last_).count() < 1.0 / rate_.get()) return;
    passed_once_ = true;
    last_ = now;
    out_.publishMessage(in_.message());
  }

 private:
  apex::Input<apex::Any> in_{this, "in"};
  apex::Output<apex::Any> out_{this, "out"};
  apex::Param<double> rate_{this, "rate"};
  bool passed_once_ = false;
  std::chrono::steady_clock::time_point last_;
};

/** "a", "b", ... : the ports of the i-th synchronised message. */
std::string letter(int i) { return std::string(1, static_cast<char>('a' + i)); }

class TimeSync : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Passes its messages on only if their stamps lie within a tolerance; else Nothing on all")
        .input<apex::Any>("a", "an image, cloud, regions, clusters or scan")
        .input<apex::Any>("b")
        .output<apex::Any>("a")
        .output<apex::Any>("b")
        .param(apex::param::range("inputs", 2, 8, 1, 2).describe("how many messages to synchronise: a, b, c, ...").shapesInterface())
        .param(apex::param::range("tolerance", 0.0, 10.0, 0.001, 0.05).describe("seconds"))
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          m.outputs.clear();
          for (int i = 0; i < p.get<int>("inputs"); ++i) {
            m.input<apex::Any>(letter(i), i == 0 ? "an image, cloud, regions, clusters or scan" : "");
            m.output<apex::Any>(letter(i));
          }
          return apex::Status::ok();
        });
  }
  void process() override {
    const auto& ports = interface().inputs;
    ros::Time low, high;
    for (std::size_t i = 0; i < ports.size(); ++i) {
      const auto header = headerOf(inputMessage(ports[i].name));
      if (!header) throw std::invalid_argument("cannot read a stamp from a " + inputMessage(ports[i].name).typeName() +
                                               " on input '" + ports[i].name + "'");
      if (i == 0 || header->stamp < low) low = header->stamp;
      if (i == 0 || header->stamp > high) high = header->stamp;
    }
    if ((high - low).toSec() > tolerance_.get()) return;
    for (const auto& in : ports) publishMessage(in.name, inputMessage(in.name));
  }

 private:
  apex::Param<double> tolerance_{this, "tolerance"};
};

/** Passes on one of its inputs: switch between variants of a pipeline while it runs. */
class Select : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Passes on the input chosen by `choice`; the others are read and dropped")
        .optionalInput<apex::Any>("in_0")
        .optionalInput<apex::Any>("in_1")
        .output<apex::Any>("out")
        .param(apex::param::range("inputs", 2, 16, 1, 2).describe("how many inputs: in_0, in_1, ...").shapesInterface())
        .param(apex::param::range("choice", 0, 15, 1, 0).describe("the input passed on").makeInteractive())
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          for (int i = 0; i < p.get<int>("inputs"); ++i) m.optionalInput<apex::Any>("in_" + std::to_string(i));
          return apex::Status::ok();
        });
  }
  void process() override {
    const auto& ports = interface().inputs;
    const int choice = choice_.get();
    if (choice >= static_cast<int>(ports.size()))
      throw std::invalid_argument("choice " + std::to_string(choice) + " but only " + std::to_string(ports.size()) + " inputs");
    out_.publishMessage(inputMessage(ports[choice].name));
  }

 private:
  apex::Output<apex::Any> out_{this, "out"};
  apex::Param<int> choice_{this, "choice"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Add, "apex_nodes/Add");
APEX_REGISTER_NODE(apex_nodes::Throttle, "apex_nodes/Throttle");
APEX_REGISTER_NODE(apex_nodes::TimeSync, "apex_nodes/TimeSync");
APEX_REGISTER_NODE(apex_nodes::Select, "apex_nodes/Select");
