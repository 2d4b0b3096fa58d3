// Where the core and node code log to: stderr by default; a host installs its
// own sink (the ROS host sends it to rosconsole, named after the node).
#pragma once

#include <functional>
#include <string>

namespace apex {

enum class LogLevel { Debug, Info, Warn, Error };

/** @brief Receives every log line: its level, the node's name ("" for the runtime) and the text. */
using LogSink = std::function<void(LogLevel, const std::string& node, const std::string& text)>;

/** @brief Replaces the process-wide sink; an empty sink restores stderr. Thread-safe. */
void setLogSink(LogSink sink);
/** @brief Logs through the current sink. Thread-safe; not for per-firing chatter. */
void log(LogLevel level, const std::string& node, const std::string& text);

}  // namespace apex
