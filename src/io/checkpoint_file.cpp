// HDF5 side of checkpoints: plain datasets and attributes, no chunking or filters, so a
// checkpoint is fast to write and every value reads back bit for bit.
#include "avalanche/io/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "avalanche/core/error.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "hdf5_handles.hpp"

namespace avalanche {

using detail::h5_check;
using detail::h5_take;
using detail::Hid;
using detail::write_attribute;

namespace {

constexpr const char* kFormat = "avalanche-hazard checkpoint";
constexpr std::int64_t kFormatVersion = 3;  // 2: the solver regime; 3: source_hash (2026-12-02)

// ---------------------------------------------------------------- writing

// Dataset `name` (intermediate groups created) of `dims` elements of `file_type`.
void write_dataset(hid_t file, const std::string& name, hid_t file_type, hid_t mem_type,
                   const std::vector<hsize_t>& dims, const void* data, const std::string& path) {
    const std::string what = "write the dataset " + name;
    Hid space = h5_take(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                        H5Sclose, path, what);
    Hid lcpl = h5_take(H5Pcreate(H5P_LINK_CREATE), H5Pclose, path, what);
    h5_check(H5Pset_create_intermediate_group(lcpl.get(), 1), path, what);
    Hid ds = h5_take(H5Dcreate2(file, name.c_str(), file_type, space.get(), lcpl.get(), H5P_DEFAULT,
                                H5P_DEFAULT),
                     H5Dclose, path, what);
    if (dims.empty() || dims[0] > 0)
        h5_check(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), path, what);
}

void write_reals(hid_t file, const std::string& name, const std::vector<double>& v,
                 const std::string& path) {
    write_dataset(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {v.size()}, v.data(), path);
}

void write_field(hid_t file, const std::string& name, const Field2D& f, const std::string& path) {
    // Ghosts included, without the rows' padding (Field2D::packed).
    const auto rows = static_cast<hsize_t>(f.ny() + 2 * f.ghosts());
    const auto cols = static_cast<hsize_t>(f.nx() + 2 * f.ghosts());
    const std::vector<double> cells = f.packed();
    write_dataset(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {rows, cols}, cells.data(), path);
}

void write_info(hid_t root, const CheckpointInfo& info, const Grid& grid, const std::string& kind,
                const std::string& path) {
    write_attribute(root, "format", std::string(kFormat), path);
    write_attribute(root, "format_version", kFormatVersion, path);
    write_attribute(root, "kind", kind, path);
    write_attribute(root, "software_version", software_version(), path);
    write_attribute(root, "source_hash", source_hash(), path);
    write_attribute(root, "config_json", info.config.dump(), path);
    write_attribute(root, "config_hash", info.config_hash, path);
    write_attribute(root, "working_dir", info.working_dir, path);
    write_attribute(root, "scene_fingerprint", info.scene_fingerprint, path);
    write_attribute(root, "checkpoint_interval", info.checkpoint_interval, path);
    write_attribute(root, "threads", static_cast<std::int64_t>(info.threads), path);
    write_attribute(root, "nx", static_cast<std::int64_t>(grid.nx), path);
    write_attribute(root, "ny", static_cast<std::int64_t>(grid.ny), path);
    write_attribute(root, "ghosts", static_cast<std::int64_t>(kGhostLayers), path);
}

// Loop state as attributes of /loop: doubles are stored as IEEE binary64, so they
// come back bit for bit.
void write_loop(hid_t file, const LoopState& L, const std::string& path) {
    Hid g = h5_take(H5Gcreate2(file, "loop", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, path,
                    "create the group loop");
    const hid_t l = g.get();
    write_attribute(l, "t", L.t, path);
    write_attribute(l, "steps", static_cast<std::int64_t>(L.steps), path);
    write_attribute(l, "outputs_done", static_cast<std::int64_t>(L.outputs_done), path);
    write_attribute(l, "next_output", L.next_output, path);
    write_attribute(l, "last_output_t", L.last_output_t, path);
    write_attribute(l, "ke_max", L.ke_max, path);
    write_attribute(l, "quiet_since", L.quiet_since, path);
    write_attribute(l, "released_volume", L.released_volume, path);
    write_attribute(l, "outflow_volume", L.outflow_volume, path);
    write_attribute(l, "cell_updates", static_cast<std::int64_t>(L.cell_updates), path);
    write_attribute(l, "next_checkpoint", L.next_checkpoint, path);
    write_attribute(l, "energy_budget", L.energy_budget, path);
}

void write_observers(hid_t file, const CheckpointData& data, const std::string& path) {
    for (const auto& [name, v] : data.reals) write_reals(file, "observers/" + name, v, path);
    for (const auto& [name, v] : data.integers)
        write_dataset(file, "observers/" + name, H5T_STD_I64LE, H5T_NATIVE_INT64, {v.size()},
                      v.data(), path);
}

void fsync_path(const std::string& p, bool directory) {
    const int fd = ::open(p.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
    if (fd < 0) return;  // best effort for the folder; the file was just written by us
    ::fsync(fd);
    ::close(fd);
}

// tmp -> fsync -> rename -> fsync(folder).
void move_into_place(const std::string& tmp, const std::string& path) {
    fsync_path(tmp, false);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw OutputError(path, "cannot move the checkpoint into place: " + ec.message());
    }
    const auto folder = std::filesystem::path(path).parent_path();
    fsync_path(folder.empty() ? "." : folder.string(), true);
}

template <class Body>
void write_file(const std::string& path, Body&& body) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const std::string tmp = path + ".tmp";
    try {
        Hid file = h5_take(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                           H5Fclose, tmp, "create the checkpoint");
        body(file.get(), tmp);
        h5_check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), tmp, "flush the checkpoint");
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    }
}

// ---------------------------------------------------------------- reading

class Reader {
  public:
    explicit Reader(std::string path) : path_(std::move(path)) {}

    [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, what); }

    Hid open_attr(hid_t loc, const std::string& name) const {
        if (H5Aexists(loc, name.c_str()) <= 0)
            fail("not a complete checkpoint: attribute " + name + " is missing");
        const hid_t a = H5Aopen(loc, name.c_str(), H5P_DEFAULT);
        if (a < 0) fail("cannot read the attribute " + name);
        return Hid(a, H5Aclose);
    }
    double real(hid_t loc, const std::string& name) const {
        Hid a = open_attr(loc, name);
        double v = 0.0;
        if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0) fail("cannot read the attribute " + name);
        return v;
    }
    std::int64_t integer(hid_t loc, const std::string& name) const {
        Hid a = open_attr(loc, name);
        std::int64_t v = 0;
        if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) < 0) fail("cannot read the attribute " + name);
        return v;
    }
    std::string text(hid_t loc, const std::string& name) const {
        Hid a = open_attr(loc, name);
        Hid type = h5_take(H5Aget_type(a.get()), H5Tclose, path_, "read the attribute " + name);
        if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0)
            fail("attribute " + name + " is not a string");
        char* ptr = nullptr;
        if (H5Aread(a.get(), type.get(), &ptr) < 0 || ptr == nullptr)
            fail("cannot read the attribute " + name);
        std::string out(ptr);
        Hid space = h5_take(H5Aget_space(a.get()), H5Sclose, path_, "read the attribute " + name);
        H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &ptr);
        return out;
    }

    // The dataset `name` as doubles or int64 (element count checked against `expected`
    // unless negative).
    template <class T>
    std::vector<T> dataset(hid_t file, const std::string& name, long long expected = -1) const {
        if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
            fail("not a complete checkpoint: " + name + " is missing");
        const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
        if (d < 0) fail("cannot open the dataset " + name);
        Hid ds(d, H5Dclose);
        Hid space = h5_take(H5Dget_space(ds.get()), H5Sclose, path_, "read " + name);
        const hssize_t n = H5Sget_simple_extent_npoints(space.get());
        if (n < 0 || (expected >= 0 && n != expected))
            fail("dataset " + name + " has " + std::to_string(n) + " values, expected " +
                 std::to_string(expected));
        std::vector<T> out(static_cast<std::size_t>(n));
        const hid_t mem = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
        if (n > 0 && H5Dread(ds.get(), mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
            fail("cannot read the dataset " + name + " (truncated file?)");
        return out;
    }

  private:
    std::string path_;
};

struct VisitContext {
    std::vector<std::string> names;
};

herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* ctx) {
    if (info->type == H5O_TYPE_DATASET) static_cast<VisitContext*>(ctx)->names.emplace_back(name);
    return 0;
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointInfo& info,
                      const SimulationCheckpoint& c, const Grid& grid,
                      const ResultsWriter* results) {
    write_file(path, [&](hid_t file, const std::string& tmp) {
        write_info(file, info, grid, "checkpoint", tmp);
        write_loop(file, c.loop, tmp);
        write_field(file, "state/h", c.state.h, tmp);
        write_field(file, "state/hu", c.state.hu, tmp);
        write_field(file, "state/hv", c.state.hv, tmp);
        write_observers(file, c.observers, tmp);
        if (results) results->copy_snapshots_to(file, tmp);
    });
    move_into_place(path + ".tmp", path);
}

void write_diagnostic_checkpoint(const std::string& path, const CheckpointInfo& info,
                                 const FaultReport& f, const Grid& grid) {
    write_file(path, [&](hid_t file, const std::string& tmp) {
        write_info(file, info, grid, "diagnostic", tmp);
        write_attribute(file, "fault", f.what, tmp);
        write_loop(file, f.last_good_loop, tmp);
        write_field(file, "state/h", f.last_good.h, tmp);
        write_field(file, "state/hu", f.last_good.hu, tmp);
        write_field(file, "state/hv", f.last_good.hv, tmp);
        write_field(file, "failing_state/h", f.failing.h, tmp);
        write_field(file, "failing_state/hu", f.failing.hu, tmp);
        write_field(file, "failing_state/hv", f.failing.hv, tmp);
    });
    move_into_place(path + ".tmp", path);
}

CheckpointContents read_checkpoint(const std::string& path) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    Reader r(path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        r.fail(
            "no checkpoint to resume from (a run writes one with --checkpoint-interval or when "
            "interrupted)");
    if (H5Fis_hdf5(path.c_str()) <= 0) r.fail("not a readable HDF5 checkpoint (corrupt?)");
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) r.fail("not a readable HDF5 checkpoint (corrupt?)");
    Hid file(f, H5Fclose);
    const hid_t root = file.get();

    CheckpointContents c;
    c.path = path;
    if (r.text(root, "format") != kFormat) r.fail("not an avalanche-hazard checkpoint");
    if (r.integer(root, "format_version") != kFormatVersion)
        r.fail("checkpoint format version " + std::to_string(r.integer(root, "format_version")) +
               " is not supported (expected " + std::to_string(kFormatVersion) + ")");
    if (r.text(root, "kind") != "checkpoint")
        r.fail("is a diagnostic checkpoint, which cannot be resumed");
    CheckpointInfo& info = c.info;
    try {
        info.config = nlohmann::json::parse(r.text(root, "config_json"));
    } catch (const nlohmann::json::exception&) {
        r.fail("attribute config_json is not valid JSON");
    }
    info.config_hash = r.text(root, "config_hash");
    info.working_dir = r.text(root, "working_dir");
    info.scene_fingerprint = r.text(root, "scene_fingerprint");
    info.checkpoint_interval = r.real(root, "checkpoint_interval");
    info.threads = static_cast<int>(r.integer(root, "threads"));
    info.software_version = r.text(root, "software_version");
    info.source_hash = r.text(root, "source_hash");
    c.nx = static_cast<int>(r.integer(root, "nx"));
    c.ny = static_cast<int>(r.integer(root, "ny"));
    c.ghosts = static_cast<int>(r.integer(root, "ghosts"));
    if (c.nx <= 0 || c.ny <= 0 || c.ghosts != kGhostLayers)
        r.fail("grid attributes nx, ny, ghosts are invalid");

    if (H5Lexists(root, "loop", H5P_DEFAULT) <= 0)
        r.fail("not a complete checkpoint: group loop is missing");
    Hid loop = h5_take(H5Gopen2(root, "loop", H5P_DEFAULT), H5Gclose, path, "open the group loop");
    const hid_t l = loop.get();
    LoopState& L = c.loop;
    L.t = r.real(l, "t");
    L.steps = static_cast<std::uint64_t>(r.integer(l, "steps"));
    L.outputs_done = static_cast<std::uint64_t>(r.integer(l, "outputs_done"));
    L.next_output = r.real(l, "next_output");
    L.last_output_t = r.real(l, "last_output_t");
    L.ke_max = r.real(l, "ke_max");
    L.quiet_since = r.real(l, "quiet_since");
    L.released_volume = r.real(l, "released_volume");
    L.outflow_volume = r.real(l, "outflow_volume");
    L.cell_updates = static_cast<std::uint64_t>(r.integer(l, "cell_updates"));
    L.next_checkpoint = r.real(l, "next_checkpoint");
    L.energy_budget = r.real(l, "energy_budget");

    const long long n = static_cast<long long>(c.nx + 2 * c.ghosts) * (c.ny + 2 * c.ghosts);
    c.h = r.dataset<double>(root, "state/h", n);
    c.hu = r.dataset<double>(root, "state/hu", n);
    c.hv = r.dataset<double>(root, "state/hv", n);

    if (H5Lexists(root, "observers", H5P_DEFAULT) > 0) {
        Hid group = h5_take(H5Gopen2(root, "observers", H5P_DEFAULT), H5Gclose, path,
                            "open the group observers");
        VisitContext ctx;
        if (H5Ovisit2(group.get(), H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &ctx,
                      H5O_INFO_BASIC) < 0)
            r.fail("cannot list the group observers");
        for (const std::string& name : ctx.names) {
            const std::string full = "observers/" + name;
            Hid ds =
                h5_take(H5Dopen2(root, full.c_str(), H5P_DEFAULT), H5Dclose, path, "open " + full);
            Hid type = h5_take(H5Dget_type(ds.get()), H5Tclose, path, "read " + full);
            if (H5Tget_class(type.get()) == H5T_INTEGER)
                c.observers.integers[name] = r.dataset<std::int64_t>(root, full);
            else
                c.observers.reals[name] = r.dataset<double>(root, full);
        }
    }
    return c;
}

}  // namespace avalanche
