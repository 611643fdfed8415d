#pragma once
// The effective configuration of a run (defaults < scenario file < flags) as canonical
// JSON, and its hash: both go into every output (STYLE.md 6), so that two results can be
// told apart, or recognised as the same run, from their files alone.
#include <nlohmann/json.hpp>
#include <string>

#include "avalanche/io/scenario.hpp"

namespace avalanche {

// Every parameter, grouped as in the scenario file (terrain, release, material,
// numerics, points, output), with the choices spelled as in the file. Keys are sorted,
// so dump() is canonical.
nlohmann::json effective_config(const Scenario& s);

// FNV-1a (64 bit) of the compact dump of `config`, as 16 hex digits.
std::string config_hash(const nlohmann::json& config);

// config_hash of `config` with its input paths (terrain.dem, release.polygons,
// release.raster, points.file) blanked: the same for the same parameters however the
// inputs are named (relative to another working folder, or moved). A resumed batch
// compares it, and the inputs' contents through the scene fingerprint (docs/batch.md).
std::string config_hash_without_paths(nlohmann::json config);

// The software version written into outputs (the CMake project version).
std::string software_version();

// 16 hex digits of a SHA-256 over the program's C++ sources (cmake/source_hash.cmake),
// written into outputs beside the version, which is the same for every commit: a batch
// or checkpoint resumes only results computed from the same sources.
std::string source_hash();

}  // namespace avalanche
