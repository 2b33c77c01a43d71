#include <iostream>

#include "cli.hpp"
#include "methods/registry_json.hpp"

namespace rrlab::cli {

int methods() {
  std::cout << methods_json().dump(2) << '\n';
  return 0;
}

}  // namespace rrlab::cli
