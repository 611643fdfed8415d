// libFuzzer harness: any bytes as a scenario file, through the parser and validation the
// CLI uses (parse_scenario_text + validate_with_source). A refusal is an avalanche::Error
// with a one-line message; anything else (another exception, a crash, a sanitizer
// report, a multi-line or empty message) is a bug.
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/io/scenario_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        avalanche::Scenario s = avalanche::parse_scenario_text(text, "fuzz.toml", "/base");
        avalanche::validate_with_source(s);
    } catch (const avalanche::Error& e) {
        const std::string what = e.what();
        // The CLI prints the message as its one error line (docs/cli.md).
        if (what.empty() || what.find('\n') != std::string::npos) std::abort();
        if (e.code() != avalanche::ExitCode::usage && e.code() != avalanche::ExitCode::input)
            std::abort();
    }
    // Any other exception escapes and libFuzzer reports it as a crash (the CLI would
    // print "internal error", exit 70).
    return 0;
}
