#include "request_text.hpp"

#include <sstream>

namespace apex {
namespace ros_host {

std::vector<std::string> fieldNames(const std::string& definition) {
  std::vector<std::string> names;
  std::istringstream lines(definition);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("===", 0) == 0) break;  // the definitions of the message types it uses follow
    line = line.substr(0, line.find('#'));
    if (line.find('=') != std::string::npos) continue;  // a constant
    std::istringstream words(line);
    std::string type, name;
    if (words >> type >> name) names.push_back(name);
  }
  return names;
}

}  // namespace ros_host
}  // namespace apex
