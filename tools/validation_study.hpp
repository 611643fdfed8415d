#pragma once
// The validation study of docs/validation.md, in three parts (one file each):
//   validation_parametric.cpp  Wang & Li (2017) section 2.3: Figs. 2-5 and the paper's claims
//   validation_koch.cpp        Koch et al. (1994) laboratory chute: front/tail table
//   validation_field.cpp       a rock avalanche on real terrain (Fluchthorn): batch sweep,
//                              and a twin experiment of batch calibration (--observed)
// validation_study.cpp runs them and assembles the Markdown; the prose lives in
// validation_text.hpp.
#include <string>

#include "paper_chute.hpp"
#include "study_support.hpp"

namespace avalanche::validation {

struct StudyOptions {
    std::string source_dir;        // the repository (scenarios/, docs/)
    std::string work_dir;          // scratch folder for the field batch
    double chute_cell = 0.0;       // m, parametric chute; 0 = the scenario's (0.5 m)
    double koch_cell = 0.0;        // m, laboratory chute; 0 = the scenario's (1 cm)
    bool field = true;             // run part 3
    [[nodiscard]] std::string figures_dir() const { return source_dir + "/docs/figures/validation"; }
};

// Loads a shipped chute scenario (scenarios/<name>/scenario.toml) as a ChuteCase;
// cell_size > 0 overrides the file's.
ChuteCase chute_case_from_scenario(const std::string& path, double cell_size);

// Each part runs its cases, writes its figures into figures_dir() and returns its
// Markdown section.
std::string parametric_section(const StudyOptions& o);
std::string koch_section(const StudyOptions& o);
std::string field_section(const StudyOptions& o);

// Formatting helpers shared by the parts.
using study::fmt;
void write_svg(const StudyOptions& o, const std::string& name, const std::string& svg);

}  // namespace avalanche::validation
