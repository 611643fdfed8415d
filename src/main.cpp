// The executable is one call: everything, including the error boundary, is in run_cli
// so that tests can run the command line in-process (STYLE.md layers).
#include "avalanche/app/cli.hpp"

int main(int argc, char** argv) { return avalanche::run_cli(argc, argv); }
