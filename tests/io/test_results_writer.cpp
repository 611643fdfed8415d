// results.h5 read back with the HDF5 C API: layout, units, row orientation (an
// asymmetric release near y = 0 must land in the BOTTOM rows), times, attributes.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>

#include "avalanche/core/error.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/release.hpp"
#include "io_test_support.hpp"

namespace avalanche {
namespace {

struct SmallRun {
    Scenario scenario;
    Grid grid;
    TerrainFields terrain;
    Field2D release;
    RunStatistics stats;
    std::string path;
};

// A 10 m x 4 m chute of 0.5 m cells (20 x 8) with a box release near y = 0.
SmallRun run_small_chute(const test::ScratchDir& dir) {
    SmallRun r;
    ChuteGeometry chute;
    chute.slope_deg = 35.0;
    chute.length = 10.0;
    chute.width = 4.0;
    r.scenario.terrain = chute;
    r.scenario.release = ReleaseShape{BoxRelease{{1.0, 3.0}, {0.5, 1.5}, 0.5}};
    r.scenario.cell_size = 0.5;
    r.scenario.numerics.t_end = 1.0;
    r.scenario.numerics.output_interval = 0.25;
    r.grid = chute_grid(chute, r.scenario.cell_size);
    r.terrain = chute_terrain(chute, r.grid, r.scenario.numerics.gravity);
    r.release = rasterize_release(std::get<ReleaseShape>(r.scenario.release), r.grid);
    const State initial = state_at_rest(r.grid, r.release, r.terrain);
    const double h_min = effective_h_min(r.scenario.numerics, initial, r.terrain);

    ResultsMetadata meta;
    meta.geotransform = {0.0, 0.5, 0.0, 4.0, 0.0, -0.5};
    meta.config = effective_config(r.scenario);
    meta.config_hash = config_hash(meta.config);
    meta.h_min = h_min;
    r.path = dir.file("results.h5");
    Simulation sim(r.grid, r.terrain, r.scenario.material, r.scenario.numerics, initial, h_min);
    ResultsWriter writer(r.path, r.grid, meta);
    sim.add_observer(&writer);
    r.stats = sim.run();
    EXPECT_TRUE(std::filesystem::exists(r.path + ".part"));
    EXPECT_FALSE(std::filesystem::exists(r.path)) << "results.h5 must appear only when complete";
    writer.finish(r.stats);
    EXPECT_EQ(writer.snapshots(), 5u);
    return r;
}

TEST(ResultsWriter, DatasetsHaveTheGridShapeAndOneRecordPerSnapshot) {
    test::ScratchDir dir("results-shape");
    const SmallRun r = run_small_chute(dir);
    EXPECT_FALSE(std::filesystem::exists(r.path + ".part"));
    for (const char* name : {"h", "u", "v"}) {
        const auto a = test::read_h5_dataset(r.path, name);
        ASSERT_EQ(a.dims.size(), 3u) << name;
        EXPECT_EQ(a.dims[0], 5u) << name;
        EXPECT_EQ(a.dims[1], 8u) << name;   // ny rows
        EXPECT_EQ(a.dims[2], 20u) << name;  // nx columns
    }
    const auto time = test::read_h5_dataset(r.path, "time");
    ASSERT_EQ(time.dims, (std::vector<hsize_t>{5}));
    EXPECT_EQ(time.values.front(), 0.0);
    EXPECT_DOUBLE_EQ(time.values.back(), r.stats.simulated_time);
    for (std::size_t k = 1; k < time.values.size(); ++k) {
        EXPECT_GT(time.values[k], time.values[k - 1]);
        // Snapshot times are multiples of output_interval (the run ends at t_end = 1 s).
        EXPECT_NEAR(time.values[k] / 0.25, std::round(time.values[k] / 0.25), 1e-9);
    }
}

// A 600 x 300 grid of 2 m cells: 3 x 2 chunk tiles of 256 x 256, the last column and
// row of tiles cut by the grid's edge. The tests set its state and normal thickness.
struct TiledGrid {
    Grid g{600, 300, 2.0, 2.0, 0.0, 0.0};
    TerrainFields terrain;
    State s{g};
    TiledGrid() { terrain.allocate(g, false, false); }
};

// Cells of snapshot `record` in the results.h5 at `path` whose h (bed-normal), u or v
// differ from those of t's state (dataset row r holds solver row ny - 1 - r).
std::size_t record_mismatches(const std::string& path, const TiledGrid& t, hsize_t record) {
    const auto h = test::read_h5_dataset(path, "h"), u = test::read_h5_dataset(path, "u"),
               v = test::read_h5_dataset(path, "v");
    const Grid& g = t.g;
    EXPECT_EQ(h.dims[1], static_cast<hsize_t>(g.ny));
    EXPECT_EQ(h.dims[2], static_cast<hsize_t>(g.nx));
    std::size_t mismatches = 0;
    for (int r = 0; r < g.ny; ++r)
        for (int i = 0; i < g.nx; ++i) {
            const int j = g.ny - 1 - r;
            const double hh = t.s.h(i, j);
            mismatches += h.at(record, r, i) != hh * t.terrain.normal_thickness(i, j);
            mismatches += u.at(record, r, i) != (hh > 0.0 ? t.s.hu(i, j) / hh : 0.0);
            mismatches += v.at(record, r, i) != (hh > 0.0 ? t.s.hv(i, j) / hh : 0.0);
        }
    return mismatches;
}

// Chunks allocated in the dataset `name` of the results.h5 at `path`, over all records.
hsize_t stored_chunks(const std::string& path, const char* name) {
    hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
    hid_t space = H5Dget_space(ds);  // everything selected
    hsize_t chunks = 0;
    EXPECT_GE(H5Dget_num_chunks(ds, space, &chunks), 0);
    H5Sclose(space);
    H5Dclose(ds);
    H5Fclose(f);
    return chunks;
}

// A snapshot writes only the chunk tiles (256 x 256) that meet the active box; the
// others are not allocated and read back as zeros. Material in a box straddling two
// tiles: every value read back equals the state's, exactly two chunks hold the record;
// an empty box writes none.
TEST(ResultsWriter, OnlyTheTilesMeetingTheActiveBoxAreWritten) {
    test::ScratchDir dir("results-tiles");
    TiledGrid t;
    const ActiveBox box{250, 262, 10, 20};  // tile columns 0 and 1, dataset rows 280-289
    std::size_t wet = 0;
    for (int j = box.j0; j < box.j1; ++j)
        for (int i = box.i0; i < box.i1; ++i) {
            if ((i + j) % 3 == 0) continue;  // dry cells inside the box too
            t.s.h(i, j) = 0.1 + 0.01 * i + 0.001 * j;
            t.s.hu(i, j) = 0.3 * t.s.h(i, j) - 0.002 * j;
            t.s.hv(i, j) = -0.2 * t.s.h(i, j) + 0.001 * i;
            t.terrain.normal_thickness(i, j) = 0.9 - 0.001 * j;
            ++wet;
        }
    EXPECT_EQ(wet, 80u);
    ResultsMetadata meta;
    meta.config = nlohmann::json::object();
    const std::string path = dir.file("results.h5");
    const TiledGrid dry;
    {
        ResultsWriter writer(path, t.g, meta);
        writer.on_output(SimulationView{t.g, t.terrain, t.s, 0.5, 10, box});
        writer.on_output(SimulationView{dry.g, dry.terrain, dry.s, 1.0, 20, ActiveBox{}});
        writer.finish(RunStatistics{});
    }
    ASSERT_EQ(test::read_h5_dataset(path, "h").dims, (std::vector<hsize_t>{2, 300, 600}));
    EXPECT_EQ(record_mismatches(path, t, 0), 0u);
    EXPECT_EQ(record_mismatches(path, dry, 1), 0u);
    // Chunks allocated in each dataset: the first record's two, none for the second.
    for (const char* name : {"h", "u", "v"}) EXPECT_EQ(stored_chunks(path, name), 2u) << name;
}

// The chunks are encoded on the run's threads (chunk_encoder.hpp) and written as bytes,
// a batch at a time. Material over the whole grid, on two threads: its six tiles (18
// chunks, more than a batch), the edge tiles among them, read back through HDF5's own
// shuffle and deflate filters to the bit.
TEST(ResultsWriter, ChunksEncodedOnThreadsReadBackThroughHdf5sFiltersToTheBit) {
    test::ScratchDir dir("results-encoded");
    TiledGrid t;
    for (int j = 0; j < t.g.ny; ++j)
        for (int i = 0; i < t.g.nx; ++i) {
            if ((3 * i + j) % 7 == 0) continue;  // dry cells among them
            t.s.h(i, j) = 0.05 + 1e-3 * i + 1e-5 * j * j;
            t.s.hu(i, j) = std::sin(0.01 * i) * t.s.h(i, j);
            t.s.hv(i, j) = std::cos(0.02 * j) * t.s.h(i, j) - 1e-4 * i;
            t.terrain.normal_thickness(i, j) = 0.8 + 1e-4 * (i - j);
        }
    ResultsMetadata meta;
    meta.config = nlohmann::json::object();
    const std::string path = dir.file("results.h5");
    const int threads_before = omp_get_max_threads();
    omp_set_num_threads(2);
    {
        ResultsWriter writer(path, t.g, meta);
        writer.on_output(SimulationView{t.g, t.terrain, t.s, 0.0, 0, ActiveBox{0, t.g.nx, 0, t.g.ny}});
        writer.finish(RunStatistics{});
    }
    omp_set_num_threads(threads_before);
    ASSERT_EQ(test::read_h5_dataset(path, "h").dims, (std::vector<hsize_t>{1, 300, 600}));
    EXPECT_EQ(record_mismatches(path, t, 0), 0u);
    EXPECT_EQ(stored_chunks(path, "h"), 6u);
    // Stored compressed: the data are 1.44 MB raw.
    hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t ds = H5Dopen2(f, "h", H5P_DEFAULT);
    EXPECT_LT(H5Dget_storage_size(ds), 1'440'000u);
    H5Dclose(ds);
    H5Fclose(f);
}

// A checkpoint's saved snapshots as a resumed run finds them: /results/{time,h,u,v},
// one record, the fields chunked as the writer chunks them (1 x 8 x 20 for a 20 x 8
// grid), with the writer's filters or without any.
void write_saved_snapshots(const std::string& path, bool filters) {
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t g = H5Gcreate2(f, "results", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::vector<double> zeros(8 * 20, 0.0);
    {
        const hsize_t dims[1] = {1}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {256};
        hid_t space = H5Screate_simple(1, dims, maxdims), dcpl = H5Pcreate(H5P_DATASET_CREATE);
        H5Pset_chunk(dcpl, 1, chunk);
        hid_t ds = H5Dcreate2(g, "time", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
        H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data());
        H5Dclose(ds), H5Pclose(dcpl), H5Sclose(space);
    }
    for (const char* name : {"h", "u", "v"}) {
        const hsize_t dims[3] = {1, 8, 20}, maxdims[3] = {H5S_UNLIMITED, 8, 20}, chunk[3] = {1, 8, 20};
        hid_t space = H5Screate_simple(3, dims, maxdims), dcpl = H5Pcreate(H5P_DATASET_CREATE);
        H5Pset_chunk(dcpl, 3, chunk);
        if (filters) H5Pset_shuffle(dcpl), H5Pset_deflate(dcpl, 4);
        hid_t ds = H5Dcreate2(g, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
        H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data());
        H5Dclose(ds), H5Pclose(dcpl), H5Sclose(space);
    }
    H5Gclose(g), H5Fclose(f);
}

// A resumed run writes its snapshots' chunks encoded for the shuffle and deflate
// filters, into the datasets it copied from the checkpoint: saved snapshots stored
// otherwise (here without filters, where the encoded bytes would read back as garbage)
// are refused with the checkpoint's name; stored as the writer stores them, they resume.
TEST(ResultsWriter, ResumeRefusesSavedSnapshotsStoredOtherwise) {
    test::ScratchDir dir("results-resume-layout");
    const Grid g{20, 8, 0.5, 0.5, 0.0, 0.0};
    ResultsMetadata meta;
    meta.config = nlohmann::json::object();
    const std::string good = dir.file("good.h5"), bad = dir.file("bad.h5");
    write_saved_snapshots(good, true);
    write_saved_snapshots(bad, false);
    {
        ResultsWriter w(dir.file("resumed-good.h5"), g, meta);
        EXPECT_NO_THROW(w.resume_from(good));
        EXPECT_EQ(w.snapshots(), 1u);
    }
    ResultsWriter w(dir.file("resumed-bad.h5"), g, meta);
    try {
        w.resume_from(bad);
        FAIL() << "snapshots without the shuffle and deflate filters were taken";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(bad + ": the saved snapshots are not stored as this version writes them"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ResultsWriter, RowZeroIsTheTopSoAReleaseNearYZeroIsInTheBottomRows) {
    test::ScratchDir dir("results-flip");
    const SmallRun r = run_small_chute(dir);
    const auto h = test::read_h5_dataset(r.path, "h");
    const hsize_t ny = h.dims[1], nx = h.dims[2];
    // At t = 0: dataset row (ny - 1 - j) holds solver row j, exactly.
    for (hsize_t row = 0; row < ny; ++row)
        for (hsize_t col = 0; col < nx; ++col)
            EXPECT_EQ(h.at(0, row, col),
                      r.release(static_cast<int>(col), static_cast<int>(ny - 1 - row)))
                << "row " << row << " col " << col;
    // The box covers y in [0.5, 1.5] m: solver rows 1-2, dataset rows 5-6 of 8.
    EXPECT_EQ(h.at(0, 6, 3), 0.5);
    EXPECT_EQ(h.at(0, 5, 3), 0.5);
    EXPECT_EQ(h.at(0, 1, 3), 0.0);
    EXPECT_EQ(h.at(0, 2, 3), 0.0);
    // At every time the mass-weighted mean row stays in the lower half of the dataset
    // (initially row 5.5 of 0..7; a flipped file would put it at row 1.5).
    for (hsize_t t = 0; t < h.dims[0]; ++t) {
        double mass = 0.0, moment = 0.0;
        for (hsize_t row = 0; row < ny; ++row)
            for (hsize_t col = 0; col < nx; ++col) {
                mass += h.at(t, row, col);
                moment += static_cast<double>(row) * h.at(t, row, col);
            }
        ASSERT_GT(mass, 0.0);
        EXPECT_GT(moment / mass, 4.5) << "t index " << t;
    }
}

TEST(ResultsWriter, VelocitiesAreZeroWhereDryAndMoveDownTheChute) {
    test::ScratchDir dir("results-velocity");
    const SmallRun r = run_small_chute(dir);
    const auto h = test::read_h5_dataset(r.path, "h");
    const auto u = test::read_h5_dataset(r.path, "u");
    const auto v = test::read_h5_dataset(r.path, "v");
    double max_u = 0.0;
    for (std::size_t k = 0; k < h.values.size(); ++k) {
        if (h.values[k] == 0.0) {
            EXPECT_EQ(u.values[k], 0.0);
            EXPECT_EQ(v.values[k], 0.0);
        }
        max_u = std::max(max_u, u.values[k]);
    }
    // 35 deg slope, delta 20 deg: after 1 s the front moves at several m/s along +x.
    EXPECT_GT(max_u, 1.0);
}

TEST(ResultsWriter, RootAttributesDescribeTheRun) {
    test::ScratchDir dir("results-attributes");
    const SmallRun r = run_small_chute(dir);
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "geotransform"),
              (std::vector<double>{0.0, 0.5, 0.0, 4.0, 0.0, -0.5}));
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "crs_wkt"), "");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "frame"), "chute");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "thickness"), "bed-normal");
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "gravity"), std::vector<double>{9.81});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "phi_deg"), std::vector<double>{35.0});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "delta_deg"), std::vector<double>{20.0});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "cfl"), std::vector<double>{0.2});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "cell_size"), std::vector<double>{0.5});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "t_end"), std::vector<double>{1.0});
    EXPECT_EQ(test::read_h5_double_attribute(r.path, "output_interval"), std::vector<double>{0.25});
    // h_min is the effective value: h_min_relative x the deepest release (0.5 m).
    EXPECT_DOUBLE_EQ(test::read_h5_double_attribute(r.path, "h_min")[0], 1e-5 * 0.5);
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "scheme"), "waf");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "limiter"), "van_leer");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "earth_pressure"), "savage-hutter");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "release.shape"), "box");
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "software_version"), software_version());
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "source_hash"), source_hash());
    const auto hash = test::read_h5_string_attribute(r.path, "config_hash");
    EXPECT_EQ(hash, config_hash(effective_config(r.scenario)));
    EXPECT_EQ(hash.size(), 16u);
    EXPECT_EQ(test::read_h5_string_attribute(r.path, "end_reason"), "end_time");
}

}  // namespace
}  // namespace avalanche
