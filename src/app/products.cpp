#include "avalanche/app/products.hpp"

#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "avalanche/gis/dem.hpp"
#include "avalanche/gis/quicklook.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "avalanche/gis/style.hpp"
#include "avalanche/io/monitoring_writer.hpp"
#include "work_queue.hpp"

namespace avalanche {

namespace {

constexpr double kNodata = -9999.0;

struct MapSpec {
    std::string name;  // file base name
    std::string description;
    std::string units;
    gis::ColorRamp ramp;
    gis::SampleType type = gis::SampleType::float32;
    double nodata = kNodata;
    bool thickness = false;  // holds a thickness: say which
    // What a quick-look pixel of several cells shows (large grids): the largest value,
    // but the earliest arrival.
    gis::QuicklookBlock block = gis::QuicklookBlock::maximum;
};

// Cells never reached are nodata in the maps of maxima, so that QGIS draws only the
// affected area over the terrain. Outside the maps' reach box no cell is reached: the
// maps are read only inside it (HazardMaps::reach_box).
std::vector<double> masked(std::span<const double> values, std::span<const double> depth, double thr,
                           const Grid& g, const ActiveBox& reach) {
    std::vector<double> out(values.size(), kNodata);
    for_each_cell(reach, g.nx, [&](int, int, std::size_t k) {
        out[k] = depth[k] >= thr ? values[k] : kNodata;
    });
    return out;
}

}  // namespace

std::vector<std::string> write_products(const std::string& dir, const ProductInputs& in) {
    const std::filesystem::path d(dir);
    const Grid& g = in.scene.grid;
    const gis::GeoGrid geo{g, in.scene.crs_wkt};
    const OutputParams& out = in.scenario.output;
    const std::span<const double> depth = in.maps.max_depth();
    const ActiveBox& reach = in.maps.reach_box();
    // One hillshade under every quick-look, already per pixel as they draw it: the cells'
    // hillshade and the elevation's copy are freed here (each is a grid-sized array of
    // first-touched memory on a large grid; dem.tif makes its own copy when written).
    // A batch's scenarios of one scene share it. The cells outside the DEM's data are
    // drawn hatched, not shaded (quicklook.hpp).
    const auto make_shade = [&] {
        return gis::quicklook_shade(g, gis::hillshade(g, in.scene.terrain.elevation.interior()),
                                    in.scene.outside_data);
    };
    const gis::QuicklookShade own_shade = in.shared ? gis::QuicklookShade{} : make_shade();
    const gis::QuicklookShade& shade = in.shared ? in.shared->shade(make_shade) : own_shade;

    const std::string pressure_breaks = "classes: low < " + std::to_string(out.pressure_low_kpa) +
                                        " kPa <= medium < " + std::to_string(out.pressure_high_kpa) +
                                        " kPa <= high";
    // Each map's values are made when it is written, so that one grid-sized copy at a
    // time is alive (on a large grid every copy is also first-touched memory).
    using Values = std::function<std::vector<double>()>;
    const std::vector<std::pair<MapSpec, Values>> maps = {
        {{"max_depth", "maximum flow depth (bed-normal)", "m", gis::depth_ramp(), gis::SampleType::float32,
          kNodata, true},
         [&] { return masked(depth, depth, out.h_threshold, g, reach); }},
        {{"max_velocity", "maximum along-surface speed", "m/s", gis::velocity_ramp()},
         [&] { return masked(in.maps.max_speed(), depth, out.h_threshold, g, reach); }},
        {{"max_pressure", "maximum impact pressure rho |u|^2", "kPa",
          gis::pressure_ramp({1.0, out.pressure_low_kpa, 10.0, out.pressure_high_kpa, 100.0})},
         [&] { return masked(in.maps.max_pressure(), depth, out.h_threshold, g, reach); }},
        {{"arrival_time", "first time the depth reached the hazard threshold", "s",
          gis::arrival_time_ramp(std::max(in.stats.simulated_time, 1e-9)), gis::SampleType::float32,
          kNodata, false, gis::QuicklookBlock::minimum},
         [&] {
             std::vector<double> arrival = in.maps.arrival_time();
             for (double& a : arrival)
                 if (a == HazardMaps::kNotReached) a = kNodata;
             return arrival;
         }},
        {{"deposit_thickness", "thickness at the end of the run (bed-normal)", "m", gis::depth_ramp(),
          gis::SampleType::float32, kNodata, true},
         [&] {
             const std::span<const double> made = in.maps.deposit_depth();
             std::vector<double> deposit(made.size(), kNodata);  // outside the reach box: none
             for_each_cell(reach, g.nx, [&](int, int, std::size_t k) {
                 deposit[k] = made[k] > 0.0 ? made[k] : kNodata;
             });
             return deposit;
         }},
        {{"hazard_class", "hazard class from the maximum impact pressure (" + pressure_breaks + ")", "class",
          gis::hazard_class_palette({"not reached", "low", "medium", "high"}), gis::SampleType::uint8, 255.0},
         [&] {
             const std::vector<std::uint8_t> classes = in.maps.hazard_classes();
             return std::vector<double>(classes.begin(), classes.end());
         }},
    };
    const bool complete = in.stats.end_reason != EndReason::interrupted;
    // Map k of `maps`: its GeoTIFF, style and quick-look; the files it wrote.
    const auto write_map = [&](std::size_t k) -> std::vector<std::string> {
        const auto& [spec, make_values] = maps[k];
        const std::vector<double> values = make_values();
        gis::BandInfo band;
        band.description = spec.description;
        band.units = spec.units;
        band.nodata = spec.nodata;
        band.metadata["CONFIG_HASH"] = in.config_hash;
        // Every map says whether the run reached its end: an interrupted run's maps are
        // the flow so far (summary.json "complete" says the same).
        band.dataset_metadata["AVALANCHE_COMPLETE"] = complete ? "YES" : "NO";
        band.dataset_metadata["AVALANCHE_STATUS"] = complete ? "complete" : "incomplete";
        band.metadata["DEPTH_THRESHOLD_M"] = std::to_string(out.h_threshold);
        if (spec.thickness) band.metadata["THICKNESS"] = "bed-normal";
        const std::string tif = spec.name + ".tif";
        // Without a predictor: a map is nodata outside the affected area, and such rasters
        // came out smaller and faster without one (docs/performance.md, "Hazard maps
        // where the flow went"); the DEM keeps it.
        gis::write_geotiff((d / tif).string(), geo, values, band, spec.type, gis::Predictor::none);
        gis::write_qml((d / (spec.name + ".qml")).string(), spec.ramp);
        gis::write_quicklook_png_over((d / (spec.name + ".png")).string(), geo, values, shade,
                                      spec.ramp, spec.nodata, spec.block);
        return {tif, spec.name + ".qml", spec.name + ".png"};
    };
    // The computational DEM: the terrain the solver saw, on its grid.
    const auto write_dem = [&]() -> std::vector<std::string> {
        gis::BandInfo dem_band;
        dem_band.description = in.scene.frame == Frame::dem ? "computational DEM (elevation)"
                                                            : "chute bed height above its lowest point";
        // Appended, not assigned from a literal: GCC 12's -Wrestrict misreads the
        // inlined literal assignment here (a false positive).
        dem_band.units.push_back('m');
        const auto write = [&] {
            gis::write_geotiff((d / "dem.tif").string(), geo, in.scene.terrain.elevation.interior(),
                               dem_band, gis::SampleType::float32);
        };
        // A batch's scenarios of one scene link the first one's file.
        if (in.shared)
            in.shared->dem(d / "dem.tif", write);
        else
            write();
        return {"dem.tif"};
    };
    // The six maps and the DEM are independent files (GDAL only): written by as many
    // threads as the run had (summary "threads"), each taking the next one. On a large
    // grid they were most of a run's time outside the solver (docs/performance.md,
    // "Outside the solver"). The DEM goes first: it takes two to three times as long as
    // a map (real values everywhere to compress), and started last it left the other
    // threads idle at the end. The list of files keeps the order of `maps`, DEM last.
    std::vector<std::vector<std::string>> files(maps.size() + 1);
    run_on_threads(files.size(), in.stats.threads, [&](std::size_t n) {
        if (n == 0) files.back() = write_dem();
        else files[n - 1] = write_map(n - 1);
    });
    std::vector<std::string> written;
    for (const auto& f : files) written.insert(written.end(), f.begin(), f.end());

    if (in.probes && !in.probes->points().empty()) {
        write_monitoring_csv((d / "monitoring.csv").string(), *in.probes);
        write_monitoring_hdf5((d / "monitoring.h5").string(), *in.probes);
        written.insert(written.end(), {"monitoring.csv", "monitoring.h5"});
    }
    return written;
}

}  // namespace avalanche
