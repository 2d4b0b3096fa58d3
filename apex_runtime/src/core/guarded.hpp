// A value and the mutex that guards it, in one type: the value is reached only through the
// handle lock() returns, which holds the mutex while it lives (NodeState::Shared).
#pragma once

#include <mutex>

namespace apex {
namespace detail {

/** A value reached only with its mutex held: lock() returns a handle that holds the lock for as
 *  long as it lives (`auto s = shared_.lock(); s->error = ...`). */
template <class T>
class Guarded {
 public:
  template <class V>
  class Handle {
   public:
    V* operator->() const { return &v_; }
    V& operator*() const { return v_; }

   private:
    friend class Guarded;
    Handle(std::mutex& m, V& v) : lock_(m), v_(v) {}
    std::lock_guard<std::mutex> lock_;
    V& v_;
  };
  Handle<T> lock() { return {m_, v_}; }
  Handle<const T> lock() const { return {m_, v_}; }

 private:
  mutable std::mutex m_;
  T v_;
};

}  // namespace detail
}  // namespace apex
