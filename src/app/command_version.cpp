#include <iostream>

#include "avalanche/io/effective_config.hpp"
#include "commands.hpp"

namespace avalanche::detail {

Command add_version_command(CLI::App& app) {
    app.add_subcommand("version", "Print the version and exit");
    return [] {
        // The version is the same for every commit; the source hash names the build.
        std::cout << "avalanche-hazard " << software_version() << " (sources " << source_hash()
                  << ")\n";
        return 0;
    };
}

}  // namespace avalanche::detail
