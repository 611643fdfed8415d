// Reruns the verification studies of MODEL.md section 4 with more grid levels than
// the tests (both schemes, all four WAF limiters) and writes docs/verification.md:
// the method text (tools/verification_text.hpp) and tables of error norms and
// observed orders. Usage: verification_report [output.md] (default: stdout).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "support/analytic_chute.hpp"
#include "support/analytic_harness.hpp"
#include "support/analytic_rigid_block.hpp"
#include "support/analytic_studies.hpp"
#include "verification_text.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {

struct Variant {
    const char* name;
    Scheme scheme;
    Limiter limiter;
};
const std::vector<Variant> kVariants = {
    {"Godunov", Scheme::godunov, Limiter::van_leer},
    {"WAF van Leer (default)", Scheme::waf, Limiter::van_leer},
    {"WAF superbee", Scheme::waf, Limiter::superbee},
    {"WAF van Albada", Scheme::waf, Limiter::van_albada},
    {"WAF minmod", Scheme::waf, Limiter::minmod},
};

NumericsParams numerics(const Variant& v) {
    NumericsParams n;
    n.scheme = v.scheme;
    n.limiter = v.limiter;
    return n;
}

using study::fmt;
std::string order(double coarse, double fine) {
    return coarse > 0.0 && fine > 0.0 ? fmt("%.2f", observed_order(coarse, fine)) : "";
}

void dam_break_table(std::ostream& out, const DamBreakCase& c) {
    out << "\n#### " << c.name << "\n\n"
        << "| scheme | dx (m) | E1 | order | front lag (m) | rear offset (cells) | mass error |\n"
        << "|---|---|---|---|---|---|---|\n";
    for (const Variant& v : kVariants) {
        double prev = 0.0;
        for (double dx : {0.2, 0.1, 0.05, 0.025}) {
            const DamBreakResult r = run_dam_break(c, numerics(v), dx);
            out << "| " << v.name << " | " << dx << " | " << fmt("%.3e", r.l1_relative) << " | "
                << order(prev, r.l1_relative) << " | " << fmt("%.3f", r.front_exact - r.front)
                << " | " << fmt("%.1f", (r.rear - r.rear_exact) / dx) << " | "
                << fmt("%.1e", r.mass_error) << " |\n";
            prev = r.l1_relative;
        }
    }
}

void similarity_table(std::ostream& out, const SimilarityCase& c,
                      const std::vector<double>& levels) {
    out << "\n#### " << c.name << "\n\n"
        << "| scheme | dx (m) | E1 | order | x_c - exact (m) | L_x / exact - 1 | L_y / exact - 1 | "
           "mean u / exact - 1 |\n|---|---|---|---|---|---|---|---|\n";
    for (const Variant& v : kVariants) {
        double prev = 0.0;
        for (double dx : levels) {
            const SimilarityResult r = run_similarity(c, numerics(v), dx);
            out << "| " << v.name << " | " << dx << " | " << fmt("%.3e", r.l1_relative) << " | "
                << order(prev, r.l1_relative) << " | " << fmt("%.1e", r.x_c - r.x_c_exact) << " | "
                << fmt("%.2e", r.l_x / r.l_x_exact - 1.0) << " | "
                << (c.exact.two_d ? fmt("%.2e", r.l_y / r.l_y_exact - 1.0) : "") << " | "
                << fmt("%.1e", r.mean_u / r.mean_u_exact - 1.0) << " |\n";
            prev = r.l1_relative;
        }
    }
}

void smooth_table(std::ostream& out, const SmoothCase& c) {
    constexpr int kCoarse = 50, kLevels = 4, kRef = 8;
    out << "\n#### " << c.name << " (reference: WAF van Leer on "
        << kCoarse * (1 << (kLevels - 1)) * kRef
        << " cells)\n\n| scheme | nx = 50 | 100 | 200 | 400 | orders "
           "|\n|---|---|---|---|---|---|\n";
    for (const Variant& v : kVariants) {
        const std::vector<double> e = smooth_errors(c, numerics(v), kCoarse, kLevels, kRef);
        out << "| " << v.name;
        for (double x : e) out << " | " << fmt("%.3e", x);
        out << " |";
        for (std::size_t l = 1; l < e.size(); ++l) out << " " << order(e[l - 1], e[l]);
        out << " |\n";
    }
}

void rigid_block_table(std::ostream& out) {
    out << "\n| scheme | case | centroid acceleration (m/s^2) | exact | relative error | mean u "
           "relative "
           "error |\n|---|---|---|---|---|---|\n";
    for (const Variant& v : {kVariants[0], kVariants[1]}) {
        for (const SimilarityCase& c : {similarity_1d(EarthPressureModel::isotropic, true),
                                        similarity_1d(EarthPressureModel::savage_hutter)}) {
            const SimilarityResult r = run_similarity(c, numerics(v), 0.1);
            const double m =
                rigid_block_acceleration(c.exact.theta_rad, c.exact.delta_rad, c.exact.gravity);
            const double t = c.t_end, u = c.exact.u_c0 + m * t;
            const double a = 2.0 * (r.x_c - c.exact.x_c0 - c.exact.u_c0 * t) / (t * t);
            out << "| " << v.name << " | " << c.name << " | " << fmt("%.5f", a) << " | "
                << fmt("%.5f", m) << " | " << fmt("%.1e", (a - m) / m) << " | "
                << fmt("%.1e", (r.mean_u - u) / u) << " |\n";
        }
    }
}

void creep_table(std::ostream& out) {
    out << "\n| scheme | model | edge moved (m) | variance radius change (m) | max speed at 30 s "
           "(m/s) "
           "|\n|---|---|---|---|---|\n";
    for (const Variant& v : {kVariants[0], kVariants[1]}) {
        for (EarthPressureModel m :
             {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
            const CreepResult r = run_creep(numerics(v), m, 0.5, 30.0);
            out << "| " << v.name << " | "
                << (m == EarthPressureModel::isotropic ? "isotropic" : "Savage-Hutter") << " | "
                << fmt("%.2f", r.front_shift) << " | " << fmt("%.2f", r.radius_shift) << " | "
                << fmt("%.4f", r.max_speed) << " |\n";
        }
    }
    // The same pile with numerics.rest_faces, every scheme, model and splitting: the
    // largest of each measure (RestFaces.GentlePileStaysExactlyAtRest asserts zeros).
    double edge = 0.0, radius = 0.0, speed = 0.0;
    for (const Variant& v : {kVariants[0], kVariants[1]})
        for (EarthPressureModel m :
             {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
            for (Splitting sp : {Splitting::lsl, Splitting::sls}) {
                NumericsParams n = numerics(v);
                n.splitting = sp;
                n.rest_faces = true;
                const CreepResult r = run_creep(n, m, 0.5, 30.0);
                edge = std::max(edge, std::abs(r.front_shift));
                radius = std::max(radius, std::abs(r.radius_shift));
                speed = std::max(speed, r.max_speed);
            }
    out << "| either, `numerics.rest_faces` | either (L S L or S L S) | " << fmt("%g", edge)
        << " | " << fmt("%g", radius) << " | " << fmt("%g", speed) << " |\n";
}

void conservation_table(std::ostream& out) {
    out << "\n| scheme | terrain | edges | t (s) | steps | relative mass error | outflow (m^3) | "
           "released (m^3) | min h | mirror asymmetry "
           "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    struct Run {
        const char* terrain;
        double length, relief;
        Boundary boundary;
        double t_end;
    };
    const Run runs[] = {{"60 m chute, smooth", 60.0, 0.0, Boundary::open, 8.0},
                        {"30 m plane (outflow)", 30.0, 0.0, Boundary::open, 6.0},
                        {"60 m chute, bumps 0.3 m", 60.0, 0.3, Boundary::open, 8.0},
                        {"60 m chute, bumps 0.3 m", 60.0, 0.3, Boundary::wall, 8.0}};
    for (const Variant& v : {kVariants[0], kVariants[1]}) {
        for (const Run& r : runs) {
            const ChuteOutcome o =
                run_chute(v.scheme, r.boundary, 0.5, r.length, r.relief, r.t_end);
            out << "| " << v.name << " | " << r.terrain << " | "
                << (r.boundary == Boundary::open ? "open" : "wall") << " | "
                << fmt("%.2f", o.stats.simulated_time) << " | " << o.steps << " | "
                << fmt("%.1e", o.stats.relative_mass_error()) << " | "
                << fmt("%.4f", o.stats.outflow_volume) << " | "
                << fmt("%.4f", o.stats.released_volume) << " | " << fmt("%g", o.min_h) << " | "
                << fmt("%g", o.asymmetry) << " |\n";
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::ostringstream out;
    out << kIntroduction;
    std::cerr << "dam break...\n";
    out << kDamBreakText;
    for (const DamBreakCase& c :
         {dam_break_isotropic(), dam_break_balanced(), dam_break_savage_hutter()})
        dam_break_table(out, c);
    std::cerr << "similarity...\n";
    out << kSimilarityText;
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        similarity_table(out, similarity_1d(m), {0.2, 0.1, 0.05, 0.025});
    similarity_table(out, similarity_1d(EarthPressureModel::savage_hutter, true),
                     {0.2, 0.1, 0.05, 0.025});
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        similarity_table(out, similarity_2d(m), {0.5, 0.25, 0.125});
    std::cerr << "rigid block, creep...\n";
    out << kRigidBlockText;
    rigid_block_table(out);
    out << kCreepText;
    creep_table(out);
    out << kCreepRestFacesText;
    std::cerr << "conservation...\n";
    out << kConservationText;
    conservation_table(out);
    std::cerr << "convergence...\n";
    out << kConvergenceText;
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        smooth_table(out, smooth_hump(m));
    out << kFindingsText;

    if (argc > 1) {
        std::ofstream file(argv[1]);
        if (!file) {
            std::cerr << "verification_report: cannot write " << argv[1] << "\n";
            return 4;
        }
        file << out.str();
        std::cerr << "wrote " << argv[1] << "\n";
    } else {
        std::cout << out.str();
    }
    return 0;
}
