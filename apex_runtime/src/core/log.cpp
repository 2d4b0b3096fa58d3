#include "apex/core/log.hpp"

#include <iostream>
#include <memory>
#include <mutex>

namespace apex {
namespace {

std::mutex& sinkMutex() {
  static std::mutex m;
  return m;
}

std::shared_ptr<const LogSink>& current() {
  static std::shared_ptr<const LogSink> sink;
  return sink;
}

}  // namespace

void setLogSink(LogSink sink) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  current() = sink ? std::make_shared<const LogSink>(std::move(sink)) : nullptr;
}

void log(LogLevel level, const std::string& node, const std::string& text) {
  std::shared_ptr<const LogSink> sink;
  {
    std::lock_guard<std::mutex> lock(sinkMutex());
    sink = current();
  }
  if (sink) return (*sink)(level, node, text);
  static const char* kNames[] = {"debug", "info", "warn", "error"};
  std::lock_guard<std::mutex> lock(sinkMutex());
  std::cerr << "[apex " << kNames[static_cast<int>(level)] << "] " << (node.empty() ? "" : node + ": ") << text << "\n";
}

}  // namespace apex
