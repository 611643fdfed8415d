// The speed/accuracy trade (issue "Speed against accuracy", part 4): the error and
// the cost (CPU time) of every numerical choice a user can make -- scheme, limiter, cell
// size (4 levels) and Courant number -- on three problems:
//   - the isotropic dam break (exact solution, tests/support),
//   - the 1D Savage-Hutter similarity solution (exact solution),
//   - the paper's parametric chute (scenarios/parametric_chute), against a reference
//     run on a finer grid.
// Writes the Pareto tables, the plots and the presets' stated error and cost into
// docs/performance.md (between the markers below) and docs/figures/pareto/*.svg.
// Usage: pareto_study [--doc docs/performance.md] [--figures docs/figures/pareto]
//                     [--chute-reference DX] [--quick]
// Runs on one thread and measures CPU time: the costs are comparable with each other
// (and robust to other work on a shared machine), not with multithreaded runs.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/quality_preset.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/enum_names.hpp"
#include "avalanche/io/scenario_file.hpp"
#include "avalanche/io/svg_plot.hpp"
#include "pareto_text.hpp"
#include "study_support.hpp"
#include "support/analytic_studies.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {

// ------------------------------------------------------------------ the choices
struct Variant {
    std::string name;
    Scheme scheme;
    Limiter limiter;
    double cfl;
    std::string legend;  // short, for the plots' legends
    Splitting splitting = Splitting::lsl;
};

// Godunov and the default WAF/van Leer at three Courant numbers; the other limiters at
// the default Courant number (the limiter changes the error, hardly the cost).
std::vector<Variant> variants() {
    std::vector<Variant> v;
    for (const char* c : {"0.1", "0.2", "0.4"}) {
        const double cfl = std::stod(c);
        v.push_back({std::string("Godunov C=") + c, Scheme::godunov, Limiter::van_leer, cfl,
                     std::string("Godunov ") + c});
        v.push_back({std::string("WAF van Leer C=") + c, Scheme::waf, Limiter::van_leer, cfl,
                     std::string("WAF vL ") + c});
    }
    v.push_back({"WAF superbee C=0.2", Scheme::waf, Limiter::superbee, 0.2, "superbee 0.2"});
    v.push_back({"WAF van Albada C=0.2", Scheme::waf, Limiter::van_albada, 0.2, "vAlbada 0.2"});
    v.push_back({"WAF minmod C=0.2", Scheme::waf, Limiter::minmod, 0.2, "minmod 0.2"});
    // The other splitting, S(dt/2) L(dt) S(dt/2): one advection per step instead of two.
    for (const char* c : {"0.2", "0.4"})
        v.push_back({std::string("WAF van Leer SLS C=") + c, Scheme::waf, Limiter::van_leer,
                     std::stod(c), std::string("WAF vL SLS ") + c, Splitting::sls});
    return v;
}

NumericsParams numerics_of(const Variant& v) {
    NumericsParams n;
    n.scheme = v.scheme;
    n.limiter = v.limiter;
    n.cfl = v.cfl;
    n.splitting = v.splitting;
    return n;
}

struct Sample {
    std::string problem, variant, legend;
    double dx = 0.0;
    double error = 0.0;      // relative L1 depth error (see the problem)
    double secondary = 0.0;  // front / runout error (m)
    double cpu = 0.0;        // s CPU, one thread
    bool pareto = false;
};

// CPU time (one thread): on the shared machine the wall time includes other work.
double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

template <class F>
double timed(F&& f) {
    const double t0 = cpu_seconds();
    f();
    return cpu_seconds() - t0;
}

// ------------------------------------------------------------------ the chute
struct ChuteRun {
    Grid grid;
    std::vector<double> deposit;  // final depth, interior cells, row-major j * nx + i
    double runout = 0.0;          // largest x (along the bed) of a cell deeper than 1 cm
    double volume = 0.0;
    double cpu = 0.0;  // s CPU
};

Scenario chute_scenario(const std::string& source_dir, double dx, const NumericsParams& n) {
    Scenario s = load_scenario(source_dir + "/scenarios/parametric_chute/scenario.toml");
    s.cell_size = dx;
    s.numerics.scheme = n.scheme;
    s.numerics.limiter = n.limiter;
    s.numerics.cfl = n.cfl;
    s.numerics.splitting = n.splitting;
    return s;
}

ChuteRun run_chute(const std::string& source_dir, double dx, const NumericsParams& n) {
    const Scenario s = chute_scenario(source_dir, dx, n);
    const PreparedScene scene = prepare_scene(s);
    const double h_min = effective_h_min(s.numerics, scene.initial, scene.terrain);
    Simulation sim(scene.grid, scene.terrain, s.material, s.numerics, scene.initial, h_min);
    ChuteRun r{scene.grid, {}, 0.0, 0.0, 0.0};
    r.cpu = timed([&] { sim.run(); });
    const Grid& g = scene.grid;
    r.deposit.resize(static_cast<std::size_t>(g.nx) * g.ny);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double h = sim.state().h(i, j);
            r.deposit[static_cast<std::size_t>(j) * g.nx + i] = h;
            r.volume += h * g.dx * g.dy;
            if (h > 0.01) r.runout = std::max(r.runout, g.x_center(i));
        }
    return r;
}

// Relative L1 distance between a coarse deposit and the reference averaged onto its
// cells (the grids share their origin; the factor is an integer).
double deposit_error(const ChuteRun& coarse, const ChuteRun& ref) {
    const int f = static_cast<int>(std::lround(coarse.grid.dx / ref.grid.dx));
    if (f < 1 || coarse.grid.nx * f != ref.grid.nx || coarse.grid.ny * f != ref.grid.ny)
        throw std::runtime_error("chute reference grid is not a refinement of the level");
    double sum = 0.0;
    for (int j = 0; j < coarse.grid.ny; ++j)
        for (int i = 0; i < coarse.grid.nx; ++i) {
            double avg = 0.0;
            for (int b = 0; b < f; ++b)
                for (int a = 0; a < f; ++a)
                    avg += ref.deposit[static_cast<std::size_t>(j * f + b) * ref.grid.nx + (i * f + a)];
            avg /= f * f;
            sum += std::abs(coarse.deposit[static_cast<std::size_t>(j) * coarse.grid.nx + i] - avg);
        }
    return sum * coarse.grid.dx * coarse.grid.dy / ref.volume;
}

// ------------------------------------------------------------------ Pareto front
// A sample is Pareto-optimal when no other sample of its problem is both faster and
// more accurate (ties count as not dominated).
void mark_pareto(std::vector<Sample>& samples) {
    for (Sample& a : samples) {
        a.pareto = true;
        for (const Sample& b : samples)
            if (&a != &b && b.problem == a.problem && b.cpu <= a.cpu && b.error <= a.error &&
                (b.cpu < a.cpu || b.error < a.error)) {
                a.pareto = false;
                break;
            }
    }
}

using study::fmt;

void write_table(std::ostream& out, const std::vector<Sample>& samples, const std::string& problem,
                 const std::string& secondary_name) {
    std::vector<const Sample*> rows;
    for (const Sample& s : samples)
        if (s.problem == problem) rows.push_back(&s);
    std::sort(rows.begin(), rows.end(), [](const Sample* a, const Sample* b) { return a->cpu < b->cpu; });
    out << "| choice | dx (m) | relative L1 error | " << secondary_name << " | CPU (s) | Pareto |\n"
        << "|---|---|---|---|---|---|\n";
    for (const Sample* s : rows)
        out << "| " << s->variant << " | " << fmt("%g", s->dx) << " | " << fmt("%.3e", s->error) << " | "
            << fmt("%.3g", s->secondary) << " | " << fmt("%.3g", s->cpu) << " | " << (s->pareto ? "**yes**" : "")
            << " |\n";
}

void write_plot(const std::filesystem::path& file, const std::vector<Sample>& samples, const std::string& problem,
                const std::string& title) {
    LinePlot plot{title, "log10 CPU time (s, one thread)", "log10 relative L1 error", {}};
    std::vector<std::string> names;
    for (const Sample& s : samples)
        if (s.problem == problem && std::find(names.begin(), names.end(), s.variant) == names.end())
            names.push_back(s.variant);
    for (const std::string& name : names) {
        PlotSeries series{"", {}, {}};
        for (const Sample& s : samples)
            if (s.problem == problem && s.variant == name && s.cpu > 0.0 && s.error > 0.0) {
                series.label = s.legend;
                series.x.push_back(std::log10(s.cpu));
                series.y.push_back(std::log10(s.error));
            }
        plot.series.push_back(std::move(series));
    }
    std::ofstream(file) << svg_line_plot(plot);
}

}  // namespace

int main(int argc, char** argv) {
    std::string doc = std::string(AVALANCHE_SOURCE_DIR) + "/docs/performance.md";
    std::string figures = std::string(AVALANCHE_SOURCE_DIR) + "/docs/figures/pareto";
    double chute_ref = 0.0625;  // 4x finer than the finest level (0.25 m)
    bool quick = false;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--doc" && k + 1 < argc) doc = argv[++k];
        else if (a == "--figures" && k + 1 < argc) figures = argv[++k];
        else if (a == "--chute-reference" && k + 1 < argc) chute_ref = std::stod(argv[++k]);
        else if (a == "--quick") quick = true;
        else {
            std::cerr << "usage: pareto_study [--doc FILE] [--figures DIR] [--chute-reference DX] [--quick]\n";
            return 2;
        }
    }
    omp_set_num_threads(1);
    std::filesystem::create_directories(figures);
    const std::string src = AVALANCHE_SOURCE_DIR;
    const std::vector<Variant> vs = variants();
    std::vector<Sample> samples;
    const auto t_study = std::chrono::steady_clock::now();

    // Dam break and similarity: four levels each, halving dx.
    const std::vector<double> line_levels = quick ? std::vector<double>{0.2, 0.1} : std::vector<double>{0.2, 0.1, 0.05, 0.025};
    const DamBreakCase dam = dam_break_isotropic();
    const SimilarityCase sim1 = similarity_1d(EarthPressureModel::savage_hutter);
    for (const Variant& v : vs)
        for (double dx : line_levels) {
            const DamBreakResult d = run_dam_break(dam, numerics_of(v), dx);
            const double wd = d.solver_seconds;
            samples.push_back({"dam_break", v.name, v.legend, dx, d.l1_relative, std::abs(d.front - d.front_exact), wd});
            const SimilarityResult r = run_similarity(sim1, numerics_of(v), dx);
            const double ws = r.solver_seconds;
            samples.push_back({"similarity", v.name, v.legend, dx, r.l1_relative, std::abs(r.l_x - r.l_x_exact), ws});
            std::cerr << v.name << " dx " << dx << ": dam " << d.l1_relative << " (" << wd << " s), similarity "
                      << r.l1_relative << " (" << ws << " s)\n";
        }

    // The chute: a reference on chute_ref, four levels from 2 m to 0.25 m.
    const std::vector<double> chute_levels = quick ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.5, 0.25};
    NumericsParams ref_numerics;  // WAF, van Leer, C = 0.2: the default scheme
    const ChuteRun ref = run_chute(src, quick ? 0.25 : chute_ref, ref_numerics);
    std::cerr << "chute reference dx " << ref.grid.dx << ": runout " << ref.runout << " m, " << ref.cpu << " s\n";
    for (const Variant& v : vs)
        for (double dx : chute_levels) {
            const ChuteRun r = run_chute(src, dx, numerics_of(v));
            samples.push_back({"chute", v.name, v.legend, dx, deposit_error(r, ref), std::abs(r.runout - ref.runout), r.cpu});
            std::cerr << v.name << " chute dx " << dx << ": " << samples.back().error << ", runout "
                      << r.runout << " (" << r.cpu << " s)\n";
        }
    mark_pareto(samples);
    const double study_wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_study).count();

    write_plot(std::filesystem::path(figures) / "dam_break.svg", samples, "dam_break",
               "Dam break (isotropic): error against CPU time");
    write_plot(std::filesystem::path(figures) / "similarity.svg", samples, "similarity",
               "Similarity solution (1D, Savage-Hutter): error against CPU time");
    write_plot(std::filesystem::path(figures) / "chute.svg", samples, "chute",
               "Parametric chute deposit: error against CPU time");

    std::ostringstream body;
    body << pareto_text::kIntro << "\nChute reference: WAF/van Leer, C = 0.2, dx = " << fmt("%g", ref.grid.dx)
         << " m (runout " << fmt("%.2f", ref.runout) << " m, " << fmt("%.0f", ref.cpu)
         << " s). Whole study: " << fmt("%.0f", study_wall) << " s wall time on one thread.\n";
    const char* problems[][3] = {{"dam_break", "Dam break (isotropic, exact solution)", "front error (m)"},
                                 {"similarity", "Similarity solution (1D, Savage-Hutter, exact)", "length error (m)"},
                                 {"chute", "Parametric chute (deposit against the reference)", "runout error (m)"}};
    for (const auto& p : problems) {
        body << "\n#### " << p[1] << "\n\n![" << p[1] << "](figures/pareto/" << p[0] << ".svg)\n\n";
        write_table(body, samples, p[0], p[2]);
    }
    body << "\n#### The presets on the chute\n\n"
         << "| preset | scheme | limiter | splitting | Courant | cell size | relative L1 error | runout error (m) | CPU (s) | cost vs standard |\n"
         << "|---|---|---|---|---|---|---|---|---|---|\n";
    // The presets' own figures on the chute, from their definitions (quality_preset.hpp):
    // the scenario's 0.2 m cell scaled by the preset's factor would leave the study's
    // levels; the presets are therefore stated at the study's 0.5 m base.
    const double preset_base = quick ? 1.0 : 0.5;
    double standard_cpu = 0.0;
    struct Row { std::string name; QualityPreset q; ChuteRun r; double err; };
    std::vector<Row> rows;
    for (Quality q : {Quality::draft, Quality::standard, Quality::fine}) {
        const QualityPreset p = quality_preset(q);
        NumericsParams n;
        apply_preset_numerics(p, n);
        const double dx = preset_base * p.cell_size_factor;
        ChuteRun r = run_chute(src, dx, n);
        const double err = deposit_error(r, ref);
        if (q == Quality::standard) standard_cpu = r.cpu;
        rows.push_back({to_string(q), p, std::move(r), err});
    }
    for (const Row& row : rows)
        body << "| " << row.name << " | " << (row.q.scheme == Scheme::waf ? "WAF" : "Godunov") << " | "
             << enum_name(kLimiterNames, row.q.limiter) << " | "
             << (row.q.splitting == Splitting::lsl ? "L S L" : "S L S") << " | " << fmt("%g", row.q.cfl) << " | " << fmt("%g", row.q.cell_size_factor)
             << " x base (" << fmt("%g", row.r.grid.dx) << " m) | " << fmt("%.3e", row.err) << " | "
             << fmt("%.3g", std::abs(row.r.runout - ref.runout)) << " | " << fmt("%.3g", row.r.cpu) << " | "
             << fmt("%.2f", row.r.cpu / standard_cpu) << " |\n";
    body << pareto_text::kPresetsNote;
    write_file_atomically(
        doc, study::with_block_replaced(study::read_text(doc), "pareto-study", body.str()));
    std::cerr << "wrote " << doc << " and " << figures << " in " << study_wall << " s\n";
    return 0;
}
