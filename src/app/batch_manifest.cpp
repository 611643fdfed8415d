#include "avalanche/app/batch_manifest.hpp"

#include <filesystem>
#include <fstream>

#include "avalanche/core/error.hpp"
#include "avalanche/io/atomic_file.hpp"

namespace avalanche {

Manifest read_manifest(const std::string& path) {
    Manifest m;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return m;
    try {
        std::ifstream in(path);
        const auto js = nlohmann::json::parse(in);
        for (const auto& s : js.at("scenarios")) {
            ManifestEntry e;
            e.parameters = s.at("parameters");
            e.config_hash = s.at("config_hash").get<std::string>();
            e.source_hash = s.value("source_hash", "");
            e.complete = s.at("complete").get<bool>();
            e.error = s.value("error", "");
            e.interrupted = s.value("interrupted", false);
            e.config_hash_without_paths = s.value("config_hash_without_paths", "");
            m[s.at("id").get<std::string>()] = e;
        }
    } catch (const nlohmann::json::exception& e) {
        throw InputError(path, std::string("is not a batch manifest (") + e.what() +
                                   "); use --overwrite or another output folder");
    }
    return m;
}

void write_manifest(const std::string& path, const Manifest& manifest,
                    const nlohmann::json& batch) {
    nlohmann::json scenarios = nlohmann::json::array();
    for (const auto& [id, e] : manifest) {
        nlohmann::json s = {{"id", id},
                            {"parameters", e.parameters},
                            {"config_hash", e.config_hash},
                            {"config_hash_without_paths", e.config_hash_without_paths},
                            {"source_hash", e.source_hash},
                            {"complete", e.complete}};
        if (!e.error.empty()) s["error"] = e.error;
        if (e.interrupted) s["interrupted"] = true;
        scenarios.push_back(std::move(s));
    }
    const nlohmann::json js = {{"batch", batch}, {"scenarios", scenarios}};
    write_file_atomically(path, js.dump(2) + "\n");
}

std::optional<std::string> completed_run_fingerprint(const std::string& scenario_dir,
                                                     const std::string& config_hash_without_paths,
                                                     const std::string& source_hash) {
    const auto summary = std::filesystem::path(scenario_dir) / "summary.json";
    std::error_code ec;
    if (!std::filesystem::exists(summary, ec)) return std::nullopt;
    try {
        std::ifstream in(summary);
        const auto js = nlohmann::json::parse(in);
        if (js.value("config_hash_without_paths", "") != config_hash_without_paths ||
            js.value("source_hash", "") != source_hash ||
            js.at("end_reason").get<std::string>() == "interrupted")
            return std::nullopt;
        return js.value("scene_fingerprint", "");
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;  // unreadable: recompute rather than trust it
    }
}

}  // namespace avalanche
