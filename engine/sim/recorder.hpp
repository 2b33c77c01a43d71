// Where frames go: the CLI's CSV writer, storage (later), the live stream.
#pragma once

#include <string>
#include <vector>

#include <rrlab/sim/frame.hpp>

namespace rrlab {

class Simulator;

class Recorder {
 public:
  virtual ~Recorder() = default;
  virtual void begin(const Simulator& /*sim*/) {}
  virtual void frame(const Frame& frame) = 0;
  virtual void end(const Summary& /*summary*/) {}
};

}  // namespace rrlab
