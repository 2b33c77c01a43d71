#include "method_reentry.hpp"

#include "python_method.hpp"

namespace rrlab::python {

namespace {
// the method code this thread is in (a sweep's workers each have their own)
thread_local const std::string* running = nullptr;
}  // namespace

InMethodCode::InMethodCode(const std::string& where) : outer_(running) { running = &where; }

InMethodCode::~InMethodCode() { running = outer_; }

void refuse_reentry(const char* call) {
  if (running)
    throw MethodError(std::string(call) + " re-entered from " + *running +
                      ": a method's own code cannot run or step a simulation (re-entry is refused)");
}

}  // namespace rrlab::python
