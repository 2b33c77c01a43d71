// The explicit table of every method: name, description, parameter specs
// and a factory. CLI, REST and scenarios look methods up here by name.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "methods/method.hpp"

namespace rrlab {

struct MethodInfo {
  std::string name, description;
  std::vector<ParamSpec> params;
  std::unique_ptr<Method> (*make)(const MethodContext&);
};

const std::vector<MethodInfo>& method_registry();
// nullptr when unknown; also finds "witness" (methods/witness_playback.hpp),
// which the registry does not list
const MethodInfo* find_method(std::string_view name);
std::string method_names();  // "pinv, dls, ..." for error messages

}  // namespace rrlab
