// Runs the built `animat` tool for the end-to-end tests of tests/cli:
// its exit code and everything it wrote (stdout and stderr together).
#ifndef ANIMAT_TESTS_CLI_RUN_ANIMAT_H_
#define ANIMAT_TESTS_CLI_RUN_ANIMAT_H_

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace animat::testing {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr.
};

// `arguments` go to a shell after "animat "; quote them accordingly.
inline Outcome Animat(const std::string& arguments) {
  const std::string command =
      std::string(ANIMAT_BIN_DIR) + "/animat " + arguments + " 2>&1";
  Outcome run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) {
    run.output.append(buffer, n);
  }
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_CLI_RUN_ANIMAT_H_
