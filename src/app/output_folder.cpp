#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {

// What a run writes under fixed names (execute_scene.cpp, products.cpp, report.cpp,
// report_html.cpp); its maps are named in its summary.
constexpr const char* kRunFiles[] = {
    "summary.json", "results.h5",  "checkpoint.h5", "diagnostic_checkpoint.h5",
    "report.md",    "report.html", "dem.tif",       "monitoring.csv",
    "monitoring.h5"};

}  // namespace

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
        // The only resumable state of a run that was killed before it finished.
        if (!overwrite && fs::exists(d / "checkpoint.h5", ec))
            throw OutputError(dir,
                              "holds the checkpoint of an unfinished run (checkpoint.h5); "
                              "continue it with --resume " +
                                  dir + ", or use --overwrite to start again");
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

void remove_previous_run(const std::string& dir) {
    namespace fs = std::filesystem;
    const fs::path d(dir);
    std::error_code ec;
    std::vector<std::string> names(std::begin(kRunFiles), std::end(kRunFiles));
    // The maps and styles the previous run listed (a run without monitoring points or
    // with other maps must not leave them beside its own).
    try {
        std::ifstream in(d / "summary.json");
        if (in) {
            const nlohmann::json old = nlohmann::json::parse(in);
            if (old.contains("products") && old["products"].is_array())
                for (const auto& name : old["products"])
                    if (name.is_string()) names.push_back(name.get<std::string>());
        }
    } catch (const nlohmann::json::exception&) {
        // Not a summary this program wrote: only the fixed names go.
    }
    for (const std::string& name : names) {
        // File names in the folder only: a summary is a file a user may have edited.
        if (name.empty() || name.find('/') != std::string::npos ||
            name.find('\\') != std::string::npos || name == "." || name == "..")
            continue;
        fs::remove(d / name, ec);
        if (fs::path(name).extension() == ".tif")  // a map's style and quick-look
            for (const char* companion : {".qml", ".png"})
                fs::remove(d / fs::path(name).replace_extension(companion), ec);
    }
}

}  // namespace avalanche
