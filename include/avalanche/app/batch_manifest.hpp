#pragma once
// DIR/manifest.json of a batch (docs/batch.md): per scenario its id, parameters, the
// hash of its effective configuration (with and without its input paths), the source
// hash of the program that computed it and whether its outputs are complete. A restarted
// batch skips a scenario only when the manifest AND its summary.json agree that it is
// complete with the same configuration (its input paths aside: they depend on the
// working folder) and the same source hash (the version number is the same for every
// commit), and its inputs still prepare to the scene fingerprint its summary.json
// records (the inputs' contents: a DEM edited in place keeps its path).
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace avalanche {

struct ManifestEntry {
    nlohmann::json parameters = nlohmann::json::object();  // {"delta_deg": 12.5, ...}
    std::string config_hash;
    // config_hash_without_paths (effective_config.hpp): what a resumed batch compares;
    // "" in manifests written before 2026-12-04.
    std::string config_hash_without_paths;
    std::string source_hash;  // "" in manifests written before it was recorded
    bool complete = false;
    std::string error;         // why the last attempt failed, "" if it did not
    bool interrupted = false;  // the last attempt was stopped (Ctrl-C, SIGTERM) before its end
};
using Manifest = std::map<std::string, ManifestEntry>;  // by scenario id (sorted)

// The manifest at `path`; empty when the file does not exist. InputError(path) when it
// exists but is not a manifest (then the user decides: --overwrite or another DIR).
Manifest read_manifest(const std::string& path);

// Writes the manifest atomically (manifest.json.part + rename), so a crash mid-write
// leaves the previous manifest. `batch` describes the batch (base scenario, sweeps).
void write_manifest(const std::string& path, const Manifest& manifest, const nlohmann::json& batch);

// The scene fingerprint (prepared_scene.hpp) recorded by the finished run in
// `scenario_dir` of the configuration whose hash without input paths is
// `config_hash_without_paths`, computed from sources `source_hash`: nullopt unless its
// summary.json exists (written last, so every product exists), carries both hashes and
// was not interrupted; "" when that summary records no fingerprint (written before
// 2026-12-04).
std::optional<std::string> completed_run_fingerprint(const std::string& scenario_dir,
                                                     const std::string& config_hash_without_paths,
                                                     const std::string& source_hash);

}  // namespace avalanche
