#include <iostream>
#include <string>

#include "cli/commands.h"

namespace animat::cli {

int Fail(const std::string& message) {
  std::cerr << "animat: " << message << "\n";
  return 1;
}

}  // namespace animat::cli
