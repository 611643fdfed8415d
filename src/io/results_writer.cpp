#include "avalanche/io/results_writer.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <system_error>
#include <type_traits>
#include <vector>

#include "avalanche/core/error.hpp"
#include "avalanche/io/effective_config.hpp"
#include "chunk_encoder.hpp"
#include "hdf5_handles.hpp"

namespace avalanche {

using detail::h5_check;
using detail::h5_take;
using detail::Hid;
using detail::write_attribute;

namespace {

// Tiles of at most 256 x 256 cells (512 KiB) per chunk: big enough for gzip, small
// enough for HDF5's default 1 MiB chunk cache.
constexpr hsize_t kChunkTile = 256;
constexpr unsigned kGzipLevel = 4;  // most of a snapshot is zeros; higher levels gain little

// The snapshot's fields, in the order of their chunks in a batch.
enum SnapshotField { kFieldH, kFieldU, kFieldV, kFields };

// Writes the configuration as root attributes: material and numerics keys bare (as the
// names users know: phi_deg, cfl, ...), other sections as "section.key".
void write_config_attributes(hid_t root, const nlohmann::json& config, const std::string& file) {
    for (const auto& [section, values] : config.items()) {
        if (!values.is_object()) continue;
        const bool bare = section == "material" || section == "numerics";
        for (const auto& [key, v] : values.items()) {
            if (bare && key == "h_min") continue;  // written as the effective value instead
            const std::string name = bare ? key : section + "." + key;
            if (v.is_number_integer()) {
                write_attribute(root, name, v.get<std::int64_t>(), file);
            } else if (v.is_number()) {
                write_attribute(root, name, v.get<double>(), file);
            } else if (v.is_string()) {
                write_attribute(root, name, v.get<std::string>(), file);
            } else if (v.is_array() && std::all_of(v.begin(), v.end(),
                                                   [](const auto& e) { return e.is_number(); })) {
                const auto numbers = v.get<std::vector<double>>();
                write_attribute(root, name, std::span<const double>(numbers), file);
            } else if (!v.is_null()) {
                write_attribute(root, name, v.dump(), file);
            }
        }
        if (bare && section == "numerics" && values.contains("h_min"))
            write_attribute(root, "h_min_setting", values["h_min"].get<double>(), file);
    }
}

}  // namespace

struct ResultsWriter::Impl {
    std::string part_path;
    Grid grid;
    Hid file;
    Hid time, h, u, v;
    std::size_t snapshots = 0;
    // Per thread: a chunk's values and its encoder; per chunk of a batch: its bytes.
    std::vector<std::vector<double>> chunk_values;
    std::vector<std::unique_ptr<detail::ChunkEncoder>> encoders;
    std::vector<std::vector<unsigned char>> encoded;

    Hid create_field(const char* name, const char* units, const char* description) {
        const hsize_t ny = static_cast<hsize_t>(grid.ny), nx = static_cast<hsize_t>(grid.nx);
        const hsize_t dims[3] = {0, ny, nx};
        const hsize_t maxdims[3] = {H5S_UNLIMITED, ny, nx};
        const std::array<hsize_t, 3> chunk = chunk_dims();
        const std::string what = std::string("create the dataset ") + name;
        Hid space = h5_take(H5Screate_simple(3, dims, maxdims), H5Sclose, part_path, what);
        Hid dcpl = h5_take(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, part_path, what);
        h5_check(H5Pset_chunk(dcpl.get(), 3, chunk.data()), part_path, what);
        // A snapshot writes only the chunk tiles that meet the active box; the others
        // are never allocated and read as this fill value (on_output).
        const double dry = 0.0;
        h5_check(H5Pset_fill_value(dcpl.get(), H5T_NATIVE_DOUBLE, &dry), part_path, what);
        h5_check(H5Pset_shuffle(dcpl.get()), part_path, what);
        h5_check(H5Pset_deflate(dcpl.get(), kGzipLevel), part_path, what);
        Hid ds = h5_take(H5Dcreate2(file.get(), name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                    dcpl.get(), H5P_DEFAULT),
                         H5Dclose, part_path, what);
        write_attribute(ds.get(), "units", std::string(units), part_path);
        write_attribute(ds.get(), "description", std::string(description), part_path);
        return ds;
    }

    Hid create_time() {
        const hsize_t dims[1] = {0}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {256};
        const std::string what = "create the dataset time";
        Hid space = h5_take(H5Screate_simple(1, dims, maxdims), H5Sclose, part_path, what);
        Hid dcpl = h5_take(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, part_path, what);
        h5_check(H5Pset_chunk(dcpl.get(), 1, chunk), part_path, what);
        Hid ds = h5_take(H5Dcreate2(file.get(), "time", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                    dcpl.get(), H5P_DEFAULT),
                         H5Dclose, part_path, what);
        write_attribute(ds.get(), "units", std::string("s"), part_path);
        write_attribute(ds.get(), "description", std::string("simulated time of each snapshot"),
                        part_path);
        return ds;
    }

    // Grows the dataset (rank 1 or 3: HDF5 reads as many sizes) by one record along
    // the first axis.
    void extend(const Hid& ds) const {
        const hsize_t extent[3] = {snapshots + 1, static_cast<hsize_t>(grid.ny),
                                   static_cast<hsize_t>(grid.nx)};
        h5_check(H5Dset_extent(ds.get(), extent), part_path, "append a snapshot");
    }
    // The snapshot fields' chunks: one record's tile of rows x columns.
    [[nodiscard]] std::array<hsize_t, 3> chunk_dims() const {
        return {1, std::min<hsize_t>(grid.ny, kChunkTile), std::min<hsize_t>(grid.nx, kChunkTile)};
    }
    // Cells of a chunk: H5Dwrite_chunk takes whole chunks, also where the grid's edge
    // cuts them.
    [[nodiscard]] std::size_t chunk_cells() const {
        const std::array<hsize_t, 3> c = chunk_dims();
        return static_cast<std::size_t>(c[1] * c[2]);
    }
    // Whether the snapshot dataset `ds` is stored as create_field stores it: chunks of
    // one record's tile, the shuffle filter and then deflate. on_output writes encoded
    // chunks as they are, which a dataset stored otherwise would read back wrong.
    [[nodiscard]] bool stored_as_written(const Hid& ds) const {
        Hid dcpl(H5Dget_create_plist(ds.get()), H5Pclose);
        if (!dcpl.valid() || H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return false;
        std::array<hsize_t, 3> chunk{};
        if (H5Pget_chunk(dcpl.get(), 3, chunk.data()) != 3 || chunk != chunk_dims()) return false;
        if (H5Pget_nfilters(dcpl.get()) != 2) return false;
        const auto filter = [&](unsigned k) {
            unsigned flags = 0;
            std::size_t values = 0;
            return H5Pget_filter2(dcpl.get(), k, &flags, &values, nullptr, 0, nullptr, nullptr);
        };
        return filter(0) == H5Z_FILTER_SHUFFLE && filter(1) == H5Z_FILTER_DEFLATE;
    }
    // The values of `field` in the dataset rows [r0, r1), columns [c0, c1) (one chunk
    // tile) from the state (solver row j = ny - 1 - r), into `chunk` (chunk_cells()
    // values), its cells beyond the grid's edge 0 (never read).
    void fill_chunk(const SimulationView& view, SnapshotField field, int r0, int r1, int c0, int c1,
                    std::vector<double>& chunk) const {
        const int cx = static_cast<int>(chunk_dims()[2]);
        std::fill(chunk.begin(), chunk.end(), 0.0);
        for (int r = r0; r < r1; ++r) {
            const int j = grid.ny - 1 - r;
            const double* h = view.state.h.row(j);
            double* out = chunk.data() + static_cast<std::ptrdiff_t>(r - r0) * cx;
            if (field == kFieldH) {
                for (int i = c0; i < c1; ++i) out[i - c0] = h[i] * view.terrain.normal_thickness(i, j);
            } else {
                const double* q = field == kFieldU ? view.state.hu.row(j) : view.state.hv.row(j);
                for (int i = c0; i < c1; ++i) out[i - c0] = h[i] > 0.0 ? q[i] / h[i] : 0.0;
            }
        }
    }
    // Writes the time `t` at record `snapshots`.
    void write_time(double t) const {
        const std::string what = "append a snapshot";
        Hid fspace = h5_take(H5Dget_space(time.get()), H5Sclose, part_path, what);
        const hsize_t start[1] = {snapshots}, count[1] = {1};
        h5_check(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
                 part_path, what);
        Hid mspace = h5_take(H5Screate_simple(1, count, nullptr), H5Sclose, part_path, what);
        h5_check(H5Dwrite(time.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT, &t),
                 part_path, what);
    }
};

ResultsWriter::ResultsWriter(std::string final_path, const Grid& grid, const ResultsMetadata& meta)
    : final_path_(std::move(final_path)), impl_(std::make_unique<Impl>()) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become OutputError, not stack dumps
    Impl& w = *impl_;
    w.part_path = final_path_ + ".part";
    w.grid = grid;
    w.file = h5_take(H5Fcreate(w.part_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                     H5Fclose, w.part_path, "create the file");
    const hid_t root = w.file.get();
    const std::string& f = w.part_path;
    write_attribute(root, "geotransform", std::span<const double>(meta.geotransform), f);
    write_attribute(root, "crs_wkt", meta.crs_wkt, f);
    write_attribute(root, "frame", std::string(meta.frame == Frame::chute ? "chute" : "dem"), f);
    write_attribute(root, "thickness", std::string("bed-normal"), f);
    write_attribute(root, "gravity", meta.gravity, f);
    write_attribute(root, "h_min", meta.h_min, f);
    write_attribute(root, "nx", static_cast<std::int64_t>(grid.nx), f);
    write_attribute(root, "ny", static_cast<std::int64_t>(grid.ny), f);
    write_config_attributes(root, meta.config, f);
    write_attribute(root, "config_json", meta.config.dump(), f);
    write_attribute(root, "config_hash", meta.config_hash, f);
    write_attribute(root, "software_version", software_version(), f);
    write_attribute(root, "source_hash", source_hash(), f);

    w.time = w.create_time();
    w.h = w.create_field("h", "m", "flow thickness normal to the bed");
    w.u = w.create_field("u", "m/s", "depth-averaged velocity along +x (columns)");
    w.v = w.create_field("v", "m/s", "depth-averaged velocity along +y (towards row 0)");
}

ResultsWriter::~ResultsWriter() = default;

std::size_t ResultsWriter::snapshots() const { return impl_->snapshots; }

// A snapshot writes the chunk tiles (kChunkTile x kChunkTile cells) that meet the active
// box, whole; every cell outside the box is dry (SimulationView), so the tiles beyond it
// hold zeros and are left unallocated, read back as the fill value 0. On a large grid
// with a small flow, writing (and compressing) every tile took 0.37 s a snapshot: most
// of the time loop of a short run on 1756 x 2068 cells (docs/performance.md, "Outside
// the solver"). The chunks are filled and encoded (chunk_encoder.hpp) on the run's
// threads, a batch of a few per thread at a time (so that a large box never holds all
// its encoded chunks), and written by this thread alone: HDF5 is not thread-safe.
void ResultsWriter::on_output(const SimulationView& view) {
    Impl& w = *impl_;
    if (!w.file.valid()) return;
    const int nx = w.grid.nx, ny = w.grid.ny;
    const int tile = static_cast<int>(kChunkTile);
    for (const Hid* ds : {&w.time, &w.h, &w.u, &w.v}) w.extend(*ds);
    const ActiveBox& b = view.box;
    struct Tile {
        int r0, r1, c0, c1;
    };
    std::vector<Tile> tiles;
    if (!b.empty()) {
        // Dataset row 0 is the top (solver row ny - 1): the box's rows [j0, j1) are
        // dataset rows [ny - j1, ny - j0).
        const int r_first = (ny - b.j1) / tile, r_last = (ny - 1 - b.j0) / tile;
        const int c_first = b.i0 / tile, c_last = (b.i1 - 1) / tile;
        for (int tr = r_first; tr <= r_last; ++tr)
            for (int tc = c_first; tc <= c_last; ++tc)
                tiles.push_back({tr * tile, std::min(ny, (tr + 1) * tile), tc * tile, std::min(nx, (tc + 1) * tile)});
    }
    const int chunks = static_cast<int>(tiles.size()) * kFields;
    const int threads = std::min(omp_get_max_threads(), std::max(chunks, 1));
    // Every buffer the threads fill is sized here: nothing in the parallel loop below
    // allocates, so nothing there throws.
    while (static_cast<int>(w.encoders.size()) < threads) {
        w.encoders.push_back(std::make_unique<detail::ChunkEncoder>(static_cast<int>(kGzipLevel)));
        w.encoders.back()->prepare(w.chunk_cells());
        w.chunk_values.emplace_back(w.chunk_cells());
    }
    const int batch = 4 * threads;
    if (static_cast<int>(w.encoded.size()) < std::min(batch, chunks)) {
        w.encoded.resize(static_cast<std::size_t>(std::min(batch, chunks)));
        const std::size_t most_bytes = w.encoders.front()->prepare(w.chunk_cells());
        for (auto& bytes : w.encoded) bytes.reserve(most_bytes);
    }
    const Hid* fields[kFields] = {&w.h, &w.u, &w.v};
    for (int first = 0; first < chunks; first += batch) {
        const int last = std::min(chunks, first + batch);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (last - first > 1)
        for (int c = first; c < last; ++c) {
            const int t = omp_get_thread_num();
            const Tile& tl = tiles[static_cast<std::size_t>(c / kFields)];
            std::vector<double>& values = w.chunk_values[static_cast<std::size_t>(t)];
            w.fill_chunk(view, static_cast<SnapshotField>(c % kFields), tl.r0, tl.r1, tl.c0, tl.c1, values);
            w.encoders[static_cast<std::size_t>(t)]->encode(values.data(), values.size(),
                                                            w.encoded[static_cast<std::size_t>(c - first)]);
        }
        for (int c = first; c < last; ++c) {
            const Tile& tl = tiles[static_cast<std::size_t>(c / kFields)];
            const std::vector<unsigned char>& bytes = w.encoded[static_cast<std::size_t>(c - first)];
            const hsize_t offset[3] = {w.snapshots, static_cast<hsize_t>(tl.r0), static_cast<hsize_t>(tl.c0)};
            // Filter mask 0: every filter of the dataset (shuffle, deflate) applied.
            h5_check(H5Dwrite_chunk(fields[c % kFields]->get(), H5P_DEFAULT, 0, offset, bytes.size(), bytes.data()),
                     w.part_path, "append a snapshot");
        }
    }
    w.write_time(view.t);
    ++w.snapshots;
}

static_assert(std::is_same_v<hid_t, std::int64_t>, "copy_snapshots_to takes an hid_t as int64_t");

namespace {
constexpr const char* kSnapshotSets[] = {"time", "h", "u", "v"};
}

void ResultsWriter::copy_snapshots_to(std::int64_t file, const std::string& file_path) const {
    const Impl& w = *impl_;
    Hid group = h5_take(H5Gcreate2(file, "results", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                        file_path, "create the group results");
    // Flushed first: H5Ocopy copies chunks from the file, and the last snapshot may
    // still sit in the chunk cache. H5Ocopy keeps chunking, filters and attributes.
    h5_check(H5Fflush(w.file.get(), H5F_SCOPE_LOCAL), w.part_path, "flush the snapshots");
    for (const char* name : kSnapshotSets)
        h5_check(H5Ocopy(w.file.get(), name, group.get(), name, H5P_DEFAULT, H5P_DEFAULT), file_path,
                 std::string("copy the snapshots (") + name + ")");
    write_attribute(group.get(), "snapshots", static_cast<std::int64_t>(w.snapshots), file_path);
}

void ResultsWriter::resume_from(const std::string& checkpoint_path) {
    Impl& w = *impl_;
    const hid_t cf = H5Fopen(checkpoint_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (cf < 0) throw InputError(checkpoint_path, "cannot open the checkpoint to copy its snapshots");
    Hid ckpt(cf, H5Fclose);
    if (H5Lexists(ckpt.get(), "results", H5P_DEFAULT) <= 0)
        throw InputError(checkpoint_path, "not a complete checkpoint: group results is missing");
    w.time.reset();
    w.h.reset();
    w.u.reset();
    w.v.reset();
    for (const char* name : kSnapshotSets) {
        const std::string src = std::string("results/") + name;
        h5_check(H5Ldelete(w.file.get(), name, H5P_DEFAULT), w.part_path, "replace the snapshots");
        if (H5Lexists(ckpt.get(), src.c_str(), H5P_DEFAULT) <= 0 ||
            H5Ocopy(ckpt.get(), src.c_str(), w.file.get(), name, H5P_DEFAULT, H5P_DEFAULT) < 0)
            throw InputError(checkpoint_path, "cannot copy the snapshots " + src);
    }
    const auto open = [&](const char* name) {
        return h5_take(H5Dopen2(w.file.get(), name, H5P_DEFAULT), H5Dclose, w.part_path,
                       std::string("open the dataset ") + name);
    };
    w.time = open("time");
    w.h = open("h");
    w.u = open("u");
    w.v = open("v");
    Hid tspace = h5_take(H5Dget_space(w.time.get()), H5Sclose, w.part_path, "read the snapshots");
    Hid hspace = h5_take(H5Dget_space(w.h.get()), H5Sclose, w.part_path, "read the snapshots");
    hsize_t tdims[1] = {0}, hdims[3] = {0, 0, 0};
    if (H5Sget_simple_extent_ndims(tspace.get()) != 1 || H5Sget_simple_extent_ndims(hspace.get()) != 3)
        throw InputError(checkpoint_path, "the saved snapshots have the wrong rank");
    H5Sget_simple_extent_dims(tspace.get(), tdims, nullptr);
    H5Sget_simple_extent_dims(hspace.get(), hdims, nullptr);
    if (hdims[0] != tdims[0] || hdims[1] != static_cast<hsize_t>(w.grid.ny) ||
        hdims[2] != static_cast<hsize_t>(w.grid.nx))
        throw InputError(checkpoint_path, "the saved snapshots do not fit the grid of the run");
    for (const Hid* ds : {&w.h, &w.u, &w.v})
        if (!w.stored_as_written(*ds))
            throw InputError(checkpoint_path,
                             "the saved snapshots are not stored as this version writes them (chunks of 1 x " +
                                 std::to_string(w.chunk_dims()[1]) + " x " + std::to_string(w.chunk_dims()[2]) +
                                 " cells, shuffle then deflate)");
    w.snapshots = static_cast<std::size_t>(tdims[0]);
}

void ResultsWriter::finish(const RunStatistics& stats) {
    Impl& w = *impl_;
    const hid_t root = w.file.get();
    write_attribute(root, "end_reason", to_string(stats.end_reason), w.part_path);
    write_attribute(root, "simulated_time", stats.simulated_time, w.part_path);
    write_attribute(root, "steps", static_cast<std::int64_t>(stats.steps), w.part_path);
    write_attribute(root, "snapshots", static_cast<std::int64_t>(w.snapshots), w.part_path);
    w.time.reset();
    w.h.reset();
    w.u.reset();
    w.v.reset();
    h5_check(H5Fflush(root, H5F_SCOPE_GLOBAL), w.part_path, "flush the file");
    w.file.reset();
    std::error_code ec;
    std::filesystem::rename(w.part_path, final_path_, ec);
    if (ec)
        throw OutputError(final_path_,
                          "cannot move the finished results into place: " + ec.message());
}

}  // namespace avalanche
