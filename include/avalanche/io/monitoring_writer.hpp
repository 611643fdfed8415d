#pragma once
// Monitoring-point time series (MODEL.md 5): DIR/monitoring.csv, one row per point and
// sample, and DIR/monitoring.h5, one group per point with 1-D datasets. Both written
// atomically (temporary name, then rename). Units in docs/io.md.
#include <string>

#include "avalanche/output/monitoring.hpp"

namespace avalanche {

// Columns: point,x,y,t_s,h_m,u_ms,v_ms,speed_ms,pressure_kpa (h bed-normal); the point's
// name quoted per RFC 4180 when it holds ',', '"', CR or LF (csv_text.hpp).
void write_monitoring_csv(const std::string& path, const MonitoringPoints& points);

// /<point name>/{t, h, u, v, speed, pressure} with attributes x, y, units.
void write_monitoring_hdf5(const std::string& path, const MonitoringPoints& points);

}  // namespace avalanche
