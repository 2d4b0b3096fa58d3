// ROS messages of any type, read field by field from their serialized bytes and the text of their
// definition (as ros::message_traits::definition, a connection header or a bag gives it: the type's
// own fields, then a `MSG: pkg/Type` section per type it uses). Pure C++ (no ROS): text and bytes
// in, a value or an error out. Every read is bounds-checked: a truncated message is an error.
// Bytes are ROS's serialization: little-endian, unaligned (read with memcpy), arrays of variable
// length and strings after a uint32 count, fixed arrays without one.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace apex_nodes {

/** @brief A read past the end of a message's bytes. */
struct TruncatedMessage : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/** @brief Reads serialized bytes front to back; every read checks the bytes are there. */
class ByteCursor {
 public:
  ByteCursor(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  /** @brief The next `n` bytes; throws TruncatedMessage if fewer are left. */
  const std::uint8_t* take(std::uint64_t n) {
    if (n > size_ - pos_)
      throw TruncatedMessage("the message ends at byte " + std::to_string(size_) + ": " + std::to_string(n) +
                             " bytes wanted at byte " + std::to_string(pos_));
    const std::uint8_t* at = data_ + pos_;
    pos_ += static_cast<std::size_t>(n);
    return at;
  }
  /** @brief Throws TruncatedMessage unless `count` elements of `each` bytes are left. */
  void require(std::uint64_t count, std::uint64_t each) const {
    if (each != 0 && count > left() / each)
      throw TruncatedMessage("the message ends at byte " + std::to_string(size_) + ": " + std::to_string(count) + " x " +
                             std::to_string(each) + " bytes wanted at byte " + std::to_string(pos_));
  }
  template <class T>
  T next() {
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));  // unaligned: memcpy, never a cast
    return v;
  }
  /** @brief A string: its uint32 length, then its bytes. */
  std::string text() {
    const auto n = next<std::uint32_t>();
    const std::uint8_t* p = take(n);
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  std::size_t left() const { return size_ - pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

struct MessageType;

/** @brief One field of a message type, in serialization order. */
struct MessageField {
  enum class Kind {
    Bool,
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float32,
    Float64,
    String,
    Time,
    Duration,
    Message
  };
  enum class Array { None, Fixed, Variable };
  std::string name;
  std::string type;  ///< resolved: "float64", "string", "geometry_msgs/Pose" (a bare Header: std_msgs/Header)
  Kind kind = Kind::Bool;
  Array array = Array::None;
  std::uint32_t length = 0;  ///< a fixed array's
  const MessageType* message = nullptr;  ///< Kind::Message: its type
  std::optional<std::uint64_t> element_size;  ///< bytes of one element, when every element has the same size
  std::optional<std::uint64_t> size;  ///< bytes of the whole field, when fixed

  /** "float32[]", "geometry_msgs/Pose[3]": the type as the definition writes it, resolved. */
  std::string typeText() const;
};

/** @brief A message type: its fields, and its size when every message of it has the same. */
struct MessageType {
  std::string name;  ///< e.g. "nav_msgs/Odometry"
  std::vector<MessageField> fields;
  std::optional<std::uint64_t> size;

  const MessageField* find(const std::string& field) const;
  /** "header, child_frame_id, pose, twist": for errors. */
  std::string fieldNames() const;
};

/** @brief The types of one full definition: its own (the root) and those of its MSG: sections. */
class MessageSchema {
 public:
  /** @brief Parses `definition` of `datatype`. Throws std::invalid_argument naming the type and
   *  line at fault: a line that is not a field or constant, a type with no MSG: section, a type
   *  that contains itself or is nested over 100 deep. */
  MessageSchema(const std::string& datatype, const std::string& definition);
  MessageSchema(const MessageSchema&) = delete;  // fields point into types_
  MessageSchema& operator=(const MessageSchema&) = delete;

  const MessageType& root() const { return *root_; }
  /** @brief Throws std::invalid_argument unless `data` holds a whole message of the root type
   *  (every count within the bytes); bytes after it are allowed, as ROS allows them. */
  void check(const std::uint8_t* data, std::size_t size) const;

 private:
  void resolve();
  /** Resolves t's message fields and finds its size; `done`: false while t is being sized. */
  void sizeType(MessageType& t, std::map<const MessageType*, bool>& done, int depth);
  std::map<std::string, MessageType> types_;
  const MessageType* root_ = nullptr;
};

/** @brief One numeric field of a schema's messages, by path (`pose.pose.position.x`,
 *  `ranges[3]`, `header.stamp`): the path is checked against the schema once, then read from
 *  each message. Numbers: bool (0 or 1), the integer and float types, byte and char, time and
 *  duration (in seconds; `header.stamp.secs` and `.nsecs` as rostopic echo shows them). */
class FieldReader {
 public:
  /** @brief Throws std::invalid_argument for a path that names no field (listing the fields at
   *  the level where the lookup failed), a field that is not a number, an array without an index,
   *  an index on a field that is not an array, or past a fixed array's end. */
  FieldReader(std::shared_ptr<const MessageSchema> schema, const std::string& path);
  /** @brief The field's value in one message's bytes. Throws std::invalid_argument for a
   *  message too short for it, or an index past the end of its array. */
  double read(const std::uint8_t* data, std::size_t size) const;
  const std::string& path() const { return path_; }

 private:
  struct Step {
    const MessageType* in;  // the message the field is in
    std::size_t field;  // its index in in->fields
    bool indexed;
    std::uint32_t index;
    std::string path;  // up to and with this step, for errors
  };
  void addStep(const MessageType& in, const std::string& component);
  /** `secs` or `nsecs` after a time or duration: that part alone; false for anything else. */
  bool addTimePart(const std::string& component);
  const MessageField& leaf() const;  // the field of the last step
  std::shared_ptr<const MessageSchema> schema_;
  std::string path_;
  std::vector<Step> steps_;
  int time_part_ = 0;  // 0: the time in seconds; 1: its secs; 2: its nsecs
};

/** @brief True when the definition's first field is `Header header`: its messages then start
 *  with a std_msgs/Header (seq, stamp, frame_id). */
bool startsWithHeader(const std::string& definition);

}  // namespace apex_nodes
