// Messages: immutable, shared payloads with a readable type name, or Nothing.
// One output feeding N inputs hands the same object to all N: no copies.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

namespace apex {

/** @brief Reads a payload's own stamp, ns since the epoch (a ROS header's), or 0 if it has none. */
using StampReader = std::int64_t (*)(const void* payload);

/** @brief A port or message type: one instance per C++ type in the process. */
struct TypeInfo {
  std::string name;  ///< readable, e.g. "int", "cv::Mat"
  std::type_index index;  ///< the C++ type
  /** How a payload of this type tells its frame's stamp (readStampWith); none: it inherits one. */
  mutable std::atomic<StampReader> stamp{nullptr};
};

/** @brief Marker type for ports that accept or send any message (e.g. a relay). */
struct Any {};

/** @brief The payload of the end-of-sequence token (Message::endOfSequence()). */
struct EndOfSequence {};

/** @brief Readable type names; specialise for your own types, or use APEX_TYPE_NAME. */
template <class T>
struct TypeName {
  static std::string get();  // default: the demangled C++ name
};

namespace detail {
std::string demangle(const char* mangled);
/** Interns (type, name) in a process-wide table so types compare by pointer
 *  even across plugin libraries. */
const TypeInfo* internType(const std::type_info& type, const std::string& name);
/** typeOf<EndOfSequence>(), read once when the core library loads: isEndOfSequence() is asked
 *  several times per firing, and a function-local static costs a guard check and a call. */
extern const TypeInfo* const kEndOfSequenceType;
}  // namespace detail

template <class T>
std::string TypeName<T>::get() {
  return detail::demangle(typeid(T).name());
}

/** @brief The TypeInfo of T; the same pointer everywhere in the process. */
template <class T>
const TypeInfo* typeOf() {
  static const TypeInfo* info = detail::internType(typeid(T), TypeName<T>::get());
  return info;
}

/** @brief Payloads of type T carry their own stamp, read by `reader` (e.g. a ROS header's): a
 *  message of T names its frame by it (Message::frame). Once per type, by the library defining it. */
template <class T>
void readStampWith(StampReader reader) {
  typeOf<T>()->stamp.store(reader, std::memory_order_relaxed);
}

/** @brief True when an output of type `from` may feed an input of type `to`. */
inline bool compatible(const TypeInfo* from, const TypeInfo* to) {
  return from == to || from == typeOf<Any>() || to == typeOf<Any>();
}

/** @brief A shared, immutable payload or the Nothing token. Cheap to copy. */
class Message {
 public:
  /** @brief The Nothing token: "this output sent nothing this time". */
  Message() = default;
  static Message nothing() { return Message(); }
  Message(const Message&) = default;
  Message& operator=(const Message&) = default;
  /** @brief A moved-from message is Nothing. */
  Message(Message&& o) noexcept : data_(std::move(o.data_)), type_(o.type_), frame_(o.frame_) { o.type_ = nullptr; }
  Message& operator=(Message&& o) noexcept {
    data_ = std::move(o.data_);
    type_ = o.type_;
    frame_ = o.frame_;
    if (&o != this) o.type_ = nullptr;
    return *this;
  }

  template <class T>
  static Message share(std::shared_ptr<const T> payload) {
    return Message(std::shared_ptr<const void>(std::move(payload)), typeOf<T>());
  }
  template <class T>
  static Message make(T value) {
    return share<T>(std::make_shared<const T>(std::move(value)));
  }

  /** @brief The end-of-sequence token: a source that plays a sequence (a bag's pass) sends it
   *  on every output after the last frame. It travels like a frame, so it reaches every node
   *  downstream after that frame: a node is told in Node::endOfSequence() instead of
   *  process(), and by default sends it on. It passes every output, whatever its type. */
  static Message endOfSequence();

  bool isNothing() const { return data_ == nullptr; }
  bool isEndOfSequence() const;
  /** @brief The payload's type; nullptr for Nothing. */
  const TypeInfo* type() const { return type_; }
  /** @brief The payload's readable type name, "Nothing" for the token. */
  const std::string& typeName() const;

  /** @brief The payload as T; nullptr when Nothing or of another type. */
  template <class T>
  std::shared_ptr<const T> as() const {
    if (type_ != typeOf<T>()) return nullptr;
    return std::static_pointer_cast<const T>(data_);
  }
  const void* raw() const { return data_.get(); }

  /** @brief The stamp (ns since the epoch) of the frame this message belongs to, 0 if unknown: the
   *  newest of the frames its sender's firing took in or, from a source, the payload stamp
   *  (readStampWith) of the first message that firing sent with one. So everything one firing of
   *  a source causes is one frame (a bag's image and cloud alike). Set by the graph as the message
   *  leaves its node; the trace and latencies follow frames by it. */
  std::int64_t frame() const { return frame_; }
  void setFrame(std::int64_t frame) { frame_ = frame; }
  /** @brief The payload's own stamp (readStampWith), 0 if its type has none. */
  std::int64_t payloadStamp() const {
    const StampReader read = type_ ? type_->stamp.load(std::memory_order_relaxed) : nullptr;
    return read ? read(data_.get()) : 0;
  }

 private:
  Message(std::shared_ptr<const void> d, const TypeInfo* t) : data_(std::move(d)), type_(t) {}
  std::shared_ptr<const void> data_;
  const TypeInfo* type_ = nullptr;
  std::int64_t frame_ = 0;
};

}  // namespace apex

/** Give a type a readable name: APEX_TYPE_NAME(cv::Mat, "cv::Mat") at namespace scope. */
#define APEX_TYPE_NAME(Type, Name)            \
  template <>                                 \
  struct apex::TypeName<Type> {               \
    static std::string get() { return Name; } \
  }

APEX_TYPE_NAME(bool, "bool");
APEX_TYPE_NAME(int, "int");
APEX_TYPE_NAME(double, "double");
APEX_TYPE_NAME(std::string, "string");
APEX_TYPE_NAME(std::vector<double>, "list<double>");
APEX_TYPE_NAME(apex::Any, "any");
APEX_TYPE_NAME(apex::EndOfSequence, "end of sequence");

// kEndOfSequenceType is null only before the core library's static initialisation: Nothing (a
// null type_) must not match it then.
inline bool apex::Message::isEndOfSequence() const { return type_ != nullptr && type_ == detail::kEndOfSequenceType; }
