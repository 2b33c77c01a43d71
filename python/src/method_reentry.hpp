// A Python method's own code (its start(), step() or the copy a sweep makes)
// may not start or step a run. Such a run would nest inside the one that
// called the method, on the same C++ stack, a few kilobytes per level: a
// method that re-entered rrlab.run from its step crashed the interpreter
// (SIGSEGV) at about 450 levels, below Python's recursion limit, and sooner
// under the sanitizers. Refusing re-entry keeps the depth at one.
#pragma once

#include <string>

namespace rrlab::python {

// While one lives, this thread is in the Python method code `where` names
// (e.g. "the Python method my_pinv").
class InMethodCode {
 public:
  explicit InMethodCode(const std::string& where);
  ~InMethodCode();
  InMethodCode(const InMethodCode&) = delete;
  InMethodCode& operator=(const InMethodCode&) = delete;

 private:
  const std::string* outer_;
};

// The engine's entry points that step a run (rrlab.run, Simulator.step,
// rrlab.sweep, rrlab.replay) call this first: a MethodError naming `call` and
// the method, when this thread is inside a Python method's code.
void refuse_reentry(const char* call);

}  // namespace rrlab::python
