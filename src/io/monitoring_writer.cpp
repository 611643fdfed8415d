#include "avalanche/io/monitoring_writer.hpp"

#include <filesystem>
#include <iomanip>
#include <sstream>
#include <vector>

#include "avalanche/core/error.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/csv_text.hpp"
#include "hdf5_handles.hpp"

namespace avalanche {

using detail::h5_check;
using detail::h5_take;
using detail::Hid;
using detail::write_attribute;

void write_monitoring_csv(const std::string& path, const MonitoringPoints& points) {
    std::ostringstream out;
    out << "point,x,y,t_s,h_m,u_ms,v_ms,speed_ms,pressure_kpa\n" << std::setprecision(10);
    for (std::size_t p = 0; p < points.points().size(); ++p) {
        const ProbeLocation& loc = points.points()[p];
        for (const ProbeSample& s : points.series()[p])
            out << csv_field(loc.name) << ',' << loc.x << ',' << loc.y << ',' << s.t << ',' << s.h
                << ',' << s.u << ',' << s.v << ',' << s.speed << ',' << s.pressure << '\n';
    }
    write_file_atomically(path, out.str());
}

namespace {
void write_series(hid_t group, const std::string& name, const std::vector<double>& values, const std::string& units,
                  const std::string& file) {
    const hsize_t n = values.size();
    Hid space = h5_take(H5Screate_simple(1, &n, nullptr), H5Sclose, file, "create a dataspace");
    Hid set = h5_take(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                 H5P_DEFAULT),
                      H5Dclose, file, "create dataset " + name);
    if (n > 0)
        h5_check(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), file,
                 "write dataset " + name);
    write_attribute(set.get(), "units", units, file);
}
}  // namespace

void write_monitoring_hdf5(const std::string& path, const MonitoringPoints& points) {
    const std::string part = path + ".part";
    {
        Hid file = h5_take(H5Fcreate(part.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, path,
                           "create the file");
        write_attribute(file.get(), "thickness", std::string("bed-normal"), path);
        for (std::size_t p = 0; p < points.points().size(); ++p) {
            const ProbeLocation& loc = points.points()[p];
            Hid group = h5_take(H5Gcreate2(file.get(), loc.name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                H5Gclose, path, "create group " + loc.name);
            write_attribute(group.get(), "x", loc.x, path);
            write_attribute(group.get(), "y", loc.y, path);
            const auto& series = points.series()[p];
            std::vector<double> t, h, u, v, speed, pressure;
            for (const ProbeSample& s : series) {
                t.push_back(s.t);
                h.push_back(s.h);
                u.push_back(s.u);
                v.push_back(s.v);
                speed.push_back(s.speed);
                pressure.push_back(s.pressure);
            }
            write_series(group.get(), "t", t, "s", path);
            write_series(group.get(), "h", h, "m", path);
            write_series(group.get(), "u", u, "m/s", path);
            write_series(group.get(), "v", v, "m/s", path);
            write_series(group.get(), "speed", speed, "m/s", path);
            write_series(group.get(), "pressure", pressure, "kPa", path);
        }
        // The data reach the disk here, not in the writes above: a full disk shows up as
        // a failed flush, and the file must then not be renamed to its final name (the
        // closer's own status is not checked).
        h5_check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), path, "write the file (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) throw OutputError(path, "could not rename the finished file: " + ec.message());
}

}  // namespace avalanche
