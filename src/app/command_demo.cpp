// `avalanche-hazard demo`: the bundled default scene (real terrain, release polygon,
// monitoring point), so that a new user sees every product with one command.
#include <filesystem>

#include "avalanche/core/error.hpp"
#include "commands.hpp"

namespace avalanche::detail {

namespace {

// The scenario ships in the source tree; look beside the executable's tree too, so an
// installed copy that keeps the layout (bin/../scenarios) finds it.
std::string locate_demo_scenario() {
    namespace fs = std::filesystem;
    const fs::path relative = fs::path("scenarios") / "demo_avakot" / "scenario.toml";
    std::vector<fs::path> candidates = {fs::path(AVALANCHE_SOURCE_DIR) / relative, fs::current_path() / relative};
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        for (fs::path dir = exe.parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path())
            candidates.push_back(dir / relative);
    for (const auto& c : candidates)
        if (fs::exists(c, ec)) return c.string();
    throw InputError(relative.string(), "the bundled demo scenario was not found beside the source tree or the "
                                        "executable; run from the repository folder");
}

}  // namespace

Command add_demo_command(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<RunArguments>();
    args->out = "results/demo";
    CLI::App* cmd = app.add_subcommand(
        "demo", "Run the bundled default scene (Kot avalanche path, Tyrol) and write every product");
    cmd->fallthrough();
    cmd->add_option("--out", args->out, "Output folder")->capture_default_str();
    cmd->add_flag("--overwrite", args->overwrite, "Replace results already in the output folder");
    cmd->add_option("--threads", args->threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
    cmd->footer("The scene: scenarios/demo_avakot/scenario.toml (see dem/README.md for the data).");
    return [args, &global] {
        RunArguments a = *args;
        a.scenario = locate_demo_scenario();
        return execute_run(a, global);
    };
}

}  // namespace avalanche::detail
