// Add, Throttle and TimeSync.
#include <ros/time.h>

#include <chrono>
#include <cmath>

#include "apex/core/registry.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Add : public apex::Node {
 public:
  static inline const apex::InputPort<double> kA{"a"};
  static inline const apex::InputPort<double> kB{"b"};
  static inline const apex::OutputPort<double> kSum{"sum"};
  static apex::Manifest manifest() {
    return apex::Manifest("Adds two numbers").inCategory("math").input(kA).input(kB).output(kSum);
  }
  void process() override { sum_.publish(*a_.get() + *b_.get()); }

 private:
  apex::Input<double> a_{this, kA};
  apex::Input<double> b_{this, kB};
  apex::Output<double> sum_{this, kSum};
};

class Throttle : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in"};
  static inline const apex::OutputPort<apex::Any> kOut{"out"};
  static inline const apex::ParamDecl<double> kRate =
      param::number("rate").range(0.01, 1000.0).step(0.01).init(5.0).describe("messages per second");
  static apex::Manifest manifest() {
    return apex::Manifest("Passes at most `rate` messages per second; sends Nothing for the others")
        .inCategory("flow")
        .input(kIn)
        .output(kOut)
        .param(kRate);
  }
  void process() override {
    const auto now = std::chrono::steady_clock::now();
    if (passed_once_ && std::chrono::duration<double>(now - last_).count() < 1.0 / rate_.get()) return;
    passed_once_ = true;
    last_ = now;
    out_.publishMessage(in_.take());
  }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<apex::Any> out_{this, kOut};
  apex::Param<double> rate_{this, kRate};
  bool passed_once_ = false;
  std::chrono::steady_clock::time_point last_;
};

/** "a", "b", ... : the ports of the i-th synchronised message. */
std::string letter(int i) { return std::string(1, static_cast<char>('a' + i)); }

class TimeSync : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kInA{"a", "an image, cloud, regions, clusters or scan"};
  static inline const apex::InputPort<apex::Any> kInB{"b"};
  static inline const apex::OutputPort<apex::Any> kOutA{"a"};
  static inline const apex::OutputPort<apex::Any> kOutB{"b"};
  static inline const apex::ParamDecl<int> kInputs = param::integer("inputs")
                                                         .range(2, 8)
                                                         .step(1)
                                                         .init(2)
                                                         .describe("how many messages to synchronise: a, b, c, ...")
                                                         .shapesInterface();
  static inline const apex::ParamDecl<double> kTolerance =
      param::number("tolerance").range(0.0, 10.0).step(0.001).init(0.05).describe("seconds");
  static apex::Manifest manifest() {
    return apex::Manifest("Passes its messages on only if their stamps lie within a tolerance; else Nothing on all")
        .inCategory("flow")
        .input(kInA)
        .input(kInB)
        .output(kOutA)
        .output(kOutB)
        .param(kInputs)
        .param(kTolerance)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          m.outputs.clear();
          for (int i = 0; i < p.get<int>(kInputs.name()); ++i) {
            m.input<apex::Any>(letter(i), i == 0 ? kInA.description : "");
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
      if (!header)
        throw std::invalid_argument("cannot read a stamp from a " + inputMessage(ports[i].name).typeName() + " on input '" +
                                    ports[i].name + "'");
      if (i == 0 || header->stamp < low) low = header->stamp;
      if (i == 0 || header->stamp > high) high = header->stamp;
    }
    if ((high - low).toSec() > tolerance_.get()) return;
    for (const auto& in : ports) publishMessage(in.name, inputMessage(in.name));
  }

 private:
  apex::Param<double> tolerance_{this, kTolerance};
};

/** The multiplexer (mux): passes on one of its inputs, to switch between variants of a pipeline while it
 *  runs. Demux (demux.cpp) is its opposite. */
class Select : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn0{"in_0", "", true};
  static inline const apex::InputPort<apex::Any> kIn1{"in_1", "", true};
  static inline const apex::OutputPort<apex::Any> kOut{"out"};
  static inline const apex::ParamDecl<int> kInputs =
      param::integer("inputs").range(2, 16).step(1).init(2).describe("how many inputs: in_0, in_1, ...").shapesInterface();
  static inline const apex::ParamDecl<int> kChoice =
      param::integer("choice").range(0, 15).step(1).describe("the input passed on").interactive();
  static apex::Manifest manifest() {
    return apex::Manifest("Passes on the input chosen by `choice`, a multiplexer (mux); the others are read and dropped")
        .inCategory("flow")
        .input(kIn0)
        .input(kIn1)
        .output(kOut)
        .param(kInputs)
        .param(kChoice)
        .shapedBy([](const apex::ParamValues& p, apex::Manifest& m) {
          m.inputs.clear();
          for (int i = 0; i < p.get<int>(kInputs.name()); ++i) m.optionalInput<apex::Any>("in_" + std::to_string(i));
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
  apex::Output<apex::Any> out_{this, kOut};
  apex::Param<int> choice_{this, kChoice};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Add, "apex_nodes/Add");
APEX_REGISTER_NODE(apex_nodes::Throttle, "apex_nodes/Throttle");
APEX_REGISTER_NODE(apex_nodes::TimeSync, "apex_nodes/TimeSync");
APEX_REGISTER_NODE(apex_nodes::Select, "apex_nodes/Select");
