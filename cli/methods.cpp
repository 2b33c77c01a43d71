#include <iostream>

#include <rrlab/methods/registry_json.hpp>

#include "cli.hpp"

namespace rrlab::cli {

int methods() {
  std::cout << methods_json().dump(2) << '\n';
  return 0;
}

}  // namespace rrlab::cli
