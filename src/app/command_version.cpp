#include <iostream>

#include "avalanche/io/effective_config.hpp"
#include "commands.hpp"

namespace avalanche::detail {

Command add_version_command(CLI::App& app) {
    app.add_subcommand("version", "Print the version and exit");
    return [] {
        std::cout << "avalanche-hazard " << software_version() << "\n";
        return 0;
    };
}

}  // namespace avalanche::detail
