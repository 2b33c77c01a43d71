#include "whole_number.hpp"

#include <charconv>
#include <string>

namespace rrlab::cli {

namespace {

// "--name", or a positional's name; CLI11's own messages leave out the name
// of a hidden option (group ""), so the message carries it.
std::string name_of(const CLI::Option& option) {
  return option.get_lnames().empty() ? option.get_single_name() : "--" + option.get_lnames().front();
}

}  // namespace

CLI::Option* whole_number_in(CLI::Option* option, std::int64_t min, std::int64_t max) {
  const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  return option->transform(CLI::Validator(
      [option, min, max, range](std::string& text) -> std::string {
        std::int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);  // decimal only, no '+', no spaces
        if (error != std::errc() || stop != end || value < min || value > max) {
          const std::string shown = text.size() > 40 ? text.substr(0, 37) + "..." : text;
          throw CLI::ConversionError(name_of(*option) + ": must be a whole number in " + range + ", got '" + shown +
                                     "'");
        }
        text = std::to_string(value);  // "007" as 7, not octal
        return "";
      },
      "in " + range, "whole_number_in"));
}

}  // namespace rrlab::cli
