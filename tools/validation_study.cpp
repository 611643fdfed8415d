// Reruns the validation study of docs/validation.md (issue 7): Wang & Li (2017)'s
// parametric study on the shipped chute scenarios, the Koch et al. (1994) laboratory
// chute, and a rock avalanche on real terrain (Fluchthorn), then writes the Markdown and
// the figures in docs/figures/validation/.
//
// Usage: validation_study SOURCE_DIR [--work DIR] [--chute-cell M] [--koch-cell M] [--no-field]
//   SOURCE_DIR  the repository (reads scenarios/, writes docs/validation.md and figures)
//   --work DIR  scratch folder of the field batch and the twin runs (default:
//               SOURCE_DIR/../validation-work); rerunning resumes the batch (complete
//               scenarios are not recomputed) and reuses twin runs of the same parameters
// `cmake --build <build> --target validation-report` runs it on the source tree.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/scenario_file.hpp"
#include "validation_study.hpp"
#include "validation_text.hpp"

namespace avalanche::validation {

void write_svg(const StudyOptions& o, const std::string& name, const std::string& svg) {
    std::filesystem::create_directories(o.figures_dir());
    write_file_atomically(o.figures_dir() + "/" + name, svg);
}

ChuteCase chute_case_from_scenario(const std::string& path, double cell_size) {
    const Scenario s = load_scenario(path);
    const auto* geometry = std::get_if<ChuteGeometry>(&s.terrain);
    const auto* shape = std::get_if<ReleaseShape>(&s.release);
    const CapRelease* cap = shape ? std::get_if<CapRelease>(shape) : nullptr;
    if (!geometry || !cap) throw InputError(path, "expected a chute scenario with a cap release");
    ChuteCase c;
    c.geometry = *geometry;
    c.cap = *cap;
    c.material = s.material;
    c.numerics = s.numerics;
    c.cell_size = cell_size > 0.0 ? cell_size : s.cell_size;
    c.front_threshold = s.output.h_threshold;
    return c;
}

}  // namespace avalanche::validation

int main(int argc, char** argv) {
    using namespace avalanche;
    using namespace avalanche::validation;
    StudyOptions o;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        auto value = [&]() -> std::string {
            if (k + 1 >= argc) throw ConfigError(a, "expects a value");
            return argv[++k];
        };
        if (a == "--work") o.work_dir = value();
        else if (a == "--chute-cell") o.chute_cell = std::stod(value());
        else if (a == "--koch-cell") o.koch_cell = std::stod(value());
        else if (a == "--no-field") o.field = false;
        else if (o.source_dir.empty() && a.rfind("--", 0) != 0) o.source_dir = a;
        else {
            std::cerr << "validation_study: unknown argument " << a
                      << "\nusage: validation_study SOURCE_DIR [--work DIR] [--chute-cell M] "
                         "[--koch-cell M] [--no-field]\n";
            return 2;
        }
    }
    if (o.source_dir.empty()) {
        std::cerr << "usage: validation_study SOURCE_DIR [--work DIR] [--chute-cell M] "
                     "[--koch-cell M] [--no-field]\n";
        return 2;
    }
    if (o.work_dir.empty()) o.work_dir = o.source_dir + "/../validation-work";
    // One thread: the machine is shared, and the wall times in the report are per core.
    // The field batch sizes its workers from OMP_NUM_THREADS (docs/batch.md), so set both.
    setenv("OMP_NUM_THREADS", "1", 1);
    omp_set_num_threads(1);
    try {
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        std::ostringstream md;
        md << kValidationIntro;
        md << parametric_section(o);
        md << koch_section(o);
        if (o.field) md << field_section(o);
        else md << "\n## 3. Field scale\n\n(Not run: `--no-field`.)\n";
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
        md << "\n---\nWhole study: " << fmt("%.0f", cpu) << " s of CPU time on one thread ("
           << fmt("%.0f", wall)
           << " s of wall time on a 2-core machine shared with other jobs; resumed field "
              "scenarios are not rerun).\n";
        const std::string path = o.source_dir + "/docs/validation.md";
        write_file_atomically(path, md.str());
        std::cerr << "wrote " << path << " and " << o.figures_dir() << "/ in "
                  << fmt("%.0f", wall) << " s\n";
    } catch (const Error& e) {
        std::cerr << "validation_study: " << e.what() << "\n";
        return static_cast<int>(e.code());
    } catch (const std::exception& e) {  // e.g. std::stod on a malformed number
        std::cerr << "validation_study: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
