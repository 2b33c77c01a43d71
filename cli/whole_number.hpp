// One check for every integer option of the command line.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>

namespace rrlab::cli {

// Makes `option` (an integer of any width) take only a whole number in
// decimal (a leading '-' for a negative one) in [min, max]; anything else
// fails the parse (exit 2) with "OPTION: must be a whole number in [MIN,
// MAX], got 'TEXT'", and --help shows the range after the type. Needed since
// CLI11 on its own reads "-1" as 18446744073709551615 for an unsigned option
// and "010" as octal. Returns `option`.
CLI::Option* whole_number_in(CLI::Option* option, std::int64_t min, std::int64_t max);

}  // namespace rrlab::cli
