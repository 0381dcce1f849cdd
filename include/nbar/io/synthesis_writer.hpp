// Writing synthesis outcomes: the ranked table for a terminal, the JSON the CLI and the web
// server give, the designs as model files, and the Burmester curves as CSV, JSON or SVG.
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "nbar/synthesis/run.hpp"

namespace nbar::io {

// Where the designs are exported (empty: not exported); shown in the table and the JSON.
struct SynthesisListing {
  std::vector<int> shown;  // shown_rows(): the rows listed, best first
  bool all = false;        // --all: defective and complex designs are listed too
  std::string export_dir;
};

void write_synthesis_table(std::ostream& out, const synthesis::SynthesisTask& task,
                           const synthesis::SynthesisOutcome& outcome, const SynthesisListing& listing);
// The JSON document (indented by 2), with a final newline.
std::string synthesis_json(const synthesis::SynthesisTask& task, const synthesis::SynthesisOutcome& outcome,
                           const SynthesisListing& listing);

// The model file of outcome.rows[row], listed at `rank` (1 = best): what export_designs writes
// for it. Throws Error(BadInput) for a complex or invalid design.
std::string design_model_yaml(const synthesis::SynthesisTask& task, const synthesis::SynthesisOutcome& outcome, int row,
                              int rank);
// The files export_designs writes, as (file name, model text): the real, valid designs listed,
// in rank order.
std::vector<std::pair<std::string, std::string>> design_files(const synthesis::SynthesisTask& task,
                                                              const synthesis::SynthesisOutcome& outcome,
                                                              const SynthesisListing& listing);
// DIR/design-01.yaml... for the real designs listed, in rank order. Throws Error(BadInput)
// naming the folder or file that cannot be written.
void export_designs(const synthesis::SynthesisTask& task, const synthesis::SynthesisOutcome& outcome,
                    const SynthesisListing& listing);

// The Burmester curves to `path`: .json, .svg, or CSV otherwise. Throws Error(BadInput) when
// the file cannot be written.
void write_burmester_curves(const std::string& path, const synthesis::SynthesisTask& task,
                            const synthesis::BurmesterCurves& curves);

// "design-01.yaml" for rank 1.
std::string design_file_name(int rank);

}  // namespace nbar::io
