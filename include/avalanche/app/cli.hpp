#pragma once
// The command line (docs/cli.md). run_cli is the single error boundary of the program:
// it catches avalanche::Error, prints one line "avalanche-hazard: error: <message>" on
// stderr and returns the error's exit code; any other exception is a bug (exit 70).
// With --debug, exceptions escape so that a debugger or the runtime shows the stack.
#include <string>
#include <vector>

namespace avalanche {

int run_cli(int argc, char** argv);

// The same with the arguments as strings (args[0] is the program name), for tests. Unlike
// the argc/argv form (the executable's), it never re-executes the process to set
// OMP_WAIT_POLICY, so it is safe to call from a test binary.
int run_cli(const std::vector<std::string>& args);

}  // namespace avalanche
