// The presets on a real scene against a refined reference (issue "Speed against
// accuracy", part 4; docs/performance.md, "The presets on the field scene"). The chute of
// pareto_study has a reference and an exact geometry but a deposit about as deep as its
// cells; a rock avalanche's deposit is tens of metres deep on cells of 10-20 m, where
// the numerics behave differently (a deposit on cells much finer than its depth need
// not come to rest with one advection per step at Courant 0.4, docs/numerics.md step 2).
// This study runs the Fluchthorn scene (scenarios/field_fluchthorn, 20 m cells) with
// each preset and, on the fine preset's 10 m cells, with the other numerics a user can
// choose there, and compares the maps with a reference on 5 m cells (standard numerics).
//
// Every run goes through `avalanche-hazard run` in-process, as a user runs it (one
// thread); its products are read back with GDAL and its final state from results.h5.
// Runs whose summary.json carries this program's source hash and configuration, and
// whose input files still have the same bytes, are reused from the work folder, so a
// rerun after a change of the docs costs nothing.
// Usage: field_presets_study [--doc docs/performance.md] [--work ../field-presets-work]
#include <hdf5.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "avalanche/app/cli.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "field_presets_text.hpp"
#include "study_support.hpp"

using namespace avalanche;

namespace {

using study::fmt;
using study::inputs_digest;
using study::read_json;

// One run of the study: its name in the table, the flags after the scenario, and what
// it produced.
struct Run {
    Run(std::string n, std::string split, double courant, std::vector<std::string> f)
        : name(std::move(n)), splitting(std::move(split)), cfl(courant), flags(std::move(f)) {}
    std::string name, splitting;
    double cfl = 0.0;
    std::vector<std::string> flags;
    std::string dir;
    nlohmann::json summary;
    double cpu_s = std::nan("");  // measured when computed here
    bool reused = false;
    // The run's cost: its CPU time, or its summary's wall time when it was reused.
    [[nodiscard]] double seconds() const {
        return reused ? summary.at("wall_s").get<double>() : cpu_s;
    }
};

// Runs `avalanche-hazard run --scenario S FLAGS --threads 1 --out DIR`, or reuses DIR
// when its summary says it is complete, from this program's sources, with the same
// command flags and input files of the same bytes (study_command.txt keeps the flags
// and the inputs' digest).
void run(Run& r, const std::string& scenario, const std::string& work) {
    r.dir = work + "/" + r.name;
    std::vector<std::string> cli = {"avalanche-hazard", "run", "--scenario", scenario};
    cli.insert(cli.end(), r.flags.begin(), r.flags.end());
    for (const char* a : {"--threads", "1", "--overwrite", "-q", "--out"}) cli.emplace_back(a);
    cli.push_back(r.dir);
    std::string line;
    for (const auto& a : cli) line += (line.empty() ? "" : " ") + a;
    const std::string summary = r.dir + "/summary.json";
    const std::string stamp = r.dir + "/study_command.txt";
    if (std::filesystem::exists(summary) && std::filesystem::exists(stamp)) {
        const nlohmann::json j = read_json(summary);
        std::string was, digest;
        std::ifstream in(stamp);
        std::getline(in, was);
        std::getline(in, digest);
        if (j.value("complete", false) && j.value("source_hash", "") == source_hash() &&
            was == line && j.contains("inputs") && digest == inputs_digest(j.at("inputs"))) {
            r.summary = j;
            r.reused = true;
            std::cerr << "reusing " << r.dir << "\n";
            return;
        }
    }
    std::cerr << line << "\n";
    const std::clock_t c0 = std::clock();
    const int rc = run_cli(cli);
    r.cpu_s = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    if (rc != 0) throw InputError(r.dir, "the run failed with exit code " + std::to_string(rc));
    r.summary = read_json(summary);
    std::ofstream(stamp) << line << "\n" << inputs_digest(r.summary.at("inputs")) << "\n";
}

// Relative L1 distance of a map from the reference's, the reference averaged over the
// blocks of its cells that make one cell of the map (the grids share their origin; the
// cell sizes are multiples). Nodata (cells never reached) counts as 0.
double map_error(const std::string& map, const std::string& ref_map) {
    const gis::RasterData a = gis::read_geotiff(map), r = gis::read_geotiff(ref_map);
    const Grid& ga = a.geo.grid;
    const Grid& gr = r.geo.grid;
    const int k = static_cast<int>(std::lround(ga.dx / gr.dx));
    const int oi = static_cast<int>(std::lround((ga.x0 - gr.x0) / gr.dx));
    const int oj = static_cast<int>(std::lround((ga.y0 - gr.y0) / gr.dy));
    if (k < 1 || std::abs(k * gr.dx - ga.dx) > 1e-6 * ga.dx ||
        std::abs(oi * gr.dx - (ga.x0 - gr.x0)) > 1e-6 * gr.dx ||
        std::abs(oj * gr.dy - (ga.y0 - gr.y0)) > 1e-6 * gr.dy)
        throw InputError(map, "its grid is not made of whole blocks of the reference's cells");
    const auto value = [](const gis::RasterData& d, std::size_t n) {
        const double v = d.values[n];
        return !std::isfinite(v) || (d.nodata && v == *d.nodata) ? 0.0 : v;
    };
    double diff = 0.0, norm = 0.0;
    for (int j = 0; j < ga.ny; ++j)
        for (int i = 0; i < ga.nx; ++i) {
            double mean = 0.0;
            for (int q = 0; q < k; ++q)
                for (int p = 0; p < k; ++p) {
                    const int I = oi + i * k + p, J = oj + j * k + q;
                    if (I >= 0 && J >= 0 && I < gr.nx && J < gr.ny)
                        mean += value(r, static_cast<std::size_t>(J) * gr.nx + I);
                }
            mean /= k * k;
            diff += std::abs(value(a, static_cast<std::size_t>(j) * ga.nx + i) - mean);
            norm += std::abs(mean);
        }
    return diff / norm;
}

// The last snapshot of `name` ("h", "u" or "v") in results.h5, row-major.
std::vector<double> last_snapshot(const std::string& file, const char* name) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) throw InputError(file, "cannot be opened as HDF5");
    const hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(ds);
    hsize_t dims[3] = {0, 0, 0};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    const hsize_t start[3] = {dims[0] - 1, 0, 0}, count[3] = {1, dims[1], dims[2]};
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    const hid_t mem = H5Screate_simple(3, count, nullptr);
    std::vector<double> out(dims[1] * dims[2]);
    const herr_t ok = H5Dread(ds, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, out.data());
    H5Sclose(mem);
    H5Sclose(space);
    H5Dclose(ds);
    H5Fclose(f);
    if (ok < 0) throw InputError(file, std::string("cannot read the dataset ") + name);
    return out;
}

// The root-mean-square speed of the cells deeper than `deep` m at the end of the run,
// and their number: how still the deposit is (a deposit that "boils" keeps its cells
// moving against each other).
std::pair<double, long> deep_rms_speed(const std::string& results, double deep) {
    const auto h = last_snapshot(results, "h"), u = last_snapshot(results, "u"),
               v = last_snapshot(results, "v");
    double sum = 0.0;
    long n = 0;
    for (std::size_t c = 0; c < h.size(); ++c)
        if (h[c] > deep) {
            sum += u[c] * u[c] + v[c] * v[c];
            ++n;
        }
    return {n ? std::sqrt(sum / static_cast<double>(n)) : 0.0, n};
}

}  // namespace

int main(int argc, char** argv) {
    const std::string src = AVALANCHE_SOURCE_DIR;
    std::string doc = src + "/docs/performance.md";
    std::string work = src + "/../field-presets-work";
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--doc" && k + 1 < argc)
            doc = argv[++k];
        else if (a == "--work" && k + 1 < argc)
            work = argv[++k];
        else {
            std::cerr << "usage: field_presets_study [--doc FILE] [--work DIR]\n";
            return 2;
        }
    }
    try {
        std::filesystem::create_directories(work);
        const std::string scenario = src + "/scenarios/field_fluchthorn/scenario.toml";
        // The scenario's cell is 20 m: the reference is 4x finer, as the chute's.
        Run ref{"reference_5m", "L S L", 0.2, {"--cell-size", "5"}};
        std::vector<Run> runs = {
            {"draft", "S L S", 0.4, {"--quality", "draft"}},
            {"standard", "L S L", 0.2, {}},
            {"fine", "S L S", 0.2, {"--quality", "fine"}},
            {"fine_cfl0.3", "S L S", 0.3, {"--quality", "fine", "--cfl", "0.3"}},
            {"fine_cfl0.4", "S L S", 0.4, {"--quality", "fine", "--cfl", "0.4"}},
            {"standard_10m", "L S L", 0.2, {"--cell-size", "10"}},
        };
        run(ref, scenario, work);
        for (Run& r : runs) run(r, scenario, work);

        const std::string labels[] = {"`--quality draft`",
                                      "`--quality standard` (the scenario)",
                                      "`--quality fine`",
                                      "`--quality fine --cfl 0.3`",
                                      "`--quality fine --cfl 0.4` (fine until 2026-12-02)",
                                      "`--cell-size 10` (standard numerics)"};
        std::ostringstream md;
        md << field_presets_text::kIntro;
        const auto ref_rms = deep_rms_speed(ref.dir + "/results.h5", 1.0);
        md << "\nReference: standard numerics (WAF, L S L, Courant 0.2) on 5 m cells, "
           << ref.summary.at("steps").get<long>() << " steps, "
           << ref.summary.at("end_reason").get<std::string>() << " at "
           << fmt("%.0f", ref.summary.at("simulated_time_s").get<double>()) << " s, runout "
           << fmt("%.0f", ref.summary.at("runout").at("runout_length_m").get<double>())
           << " m, affected area "
           << fmt("%.3f", ref.summary.at("runout").at("affected_area_m2").get<double>() / 1e6)
           << " km², cells deeper than 1 m at the end moving at " << fmt("%.2f", ref_rms.first)
           << " m/s (root mean square over " << ref_rms.second << " cells).\n\n"
           << "| run | cell (m) | splitting | Courant | cell updates | CPU (s) | deposit error | "
              "max depth error | max speed error | runout (m) | affected area (km²) | end | final "
              "kinetic energy / max | deep cells' rms speed (m/s) |\n"
           << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        struct Metrics {
            double deposit, depth, speed, rms;
        };
        std::vector<Metrics> m;
        for (const Run& r : runs)
            m.push_back(
                {map_error(r.dir + "/deposit_thickness.tif", ref.dir + "/deposit_thickness.tif"),
                 map_error(r.dir + "/max_depth.tif", ref.dir + "/max_depth.tif"),
                 map_error(r.dir + "/max_velocity.tif", ref.dir + "/max_velocity.tif"),
                 deep_rms_speed(r.dir + "/results.h5", 1.0).first});
        for (std::size_t k = 0; k < runs.size(); ++k) {
            const Run& r = runs[k];
            const auto& s = r.summary;
            md << "| " << labels[k] << " | " << fmt("%g", s.at("grid").at("dx_m").get<double>())
               << " | " << r.splitting << " | " << fmt("%g", r.cfl) << " | "
               << fmt("%.1f M", s.at("performance").at("cell_updates").get<double>() / 1e6) << " | "
               << fmt(r.reused ? "(%.1f wall)" : "%.1f", r.seconds()) << " | "
               << fmt("%.3f", m[k].deposit) << " | " << fmt("%.3f", m[k].depth) << " | "
               << fmt("%.3f", m[k].speed) << " | "
               << fmt("%.0f", s.at("runout").at("runout_length_m").get<double>()) << " | "
               << fmt("%.3f", s.at("runout").at("affected_area_m2").get<double>() / 1e6) << " | "
               << s.at("end_reason").get<std::string>() << " | "
               << fmt("%.1e", s.at("final_kinetic_energy_fraction").get<double>()) << " | "
               << fmt("%.2f", m[k].rms) << " |\n";
        }
        // runs: 0 draft, 1 standard, 2 fine, 3 fine at 0.3, 4 fine at 0.4, 5 standard on 10 m.
        md << "\nOn the fine preset's 10 m cells the deposit's deep cells move at "
           << fmt("%.2f", m[2].rms) << " m/s with the fine preset (Courant 0.2), "
           << fmt("%.2f", m[3].rms) << " at Courant 0.3, " << fmt("%.2f", m[4].rms)
           << " at Courant 0.4 and " << fmt("%.2f", m[5].rms)
           << " with the standard numerics (the reference: " << fmt("%.2f", ref_rms.first)
           << "); the deposit maps lie " << fmt("%.3f", m[2].deposit) << ", "
           << fmt("%.3f", m[3].deposit) << ", " << fmt("%.3f", m[4].deposit) << " and "
           << fmt("%.3f", m[5].deposit) << " from the reference. The fine preset costs "
           << fmt("%.1f", runs[2].seconds() / runs[1].seconds())
           << " times the standard preset's CPU time (Courant 0.4: "
           << fmt("%.1f", runs[4].seconds() / runs[1].seconds())
           << " times; the standard numerics on the same cells: "
           << fmt("%.1f", runs[5].seconds() / runs[1].seconds()) << " times).\n";
        md << field_presets_text::kDiscussion;
        write_file_atomically(
            doc, study::with_block_replaced(study::read_text(doc), "field-presets", md.str()));
        std::cerr << "wrote " << doc << "\n";
    } catch (const std::exception& e) {
        std::cerr << "field_presets_study: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
