#include "avalanche/app/quality_preset.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche {

// The values come from the Pareto study (docs/performance.md, "The speed/accuracy
// trade"): WAF/van Leer at Courant 0.4 with the splitting S(dt/2) L(dt) S(dt/2) (one
// advection per step instead of two) is on the error/cost front at every cell size of
// all three problems, and beats L S L at Courant 0.4 on the similarity solution and the
// chute (WAF's numerical diffusion falls as the Courant number of an advection rises), so
//   draft:    twice the cell size at Courant 0.4, S L S: well under a tenth of the
//             standard cost for 1.2 times its deposit error on the chute;
//   standard: the defaults (the paper's scheme, WAF/van Leer, L S L at Courant 0.2);
//   fine:     half the cell size at Courant 0.4, S L S: on the chute 0.6 times the
//             deposit error of standard for 1.5-2 times its cost (L S L at Courant 0.4:
//             0.8 times the error for 2.3-3.5 times the cost).
QualityPreset quality_preset(Quality q) {
    switch (q) {
        case Quality::draft: return {Scheme::waf, Limiter::van_leer, 0.4, 2.0, Splitting::sls};
        case Quality::standard: return {Scheme::waf, Limiter::van_leer, 0.2, 1.0, Splitting::lsl};
        case Quality::fine: return {Scheme::waf, Limiter::van_leer, 0.4, 0.5, Splitting::sls};
    }
    return {};
}

void apply_preset_numerics(const QualityPreset& p, NumericsParams& n) {
    n.scheme = p.scheme;
    n.limiter = p.limiter;
    n.cfl = p.cfl;
    n.splitting = p.splitting;
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
