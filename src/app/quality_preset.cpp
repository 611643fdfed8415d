#include "avalanche/app/quality_preset.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche {

// The values come from the Pareto study (docs/performance.md, "The speed/accuracy
// trade"): WAF/van Leer at Courant 0.4 is on the error/cost front at every cell size of
// all three problems (WAF's numerical diffusion falls as the Courant number rises), so
//   draft:    twice the cell size at Courant 0.4: about a tenth of the standard cost;
//   standard: the defaults (the paper's scheme, WAF/van Leer at Courant 0.2);
//   fine:     half the cell size at Courant 0.4: on the chute 13 % less deposit error
//             than standard for 2.8 times its cost (at Courant 0.2 it would cost six
//             times and be less accurate).
QualityPreset quality_preset(Quality q) {
    switch (q) {
        case Quality::draft: return {Scheme::waf, Limiter::van_leer, 0.4, 2.0};
        case Quality::standard: return {Scheme::waf, Limiter::van_leer, 0.2, 1.0};
        case Quality::fine: return {Scheme::waf, Limiter::van_leer, 0.4, 0.5};
    }
    return {};
}

Quality parse_quality(const std::string& text, const std::string& what) {
    if (text == "draft") return Quality::draft;
    if (text == "standard") return Quality::standard;
    if (text == "fine") return Quality::fine;
    throw ConfigError(what, "expected draft, standard or fine, got '" + text + "'");
}

std::string to_string(Quality q) {
    switch (q) {
        case Quality::draft: return "draft";
        case Quality::standard: return "standard";
        case Quality::fine: return "fine";
    }
    return "?";
}

}  // namespace avalanche
