#include "avalanche/app/quality_preset.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche {

// The values come from the Pareto study (docs/performance.md, "The speed/accuracy
// trade") and the presets on the field scene (the section after it): WAF/van Leer with
// the splitting S(dt/2) L(dt) S(dt/2) (one advection per step instead of two) is on the
// error/cost front at every cell size of all three problems of the study, and beats
// L S L at Courant 0.4 on the similarity solution and the chute (WAF's numerical
// diffusion falls as the Courant number of an advection rises), so
//   draft:    twice the cell size at Courant 0.4, S L S: well under a tenth of the
//             standard cost for 1.2 times its deposit error on the chute;
//   standard: the defaults (the paper's scheme, WAF/van Leer, L S L at Courant 0.2);
//   fine:     half the cell size at Courant 0.2, S L S: on the chute 0.7 times the
//             deposit error of standard for about 2.7 times its cost, on the field scene
//             0.5 times for about 3 times. Courant 0.4 was cheaper (1.5-1.9 times the
//             cost) and better on the chute (0.6 times), but where the cells are a
//             quarter to half of a deposit's depth (a rock avalanche on 10 m cells) one
//             advection at Courant 0.4 kept the deposit moving cell against cell (2.2 m/s
//             against 0.33 m/s in the reference) and its deposit map was 0.19 from the
//             reference against 0.12 (tests/regression/test_field_deposit.cpp). The fine
//             preset is the check a map is defended with: it must not depend on how deep
//             the deposit is against its cells.
QualityPreset quality_preset(Quality q) {
    switch (q) {
        case Quality::draft: return {Scheme::waf, Limiter::van_leer, 0.4, 2.0, Splitting::sls};
        case Quality::standard: return {Scheme::waf, Limiter::van_leer, 0.2, 1.0, Splitting::lsl};
        case Quality::fine: return {Scheme::waf, Limiter::van_leer, 0.2, 0.5, Splitting::sls};
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
