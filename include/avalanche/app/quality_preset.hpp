#pragma once
// `--quality draft|standard|fine`: the speed/accuracy presets of docs/performance.md
// ("The speed/accuracy trade"). Each is a point chosen from the Pareto study
// (tools/pareto_study.cpp), which states its error and cost on the paper's chute.
// A preset sets the scheme, the limiter, the Courant number, the splitting and scales
// the scene's cell size (the scenario's numerics.cell_size, or the DEM's resolution
// when that is automatic); flags given explicitly (--scheme, --limiter, --cfl,
// --cell-size) win.
#include <string>

#include "avalanche/numerics/parameters.hpp"

namespace avalanche {

enum class Quality { draft, standard, fine };

struct QualityPreset {
    Scheme scheme = Scheme::waf;
    Limiter limiter = Limiter::van_leer;
    double cfl = 0.2;
    double cell_size_factor = 1.0;  // x the scene's cell size
    Splitting splitting = Splitting::lsl;
};

QualityPreset quality_preset(Quality q);
// Sets the preset's numerical choices in n: scheme, limiter, Courant number, splitting.
// The cell size is the caller's to scale (a scenario's, or a study's level).
void apply_preset_numerics(const QualityPreset& p, NumericsParams& n);
// "draft" | "standard" | "fine"; throws ConfigError naming `what` otherwise.
Quality parse_quality(const std::string& text, const std::string& what);
std::string to_string(Quality q);

}  // namespace avalanche
