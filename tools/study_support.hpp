#pragma once
// What the study tools share (verification_report, validation_study, pareto_study,
// field_presets_study): number formatting for their Markdown, reading a run's JSON,
// replacing a generated block of a document, and the digest of a run's input files.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/io/sha256.hpp"

namespace avalanche::study {

// printf-style formatting of one number (the tables' digits are chosen per column).
inline std::string fmt(const char* f, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, x);
    return buf;
}

// A JSON file (a run's summary.json); InputError naming it when it cannot be read.
inline nlohmann::json read_json(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, "cannot be read");
    return nlohmann::json::parse(in);
}

// The text of `doc` with the block between `<!-- name:begin -->` and `<!-- name:end -->`
// replaced by `body` (the block is appended when the markers are missing).
inline std::string with_block_replaced(const std::string& text, const std::string& name,
                                       const std::string& body) {
    const std::string begin = "<!-- " + name + ":begin -->", end = "<!-- " + name + ":end -->";
    const std::string block = begin + "\n" + body + end;
    std::string out = text;
    const auto a = out.find(begin), b = out.find(end);
    if (a != std::string::npos && b != std::string::npos && b > a)
        out.replace(a, b + end.size() - a, block);
    else
        out += "\n" + block + "\n";
    return out;
}

inline std::string read_text(const std::string& path) {
    std::stringstream ss;
    ss << std::ifstream(path).rdbuf();
    return ss.str();
}

// 16 hex digits of the SHA-256 of the listing "name checksum" of the files a run read
// (summary.json's `inputs`, as named from the working folder; each file's SHA-256 as the
// run's report.html gives it, "unreadable" for one that cannot be read). A study reuses
// a run only while its inputs still digest the same: a DEM edited in place keeps its name.
inline std::string inputs_digest(const nlohmann::json& inputs) {
    std::string listing;
    for (const auto& path : inputs) {
        const std::string name = path.get<std::string>();
        std::string checksum;
        try {
            checksum = sha256_file_hex(name);
        } catch (const Error&) {
            checksum = "unreadable";
        }
        listing += name + " " + checksum + "\n";
    }
    return sha256_hex(listing).substr(0, 16);
}

}  // namespace avalanche::study
