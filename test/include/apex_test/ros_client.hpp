// Calling the runtime's services from rostest gtests: wait for the service,
// call, fail the test with the service's message when asked to.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <apex/GetGraph.h>

#include <string>

namespace apex_test {

inline std::string service(const std::string& name) { return "/apex/" + name; }

/** Calls a service; ADD_FAILURE if the call itself fails (not if success is false). */
template <class Srv>
typename Srv::Response call(const std::string& name, typename Srv::Request req = {}) {
  Srv srv;
  srv.request = req;
  const std::string full = service(name);
  if (!ros::service::waitForService(full, ros::Duration(20))) ADD_FAILURE() << full << " never appeared";
  if (!ros::service::call(full, srv)) ADD_FAILURE() << "calling " << full << " failed";
  return srv.response;
}

/** The graph as file text: compared before and after a refused edit. */
inline std::string graphText() { return call<apex::GetGraph>("get_graph").yaml; }

}  // namespace apex_test
