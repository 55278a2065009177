// Runs phonglab-cli (PHONGLAB_CLI) with the words `args` through the shell, for the CLI's tests.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace phonglab::test {

struct RunResult {
  int exit_code = -1;
  std::string out;  // what the command wrote
};

// `redirect`: what follows the command on its shell line (" 2>&1": stderr too, " 2>/dev/null").
inline RunResult run_cli_with(const std::string& args, const char* redirect) {
  const std::string cmd = std::string(PHONGLAB_CLI) + " " + args + redirect;
  RunResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Its standard output and error together.
inline RunResult run_cli(const std::string& args) { return run_cli_with(args, " 2>&1"); }
// Its standard output alone (its warnings on stderr left out).
inline RunResult run_cli_stdout(const std::string& args) { return run_cli_with(args, " 2>/dev/null"); }

}  // namespace phonglab::test
