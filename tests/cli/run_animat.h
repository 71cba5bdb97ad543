// Runs a built program of build/bin (`animat`, or a tool beside it) for the
// end-to-end tests: its exit code and everything it wrote (stdout and
// stderr together).
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

// Runs build/bin/`program`; `arguments` go to a shell after its name, so
// quote them accordingly.
inline Outcome RunTool(const std::string& program,
                       const std::string& arguments) {
  const std::string command =
      std::string(ANIMAT_BIN_DIR) + "/" + program + " " + arguments + " 2>&1";
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

// Runs build/bin/animat with `arguments` (as RunTool).
inline Outcome Animat(const std::string& arguments) {
  return RunTool("animat", arguments);
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_CLI_RUN_ANIMAT_H_
