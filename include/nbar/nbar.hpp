// nbar's front door: the few calls a C++ program needs to analyse a planar linkage or to design a
// four-bar, and the types they return. Link nbar::io and nbar::analysis (find_package(nbar)):
//
//   #include "nbar/nbar.hpp"
//
//   const nbar::io::LoadedModel file = nbar::io::load_model_file("fourbar.yaml");
//   const auto mechanism = std::make_shared<const nbar::Mechanism>(file.model);
//   nbar::AnalysisOptions options;
//   options.dynamics = true;
//   const nbar::Analysis analysis = nbar::analyse(mechanism, options);
//
// The main calls:
//
// - io::load_model_file(path), io::parse_model(text, name): read a model file (YAML,
//   docs/model-format.md) into a Model in SI units, validated, with a SourceMap of where each
//   entity was written. Keep the SourceMap to locate later errors in the file (io::located).
//   Throws io::ModelFileError ("file:line:column: message", kind InvalidModel).
//
// - Mechanism(model): compiles the model once into constraint rows and checks its mobility.
//   Immutable afterwards: share it (std::shared_ptr<const Mechanism>) between analyses and
//   threads. Throws ModelError (an Error of kind InvalidModel) for an invalid model or drivers
//   that do not match the degrees of freedom.
//
// - analyse(mechanism, options): the whole pipeline, stage by stage as the options ask: the sweep
//   (positions and time derivatives of every point), the inverse dynamics (joint forces, driver
//   efforts), the link stresses. The Analysis it returns keeps the mechanism and every stage's
//   results (see its fields for which stage fills what, in which units); result_table(analysis)
//   gives them as named columns in the model's units. Throws Error: CannotAssemble when the start
//   cannot be assembled, BadInput for options out of range, UndefinedLaw, InvalidModel (stresses
//   of a model without a shaped link), Cancelled (options.control). A sweep that stops at a limit
//   position is not an error: analysis.complete() is false and the samples solved are kept.
//
// - io::load_synthesis_task(path), synthesis::run_synthesis(task, options): design four-bars (five
//   coupler points, Burmester poses, function generation, path fitting; docs/synthesis.md); every
//   real design is checked with the kinematics engine and ranked. The outcome keeps the designs,
//   their checks and notes. Throws io::ModelFileError for a bad task file, Error (InvalidModel,
//   Cancelled) from the solvers.
//
// Every problem these calls report is an nbar::Error (model/diagnostics.hpp), with a kind() for
// programs and a what() for people.
#pragma once

#include "nbar/analysis/analysis.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/model.hpp"
#include "nbar/synthesis/run.hpp"
#include "nbar/version.hpp"
