#include "avalanche/numerics/cell_rows.hpp"

#include <algorithm>
#include <cmath>

#include "simd_clones.hpp"

namespace avalanche {

namespace {

// One sub-step of gravity and friction on the velocity (u, v) of a cell; returns
// the true speed^2 after it.
template <bool Curvature, bool Metric>
AVALANCHE_INLINE double gravity_friction(double& u, double& v, const SourceRowTerrain& t, int i,
                                         double sub, double td) {
    u += sub * t.ax[i];
    v += sub * t.ay[i];
    double load = t.gn[i];
    if constexpr (Curvature) load += t.cxx[i] * u * u + 2.0 * t.cxy[i] * u * v + t.cyy[i] * v * v;
    load = std::max(load, 0.0);  // material lifting off feels no friction
    double speed2 = u * u + v * v;
    if constexpr (Metric) {
        const double w = t.sx[i] * u + t.sy[i] * v;
        speed2 += w * w;
    }
    const double speed = std::sqrt(speed2);
    const double f = td * load * sub;
    const bool stops = speed <= f;
    const double scale = 1.0 - f / speed;  // discarded when the cell stops
    u = stops ? 0.0 : u * scale;
    v = stops ? 0.0 : v * scale;
    return stops ? 0.0 : (speed - f) * (speed - f);
}

// OneSubstep: the common m = 1 as straight-line code (GCC does not vectorise a
// loop around the sub-step loop).
template <bool Curvature, bool Metric, bool OneSubstep>
AVALANCHE_INLINE void sources_row(double* __restrict h, double* __restrict hu,
                                  double* __restrict hv, const SourceRowTerrain& t,
                                  const SourceRowParams& p, int i0, int i1) {
    const double sub = p.substep, td = p.tan_delta, g = p.gravity, budget = p.energy_budget;
    const int m = p.substeps;
    const double* __restrict elev = t.elevation;
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const double hh = h[i];
        const bool wet = hh > 0.0;
        double u = hu[i] / hh, v = hv[i] / hh;  // discarded on dry cells
        double after2 = 0.0;                    // true speed^2 after the last sub-step
        if constexpr (OneSubstep) {
            after2 = gravity_friction<Curvature, Metric>(u, v, t, i, sub, td);
        } else {
            for (int n = 0; n < m; ++n)
                after2 = gravity_friction<Curvature, Metric>(u, v, t, i, sub, td);
        }
        // The energy cap (cap_speed in stepper.cpp): scale down to the cap, stop
        // above the reachable height.
        const double cap2 = 2.0 * (budget - g * elev[i]);
        const double cap_scale = std::sqrt(cap2 / after2);
        const bool over = !(after2 <= cap2);
        const double uc = over ? (cap2 <= 0.0 ? 0.0 : u * cap_scale) : u;
        const double vc = over ? (cap2 <= 0.0 ? 0.0 : v * cap_scale) : v;
        hu[i] = wet ? hh * uc : hu[i];
        hv[i] = wet ? hh * vc : hv[i];
    }
}

template <bool Curvature, bool Metric>
AVALANCHE_SIMD_CLONES void sources_row_clone(double* h, double* hu, double* hv,
                                             const SourceRowTerrain& t, const SourceRowParams& p,
                                             int i0, int i1) {
    if (p.substeps == 1)
        sources_row<Curvature, Metric, true>(h, hu, hv, t, p, i0, i1);
    else
        sources_row<Curvature, Metric, false>(h, hu, hv, t, p, i0, i1);
}

AVALANCHE_SIMD_CLONES double cfl_rate_clone(const double* __restrict h, const double* __restrict hu,
                                            const double* __restrict hv,
                                            const double* __restrict px,
                                            const double* __restrict py, double kx, double ky,
                                            double dx, double dy, double h_min, int i0, int i1) {
    double rate = 0.0;
#pragma omp simd reduction(max : rate)
    for (int i = i0; i < i1; ++i) {
        const double hh = h[i];
        const double u = hu[i] / hh, v = hv[i] / hh;
        const double rx = (std::abs(u) + std::sqrt(kx * px[i] * hh)) / dx;
        const double ry = (std::abs(v) + std::sqrt(ky * py[i] * hh)) / dy;
        const double r = std::max(rx, ry);
        // max is exact, so the order of the lanes does not change the result.
        rate = (hh < h_min) | (hh <= 0.0) ? rate : std::max(rate, r);
    }
    return rate;
}

}  // namespace

void apply_sources_row(double* h, double* hu, double* hv, const SourceRowTerrain& t,
                       const SourceRowParams& p, int i0, int i1) noexcept {
    const bool curvature = t.cxx != nullptr, metric = t.sx != nullptr;
    if (curvature && metric)
        sources_row_clone<true, true>(h, hu, hv, t, p, i0, i1);
    else if (curvature)
        sources_row_clone<true, false>(h, hu, hv, t, p, i0, i1);
    else if (metric)
        sources_row_clone<false, true>(h, hu, hv, t, p, i0, i1);
    else
        sources_row_clone<false, false>(h, hu, hv, t, p, i0, i1);
}

double cfl_rate_row(const double* h, const double* hu, const double* hv, const double* px,
                    const double* py, double kx, double ky, double dx, double dy, double h_min,
                    int i0, int i1) noexcept {
    return cfl_rate_clone(h, hu, hv, px, py, kx, ky, dx, dy, h_min, i0, i1);
}

}  // namespace avalanche
