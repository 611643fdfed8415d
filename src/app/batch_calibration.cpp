// Fit of each scenario to an observed deposit: footprint overlap (Jaccard index) and
// runout error, combined into one score for the ranking. The simulated footprint is read
// back from the scenario's max_depth.tif, which is nodata exactly where the max depth
// stayed below output.h_threshold: the cells the affected area, the runout tip and the
// impact frequency count, so the fit sees the same footprint as every other product.
#include "batch_calibration.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/io/atomic_file.hpp"

namespace avalanche::detail {

namespace {

namespace fs = std::filesystem;

// The scenario's footprint (1 = reached) in solver order, checked against the grid.
std::vector<std::uint8_t> simulated_footprint(const std::string& dir, const Grid& grid) {
    const std::string path = (fs::path(dir) / "max_depth.tif").string();
    const gis::RasterData r = gis::read_geotiff(path);
    if (r.geo.grid.nx != grid.nx || r.geo.grid.ny != grid.ny)
        throw InputError(path, "is on another grid than the observed deposit was rasterised on");
    std::vector<std::uint8_t> reached(r.values.size(), 0);
    for (std::size_t k = 0; k < r.values.size(); ++k)
        reached[k] = !(r.nodata && r.values[k] == *r.nodata);
    return reached;
}

// The observed runout measured like the simulated one (compute_runout): the largest
// horizontal distance from the scenario's release top to an observed cell.
double observed_runout(const Observation& o, const std::array<double, 2>& top) {
    double far2 = 0.0;
    for (const auto& p : o.positions)
        far2 =
            std::max(far2, (p[0] - top[0]) * (p[0] - top[0]) + (p[1] - top[1]) * (p[1] - top[1]));
    return std::sqrt(far2);
}

}  // namespace

Observation load_observation(const std::string& path, const PreparedScene& scene,
                             double h_threshold) {
    Observation o;
    o.path = path;
    o.grid = scene.grid;
    o.footprint = gis::rasterize_observed_polygons(path, gis::GeoGrid{scene.grid, scene.crs_wkt});
    o.cell_area_m2 = scene.cell_area_m2;
    o.h_threshold = h_threshold;
    for (int j = 0; j < scene.grid.ny; ++j)
        for (int i = 0; i < scene.grid.nx; ++i)
            if (o.footprint.inside[static_cast<std::size_t>(j) * scene.grid.nx + i])
                o.positions.push_back(scene.horizontal_position(i, j));
    spdlog::info("{}", o.footprint.description);
    return o;
}

void fit_to_observation(const Observation& o, std::vector<BatchResult>& rows) {
    std::vector<BatchResult*> ranked;
    for (auto& r : rows) {
        r.fit.reset();
        if (!r.summary) continue;
        const auto reached = simulated_footprint(r.dir, o.grid);
        ScenarioFit f;
        for (std::size_t k = 0; k < reached.size(); ++k) {
            const bool obs = o.footprint.inside[k] != 0, sim = reached[k] != 0;
            f.intersection_cells += obs && sim;
            f.union_cells += obs || sim;
        }
        // The union holds the observed cells, so it is never empty.
        f.jaccard = static_cast<double>(f.intersection_cells) / static_cast<double>(f.union_cells);
        const auto& runout = r.summary->at("runout");
        const auto top = runout.at("release_top_xy").get<std::array<double, 2>>();
        f.simulated_runout_m = runout.at("runout_length_m").get<double>();
        f.observed_runout_m = observed_runout(o, top);
        f.runout_error_m = f.simulated_runout_m - f.observed_runout_m;
        // A one-cell observed outline would make the relative error blow up: the
        // denominator is at least the cell size, the resolution of either runout.
        const double scale = std::max(f.observed_runout_m, std::min(o.grid.dx, o.grid.dy));
        f.score = (1.0 - f.jaccard) + std::abs(f.runout_error_m) / scale;
        r.fit = f;
        ranked.push_back(&r);
    }
    std::sort(ranked.begin(), ranked.end(), [](const BatchResult* a, const BatchResult* b) {
        if (a->fit->score != b->fit->score) return a->fit->score < b->fit->score;
        return a->batch_case->id < b->batch_case->id;
    });
    for (std::size_t k = 0; k < ranked.size(); ++k) ranked[k]->fit->rank = static_cast<int>(k) + 1;
    if (!ranked.empty())
        spdlog::info("best fit to {}: {} (Jaccard {:.3f}, runout error {:.1f} m)", o.path,
                     ranked.front()->batch_case->id, ranked.front()->fit->jaccard,
                     ranked.front()->fit->runout_error_m);
}

std::string write_calibration(const std::string& dir, const Observation& o,
                              const std::vector<BatchResult>& rows) {
    std::vector<const BatchResult*> order;
    for (const auto& r : rows) order.push_back(&r);
    // Best first; scenarios without a fit (failed) last, by id.
    std::sort(order.begin(), order.end(), [](const BatchResult* a, const BatchResult* b) {
        const int ra = a->fit ? a->fit->rank : 1 << 30, rb = b->fit ? b->fit->rank : 1 << 30;
        return ra != rb ? ra < rb : a->batch_case->id < b->batch_case->id;
    });
    nlohmann::json scenarios = nlohmann::json::array();
    for (const auto* r : order) {
        nlohmann::json s = {{"id", r->batch_case->id}};
        if (!r->fit) {
            s["rank"] = nullptr;
            s["error"] = r->failure;
        } else {
            const ScenarioFit& f = *r->fit;
            s.update({{"rank", f.rank},
                      {"score", f.score},
                      {"jaccard", f.jaccard},
                      {"intersection_cells", f.intersection_cells},
                      {"union_cells", f.union_cells},
                      {"simulated_runout_m", f.simulated_runout_m},
                      {"observed_runout_m", f.observed_runout_m},
                      {"runout_error_m", f.runout_error_m}});
        }
        scenarios.push_back(std::move(s));
    }
    const bool any = !order.empty() && order.front()->fit;
    const nlohmann::json js = {
        {"observed",
         {{"file", o.path},
          {"polygons", o.footprint.polygons},
          {"cells", o.footprint.cells},
          {"area_m2", static_cast<double>(o.footprint.cells) * o.cell_area_m2},
          {"rule", "cell centre inside a polygon, on the computational grid"}}},
        {"simulated_footprint", "cells whose max depth reached output.h_threshold"},
        {"h_threshold_m", o.h_threshold},
        {"cell_size_m", std::min(o.grid.dx, o.grid.dy)},
        {"score",
         "(1 - jaccard) + |runout_error_m| / max(observed_runout_m, cell_size_m); lower is "
         "better"},
        {"best", any ? nlohmann::json(order.front()->batch_case->id) : nlohmann::json(nullptr)},
        {"scenarios", scenarios}};
    write_file_atomically((fs::path(dir) / "calibration.json").string(), js.dump(2) + "\n");
    return "calibration.json";
}

}  // namespace avalanche::detail
