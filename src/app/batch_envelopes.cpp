// Envelope maps and impact frequency over the scenarios of a batch.
//
// Built by reading back each scenario's GeoTIFFs rather than keeping its HazardMaps in
// memory: scenarios skipped on resume have no maps in memory, so the read-back path is
// needed anyway, and one path for all keeps them identical; memory stays at one map set
// however many scenarios there are; and the envelope is exactly the maximum of the maps
// a user opens (the float32 values as written), so envelope >= each map holds bit for bit.
#include <algorithm>
#include <filesystem>
#include <limits>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "batch_outputs.hpp"

namespace avalanche::detail {

namespace {

constexpr double kNodata = -9999.0;

bool same_grid(const Grid& a, const Grid& b) {
    return a.nx == b.nx && a.ny == b.ny && a.dx == b.dx && a.dy == b.dy && a.x0 == b.x0 &&
           a.y0 == b.y0;
}

// Values of a map that hold data: a scenario's maps are nodata where it never reached.
bool has_value(const gis::RasterData& r, std::size_t k) {
    return !(r.nodata && r.values[k] == *r.nodata);
}

struct Envelope {
    std::vector<double> value;
    bool take_min = false;
    void add(const gis::RasterData& r) {
        if (value.empty()) value.assign(r.values.size(), kNodata);
        for (std::size_t k = 0; k < value.size(); ++k) {
            if (!has_value(r, k)) continue;
            const double v = r.values[k];
            if (value[k] == kNodata || (take_min ? v < value[k] : v > value[k])) value[k] = v;
        }
    }
};

}  // namespace

std::vector<std::string> write_envelopes(const std::string& dir,
                                         const std::vector<BatchResult>& rows) {
    const std::vector<std::pair<std::string, std::string>> maps = {{"max_depth", "m"},
                                                                   {"max_velocity", "m/s"},
                                                                   {"max_pressure", "kPa"},
                                                                   {"arrival_time", "s"}};
    std::vector<Envelope> envelopes(maps.size());
    envelopes[3].take_min = true;  // earliest arrival over the scenarios
    std::vector<double> reached;
    std::optional<gis::GeoGrid> geo;
    int scenarios = 0;
    for (const auto& row : rows) {
        if (!row.summary) continue;
        for (std::size_t m = 0; m < maps.size(); ++m) {
            const std::string path =
                (std::filesystem::path(row.dir) / (maps[m].first + ".tif")).string();
            const gis::RasterData r = gis::read_geotiff(path);
            if (!geo) geo = r.geo;
            if (!same_grid(geo->grid, r.geo.grid))
                throw InputError(path, "is on another grid than the batch's first scenario");
            envelopes[m].add(r);
            // max_depth is masked below output.h_threshold: a value means "reached".
            if (m == 0) {
                if (reached.empty()) reached.assign(r.values.size(), 0.0);
                for (std::size_t k = 0; k < r.values.size(); ++k) reached[k] += has_value(r, k);
            }
        }
        ++scenarios;
    }
    if (scenarios == 0) return {};
    for (double& f : reached) f /= scenarios;

    const std::filesystem::path d(dir);
    const std::string count = std::to_string(scenarios);
    std::vector<std::string> written;
    gis::BandInfo freq{"fraction of the " + count +
                           " scenarios whose max depth reached "
                           "output.h_threshold",
                       "fraction",
                       kNodata,
                       {{"SCENARIOS", count}},
                       {}};
    gis::write_geotiff((d / "impact_frequency.tif").string(), *geo, reached, freq);
    written.push_back("impact_frequency.tif");
    const char* words[] = {"maximum flow depth (bed-normal)", "maximum along-surface speed",
                           "maximum impact pressure rho |u|^2", "earliest arrival time"};
    for (std::size_t m = 0; m < maps.size(); ++m) {
        const std::string name = m == 3 ? "envelope_min_arrival_time" : "envelope_" + maps[m].first;
        gis::BandInfo band{std::string(words[m]) + " over " + count + " scenarios",
                           maps[m].second,
                           kNodata,
                           {{"SCENARIOS", count}},
                           {}};
        if (m == 0) band.metadata["THICKNESS"] = "bed-normal";
        gis::write_geotiff((d / (name + ".tif")).string(), *geo, envelopes[m].value, band);
        written.push_back(name + ".tif");
    }
    return written;
}

}  // namespace avalanche::detail
