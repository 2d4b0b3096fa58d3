#include "node_log.hpp"

#include <log4cxx/helpers/transcoder.h>
#include <log4cxx/logger.h>
#include <log4cxx/logmanager.h>
#include <ros/console.h>
#include <ros/service_manager.h>
#include <roscpp/GetLoggers.h>
#include <roscpp/SetLoggerLevel.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <mutex>

#include "apex/core/log.hpp"

namespace apex {
namespace ros_host {
namespace {

ros::console::Level rosLevel(LogLevel level) {
  switch (level) {
    case LogLevel::Debug:
      return ros::console::levels::Debug;
    case LogLevel::Info:
      return ros::console::levels::Info;
    case LogLevel::Warn:
      return ros::console::levels::Warn;
    case LogLevel::Error:
      break;
  }
  return ros::console::levels::Error;
}

/** Whether a line at `level` on logger `name` is logged now, and its logger. rosconsole keeps a
 *  pointer to every location it initialised (to update them when a level is set), so these live
 *  as long as the process: one per logger and level, never removed. */
bool enabled(const std::string& name, ros::console::Level level, void** logger) {
  // Never destroyed, not even at exit: a thread that logs late, or rosconsole updating levels,
  // must not meet freed locations.
  static auto* mutex = new std::mutex;
  static auto* locations = new std::map<std::pair<std::string, ros::console::Level>, ros::console::LogLocation>;
  std::lock_guard<std::mutex> lock(*mutex);
  auto [it, added] = locations->try_emplace({name, level}, ros::console::LogLocation{false, false, level, nullptr});
  ros::console::LogLocation& loc = it->second;
  if (!loc.initialized_) ros::console::initializeLogLocation(&loc, name, level);
  ros::console::checkLogLocationEnabled(&loc);
  *logger = loc.logger_;
  return loc.logger_enabled_;
}

std::string levelName(const log4cxx::LevelPtr& level) {
  const int v = level ? level->toInt() : log4cxx::Level::INFO_INT;
  if (v <= log4cxx::Level::DEBUG_INT) return "debug";
  if (v <= log4cxx::Level::INFO_INT) return "info";
  if (v <= log4cxx::Level::WARN_INT) return "warn";
  if (v <= log4cxx::Level::ERROR_INT) return "error";
  return "fatal";
}

log4cxx::LevelPtr levelNamed(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  if (name == "debug") return log4cxx::Level::getDebug();
  if (name == "info") return log4cxx::Level::getInfo();
  if (name == "warn") return log4cxx::Level::getWarn();
  if (name == "error") return log4cxx::Level::getError();
  if (name == "fatal") return log4cxx::Level::getFatal();
  return {};
}

bool getLoggers(roscpp::GetLoggers::Request&, roscpp::GetLoggers::Response& res) {
  for (const log4cxx::LoggerPtr& logger : log4cxx::LogManager::getCurrentLoggers()) {
    roscpp::Logger out;
    LOG4CXX_ENCODE_CHAR(name, logger->getName());
    out.name = name;
    out.level = levelName(logger->getEffectiveLevel());
    res.loggers.push_back(out);
  }
  return true;
}

bool setLoggerLevel(roscpp::SetLoggerLevel::Request& req, roscpp::SetLoggerLevel::Response&) {
  const log4cxx::LevelPtr level = levelNamed(req.level);
  if (!level) {
    ROS_ERROR_STREAM_NAMED("apex", "set_logger_level: unknown level '" << req.level << "' (debug, info, warn, error, fatal)");
    return false;
  }
  LOG4CXX_DECODE_CHAR(name, req.logger);
  log4cxx::Logger::getLogger(name)->setLevel(level);
  ros::console::notifyLoggerLevelsChanged();
  return true;
}

}  // namespace

std::vector<ros::ServiceServer> serveLoggerServices(ros::NodeHandle& pnh) {
  if (pnh.getNamespace() != ros::this_node::getName()) return {};
  for (const char* service : {"/get_loggers", "/set_logger_level"})
    ros::ServiceManager::instance()->unadvertiseService(ros::this_node::getName() + service);
  return {pnh.advertiseService("get_loggers", getLoggers), pnh.advertiseService("set_logger_level", setLoggerLevel)};
}

std::string nodeLoggerName(const std::string& node_path) {
  std::string name = std::string(ROSCONSOLE_DEFAULT_NAME) + "." + node_path;
  std::replace(name.begin() + static_cast<std::ptrdiff_t>(std::string(ROSCONSOLE_DEFAULT_NAME).size()), name.end(), '/', '.');
  return name;
}

void installRosconsoleSink() {
  setLogSink([](LogLevel level, const std::string& node, const std::string& text) {
    const std::string name = node.empty() ? std::string(ROSCONSOLE_DEFAULT_NAME) + ".apex" : nodeLoggerName(node);
    const ros::console::Level at = rosLevel(level);
    void* logger = nullptr;
    if (!enabled(name, at, &logger)) return;
    const std::string line = node.empty() ? text : "[" + node + "] " + text;
    ros::console::print(nullptr, logger, at, __FILE__, __LINE__, __ROSCONSOLE_FUNCTION__, "%s", line.c_str());
  });
}

}  // namespace ros_host
}  // namespace apex
