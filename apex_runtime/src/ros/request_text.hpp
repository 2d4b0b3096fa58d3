// Every text of a service request checked in one place, before any handler sees it: UTF-8 without
// control characters (apex::checkText), so that nothing a client sent can reach the graph, a
// file's name or another client's display as bytes it cannot show.
#pragma once

#include <ros/advertise_service_options.h>
#include <ros/message_traits.h>
#include <ros/node_handle.h>
#include <ros/serialization.h>
#include <ros/service_server.h>

#include <functional>
#include <string>
#include <vector>

#include "apex/core/text.hpp"

namespace apex {
namespace ros_host {

/** The names of a message's own fields, in order, from its definition's text. */
std::vector<std::string> fieldNames(const std::string& definition);

/** Walks a message's fields in the order roscpp's serializer does (its allInOne visits each with
 *  next()); strings are checked, the first bad one kept with the request's field it is in. */
class RequestText {
 public:
  explicit RequestText(std::vector<std::string> fields) : fields_(std::move(fields)) {}
  template <class T>
  void next(const T& value) {
    Field in(*this);
    if constexpr (ros::message_traits::IsMessage<T>::value)
      ros::serialization::Serializer<T>::template allInOne<RequestText, const T&>(*this, value);
  }
  template <class T>
  void next(const std::vector<T>& items) {
    Field in(*this);
    for (const auto& item : items) next(item);
  }
  void next(const std::string& text) {
    Field in(*this);
    if (!status_) return;
    if (auto st = checkText(text); !st) {
      const std::size_t k = static_cast<std::size_t>(field_);
      const std::string name = k < fields_.size() ? fields_[k] : "text";
      status_ = Status::error("'" + name + "' is refused: " + st.message() + " ('" + printable(text) + "')");
    }
  }
  const Status& status() const { return status_; }

 private:
  /** Depth in the request while a field is visited: its own fields count at depth 0. */
  struct Field {
    explicit Field(RequestText& r) : r(r) {
      if (r.depth_++ == 0) ++r.field_;
    }
    ~Field() { --r.depth_; }
    RequestText& r;
  };
  std::vector<std::string> fields_;
  int depth_ = 0, field_ = -1;
  Status status_ = Status::ok();
};

/** @brief OK if every string of `request` (in nested messages and lists too) is text; else which
 *  field holds one that is not. */
template <class Request>
Status checkRequestText(const Request& request) {
  RequestText check(fieldNames(ros::message_traits::definition<Request>()));
  ros::serialization::Serializer<Request>::template allInOne<RequestText, const Request&>(check, request);
  return check.status();
}

/** @brief Advertises `name` on `nh` with `handle` (on `queue`, if given), which sees only requests
 *  whose strings are all text: another is answered `success: false` with a message naming the
 *  field. Every service of the runtime is advertised through here. */
template <class Req, class Res>
ros::ServiceServer advertiseChecked(ros::NodeHandle& nh, const std::string& name, std::function<bool(Req&, Res&)> handle,
                                    ros::CallbackQueueInterface* queue = nullptr) {
  ros::AdvertiseServiceOptions options;
  options.template init<Req, Res>(name, [name, handle = std::move(handle)](Req& req, Res& res) {
    if (auto st = checkRequestText(req); !st) {
      res.success = false;
      res.message = name + ": " + st.message();
      return true;
    }
    return handle(req, res);
  });
  options.callback_queue = queue;  // none: the node handle's
  return nh.advertiseService(options);
}

}  // namespace ros_host
}  // namespace apex
