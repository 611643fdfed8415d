// `batch --observed`: calibration of a sweep against an observed deposit. The observation
// is built independently of the code under test: the footprint of one scenario's
// max_depth.tif turned into polygons by GDAL's polygonizer and reprojected by ogr2ogr to
// another CRS (geographic degrees), so the scenario it came from must fit it exactly
// (Jaccard 1, runout error 0) and rank first; the other scenarios' Jaccard indices are
// recounted here from the two maps. Refusals: unreadable, no polygon, outside the DEM.
#include <gdal_alg.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "avalanche/app/cli.hpp"
#include "batch_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

// The cells of a product map that hold a value (reached), row-major as in the file.
std::vector<bool> footprint_of(const test::Raster& r) {
    std::vector<bool> reached(r.values.size());
    for (std::size_t k = 0; k < r.values.size(); ++k)
        reached[k] = !(r.has_nodata && r.values[k] == r.nodata);
    return reached;
}

// The reached cells of `map` as polygons (GDALPolygonize of a 0/1 mask, zeros masked out)
// in a GeoPackage in the map's CRS.
void polygonize_footprint(const std::string& map, const std::string& gpkg) {
    GDALAllRegister();
    const test::Raster r = test::read_raster(map);
    GDALDataset* src = GDALDataset::Open(map.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(src, nullptr);
    GDALDriver* mem_driver = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDataset* mem = mem_driver->Create("", r.width, r.height, 1, GDT_Byte, nullptr);
    std::vector<GByte> mask(r.values.size());
    const auto reached = footprint_of(r);
    for (std::size_t k = 0; k < mask.size(); ++k) mask[k] = reached[k] ? 1 : 0;
    ASSERT_EQ(mem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, r.width, r.height, mask.data(),
                                              r.width, r.height, GDT_Byte, 0, 0, nullptr),
              CE_None);
    GDALDriver* gpkg_driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    GDALDataset* out = gpkg_driver->Create(gpkg.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    ASSERT_NE(out, nullptr);
    OGRSpatialReference srs(*src->GetSpatialRef());
    OGRLayer* layer = out->CreateLayer("deposit", &srs, wkbPolygon, nullptr);
    OGRFieldDefn field("reached", OFTInteger);
    layer->CreateField(&field);
    GDALRasterBand* band = mem->GetRasterBand(1);
    band->SetNoDataValue(0);  // not needed by Polygonize (the mask is), but explicit
    std::array<double, 6> gt{};
    src->GetGeoTransform(gt.data());
    mem->SetGeoTransform(gt.data());
    ASSERT_EQ(GDALPolygonize(band, band, layer, 0, nullptr, nullptr, nullptr), CE_None);
    GDALClose(out);
    GDALClose(mem);
    GDALClose(src);
}

std::string dem_scenario() {
    return std::string("[terrain]\ntype = \"dem\"\ndem = \"") + test::avaKot("avaKot_dem.tif") +
           "\"\n[release]\npolygons = \"" + test::avaKot("avaKot_release.gpkg") +
           "\"\nthickness_field = \"thickness\"\n[material]\nphi_deg = 35.0\ndelta_deg = "
           "25.0\n[numerics]\ncell_size = 30.0\nt_end = 30.0\noutput_interval = 10.0\n";
}

const nlohmann::json& entry_of(const nlohmann::json& calibration, const std::string& id) {
    for (const auto& s : calibration["scenarios"])
        if (s["id"] == id) return s;
    ADD_FAILURE() << "no scenario " << id;
    return calibration;
}

TEST(BatchCalibration, ScenarioWhoseFootprintWasObservedRanksFirstAfterReprojection) {
    test::ScratchDir dir("batch-calibration");
    const auto base = dir.write("base.toml", dem_scenario());
    const std::string out = dir.file("out");
    const std::vector<std::string> batch = {"avalanche-hazard", "batch", "--quiet",
                                            "--scenario",       base,    "--sweep",
                                            "delta=20,25,30",   "--out", out};
    ASSERT_EQ(run_cli(batch), 0);
    EXPECT_FALSE(fs::exists(out + "/calibration.json"));  // only with --observed

    // The observation: delta=25's footprint, in EPSG:4326 (not the grid's CRS).
    const std::string gpkg = dir.file("footprint.gpkg"), shp = dir.file("deposit.shp");
    polygonize_footprint(out + "/delta=25/max_depth.tif", gpkg);
    ASSERT_TRUE(test::ogr2ogr(shp, gpkg, {"-t_srs", "EPSG:4326", "-f", "ESRI Shapefile"}));
    const auto in_degrees = test::first_polygon(shp);
    OGREnvelope e;
    in_degrees->getEnvelope(&e);
    ASSERT_LT(std::abs(e.MaxX), 180.0);  // longitudes: the file really is in degrees
    ASSERT_LT(std::abs(e.MaxY), 90.0);

    // Same batch with --observed: every scenario is complete, only the comparison is redone.
    auto calibrated = batch;
    calibrated.insert(calibrated.end(), {"--observed", shp});
    ASSERT_EQ(run_cli(calibrated), 0);

    const auto cal = test::read_json(out + "/calibration.json");
    EXPECT_EQ(cal["best"], "delta=25");
    const auto& best = entry_of(cal, "delta=25");
    EXPECT_EQ(best["rank"], 1);
    EXPECT_EQ(best["jaccard"].get<double>(), 1.0);
    EXPECT_NEAR(best["runout_error_m"].get<double>(), 0.0, 1e-9);
    EXPECT_NEAR(best["score"].get<double>(), 0.0, 1e-9);

    // The others: Jaccard recounted from the two maps; the runout error is the difference
    // of the summaries' runouts (same scene, so the same release top).
    const auto observed = footprint_of(test::read_raster(out + "/delta=25/max_depth.tif"));
    const double observed_runout =
        test::read_json(out + "/delta=25/summary.json")["runout"]["runout_length_m"];
    EXPECT_EQ(cal["observed"]["cells"].get<std::size_t>(),
              static_cast<std::size_t>(std::count(observed.begin(), observed.end(), true)));
    for (const std::string id : {"delta=20", "delta=30"}) {
        const auto sim = footprint_of(test::read_raster(out + "/" + id + "/max_depth.tif"));
        ASSERT_EQ(sim.size(), observed.size());
        std::size_t both = 0, either = 0;
        for (std::size_t k = 0; k < sim.size(); ++k) {
            both += sim[k] && observed[k];
            either += sim[k] || observed[k];
        }
        const auto& fit = entry_of(cal, id);
        EXPECT_DOUBLE_EQ(fit["jaccard"].get<double>(), static_cast<double>(both) / either) << id;
        EXPECT_LT(fit["jaccard"].get<double>(), 1.0) << id;
        EXPECT_GT(fit["rank"].get<int>(), 1) << id;
        const double runout =
            test::read_json(out + "/" + id + "/summary.json")["runout"]["runout_length_m"];
        EXPECT_NEAR(fit["runout_error_m"].get<double>(), runout - observed_runout, 1e-9) << id;
    }

    // comparison.csv carries the fit, comparison.md names the best scenario.
    const auto csv = test::read_csv(out + "/comparison.csv");
    const auto col = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(csv[0].begin(), csv[0].end(), name) -
                                        csv[0].begin());
    };
    ASSERT_LT(col("fit_rank"), csv[0].size());
    ASSERT_LT(col("jaccard"), csv[0].size());
    ASSERT_LT(col("runout_error_m"), csv[0].size());
    EXPECT_EQ(csv[0].back(), "wall_s");
    for (std::size_t r = 1; r < csv.size(); ++r) {
        const auto& fit = entry_of(cal, csv[r][0]);
        EXPECT_EQ(csv[r][col("fit_rank")], std::to_string(fit["rank"].get<int>()));
        EXPECT_EQ(std::strtod(csv[r][col("jaccard")].c_str(), nullptr),
                  fit["jaccard"].get<double>());
    }
    EXPECT_NE(test::read_text(out + "/comparison.md").find("Best fit: **delta=25**"),
              std::string::npos);
}

TEST(BatchCalibration, RefusesUnusableObservationsBeforeWritingAnything) {
    test::ScratchDir dir("batch-observed-refusal");
    const auto base = dir.write("base.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    const auto rect = [](double x0, double x1) {
        return "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
               "\"properties\":{},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[" +
               std::to_string(x0) + ",1],[" + std::to_string(x1) + ",1],[" + std::to_string(x1) +
               ",3],[" + std::to_string(x0) + ",3],[" + std::to_string(x0) + ",1]]]}}]}";
    };
    const std::vector<std::pair<std::string, std::string>> cases = {
        {dir.file("missing.shp"), "not found"},
        {dir.write("garbage.shp", "not a shapefile"), "garbage.shp"},
        {dir.write("empty.geojson", R"({"type":"FeatureCollection","features":[]})"),
         "contains no polygon"},
        {dir.write("line.geojson",
                   R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
                   R"("geometry":{"type":"LineString","coordinates":[[1,1],[5,2]]}}]})"),
         "must be polygons"},
        {dir.write("far.geojson", rect(500.0, 520.0)), "outside the DEM"},
    };
    for (const auto& [file, why] : cases) {
        const auto r =
            test::run_binary(dir, "batch --scenario '" + base + "' --sweep delta=20 --observed '" +
                                      file + "' --out '" + out + "'");
        EXPECT_EQ(r.exit_code, 3) << file << ": " << r.err;
        EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
        EXPECT_EQ(test::lines_of(r.err).size(), 1u) << r.err;
        EXPECT_FALSE(fs::exists(out)) << file;
    }
}

}  // namespace
}  // namespace avalanche
