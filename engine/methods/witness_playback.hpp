// The "witness" lane: plays back a scenario's witness trajectory. Found by
// find_method() like a method, but not in method_registry(): it resolves no
// redundancy and runs only scenarios that carry a witness.
#pragma once

#include <rrlab/methods/registry.hpp>

namespace rrlab {

inline constexpr const char* kWitnessMethod = "witness";
const MethodInfo& witness_method_info();

}  // namespace rrlab
