#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <system_error>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/core/error.hpp"

namespace avalanche {

void prepare_output_folder(const std::string& dir, bool overwrite) {
    namespace fs = std::filesystem;
    if (dir.empty()) throw ConfigError("--out", "expected an output folder");
    const fs::path d(dir);
    std::error_code ec;
    if (fs::exists(d, ec)) {
        if (!fs::is_directory(d, ec)) throw OutputError(dir, "exists and is not a folder");
        for (const char* product : {"summary.json", "results.h5"})
            if (!overwrite && fs::exists(d / product, ec))
                throw OutputError(dir, std::string("already holds results (") + product +
                                           "); use --overwrite to replace them");
    } else {
        fs::create_directories(d, ec);
        if (ec) throw OutputError(dir, "cannot create the output folder: " + ec.message());
    }
    // Find out now, not after an hour of simulation, that nothing can be written here.
    const fs::path probe = d / (".write-test-" + std::to_string(::getpid()));
    {
        std::ofstream f(probe);
        if (!f) throw OutputError(dir, "the output folder is not writable");
    }
    fs::remove(probe, ec);
}

}  // namespace avalanche
