// A node library one of whose types cannot register (a handle names an output its manifest does
// not declare): the runtime refuses the whole library and says why (services.test, through
// ros/broken_plugins.xml), instead of a line on stderr and a library with a type missing.
#include "apex/core/registry.hpp"
#include "apex/ros/node_library.hpp"

namespace apex_test {

class Fine : public apex::Node {
 public:
  static apex::Manifest manifest() { return apex::Manifest("registers, but its library is refused"); }
  void process() override {}
};

class Misnamed : public apex::Node {
 public:
  static apex::Manifest manifest() { return apex::Manifest("its handle names no output").output<int>("out"); }
  void process() override { value_.publish(1); }

 private:
  apex::Output<int> value_{this, "value"};
};

}  // namespace apex_test

APEX_REGISTER_NODE(apex_test::Fine, "apex_test/FineButRefused");
APEX_REGISTER_NODE(apex_test::Misnamed, "apex_test/Misnamed");
APEX_NODE_LIBRARY(apex_test_bad_registration)
