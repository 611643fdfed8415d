// The error boundary of the program (STYLE.md 7): parse, dispatch, and turn every
// avalanche::Error into one line on stderr and its documented exit code.
#include "avalanche/app/cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <exception>
#include <fstream>
#include <map>
#include <string>

#include "avalanche/app/malloc_huge_pages.hpp"
#include "avalanche/app/openmp_wait.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/io/effective_config.hpp"
#include "commands.hpp"
#include "logging.hpp"

namespace avalanche {

namespace {

void print_error(const std::string& message) {
    std::fprintf(stderr, "avalanche-hazard: error: %s\n", message.c_str());
    std::fflush(stderr);
}

std::string join_command_line(int argc, char** argv) {
    std::string out;
    for (int k = 0; k < argc; ++k) {
        std::string a = argv[k];
        if (a.find_first_of(" \t\"'") != std::string::npos) a = "'" + a + "'";
        out += (k ? " " : "") + a;
    }
    return out;
}

// How the OpenMP threads wait between parallel regions (openmp_wait.hpp says why),
// unless the user chose, and huge pages for malloc's large buffers
// (malloc_huge_pages.hpp): libgomp and glibc read them as the program starts, so they
// are set by re-executing once.
void choose_environment_for_run(char** argv) {
    bool changed = false;
    if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr) {
        std::ifstream file("/proc/loadavg");
        std::string loadavg;
        std::getline(file, loadavg);
        const OpenmpWait wait = choose_openmp_wait(loadavg);
        ::setenv(wait.variable.c_str(), wait.value.c_str(), 1);
        changed = true;
    }
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    const char* asked = std::getenv("AVALANCHE_HUGE_PAGES");
    std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string thp_enabled;
    std::getline(thp, thp_enabled);
    if (wants_malloc_huge_pages(thp_enabled, tunables ? tunables : "", asked ? asked : "")) {
        ::setenv("GLIBC_TUNABLES", tunables_with_huge_pages(tunables ? tunables : "").c_str(), 1);
        ::setenv("AVALANCHE_HUGE_PAGES", "1", 1);
        changed = true;
    }
    if (changed) ::execv("/proc/self/exe", argv);  // returns only on failure: then run as we are
}

// Parse, dispatch, catch: the error boundary itself, without the re-exec above.
int dispatch(int argc, char** argv) {
    detail::GlobalOptions global;
    global.command_line = join_command_line(argc, argv);
    CLI::App app{
        "avalanche-hazard: granular avalanche simulation (Savage-Hutter, Wang & Li 2017) "
        "and hazard maps"};
    app.name("avalanche-hazard");
    app.set_version_flag("--version", software_version() + " (sources " + source_hash() + ")");
    app.add_flag("-q,--quiet", global.quiet, "Only warnings and errors; no progress bar");
    app.add_flag("-v,--verbose", global.verbose, "Debug log lines");
    app.add_flag("--debug", global.debug, "Let errors escape as exceptions (for a stack trace)");
    app.require_subcommand(1);
    app.footer("Run 'avalanche-hazard run --help' for the run options and examples; docs/cli.md.");

    std::map<std::string, detail::Command> commands;
    commands["run"] = detail::add_run_command(app, global);
    commands["demo"] = detail::add_demo_command(app, global);
    commands["batch"] = detail::add_batch_command(app, global);
    commands["version"] = detail::add_version_command(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        print_error(e.what());
        return static_cast<int>(ExitCode::usage);
    }

    detail::configure_logging(global.quiet     ? detail::Verbosity::quiet
                              : global.verbose ? detail::Verbosity::verbose
                                               : detail::Verbosity::normal);
    const detail::Command& command = commands.at(app.get_subcommands().front()->get_name());
    if (global.debug) return command();
    try {
        return command();
    } catch (const Error& e) {
        print_error(e.what());
        return static_cast<int>(e.code());
    } catch (const std::exception& e) {
        print_error(std::string("internal error: ") + e.what());
        return static_cast<int>(ExitCode::internal);
    }
}

}  // namespace

int run_cli(int argc, char** argv) {
    choose_environment_for_run(argv);
    return dispatch(argc, argv);
}

int run_cli(const std::vector<std::string>& args) {
    std::vector<std::string> copy = args;
    std::vector<char*> argv;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    // No re-exec here: in a test process /proc/self/exe is the test binary, which would
    // restart with the CLI's arguments (and, under gtest, run every test again).
    return dispatch(static_cast<int>(copy.size()), argv.data());
}

}  // namespace avalanche
