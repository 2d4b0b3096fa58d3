#include "apex/core/message.hpp"

#include <cxxabi.h>

#include <cstdlib>
#include <map>
#include <set>
#include <mutex>

namespace apex {
namespace detail {

std::string demangle(const char* mangled) {
  int status = 0;
  char* out = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
  std::string name = (status == 0 && out) ? out : mangled;
  std::free(out);
  return name;
}

const TypeInfo* internType(const std::type_info& type, const std::string& name) {
  // Types live for the whole process: plugin libraries may be unloaded, but a
  // TypeInfo they created must stay valid for messages still in flight.
  static std::mutex mutex;
  // Names are unique, so that rules and front ends can compare types by name: a second
  // C++ type given a name already taken keeps its mangled name as well.
  static auto* table = new std::map<std::type_index, TypeInfo*>();
  static auto* names = new std::set<std::string>();
  std::lock_guard<std::mutex> lock(mutex);
  auto [it, inserted] = table->emplace(std::type_index(type), nullptr);
  if (inserted) {
    const std::string unique = names->insert(name).second ? name : name + " (" + type.name() + ")";
    names->insert(unique);
    it->second = new TypeInfo{unique, std::type_index(type)};
  }
  return it->second;
}

const TypeInfo* const kEndOfSequenceType = typeOf<EndOfSequence>();

}  // namespace detail

Message Message::endOfSequence() {
  static const auto kToken = std::make_shared<const EndOfSequence>();  // one for the process: no allocation per pass
  return share<EndOfSequence>(kToken);
}

const std::string& Message::typeName() const {
  static const std::string kNothing = "Nothing";
  return type_ ? type_->name : kNothing;
}

}  // namespace apex
