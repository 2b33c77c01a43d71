#include <rrlab/sim/frame_fields.hpp>

#include <stdexcept>
#include <string>

namespace rrlab::detail {

void throw_bad_frame_field(const char* field) { throw std::runtime_error(std::string("frame has a bad ") + field); }

}  // namespace rrlab::detail
