// Loads a model file, analyses it (the sweep, then the inverse dynamics of every sample) and
// prints the torque the first driver needs at a few of its positions.
//
//   analyse-model examples/fourbar-steel-bars.yaml
#include <cstdio>
#include <memory>

#include "nbar/nbar.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: analyse-model MODEL.yaml\n");
    return 2;
  }
  try {
    // The file gives a Model (SI units) and where each part of it was written, for messages.
    const nbar::io::LoadedModel file = nbar::io::load_model_file(argv[1]);
    // Compiled once; the analysis shares it.
    const auto mechanism = std::make_shared<const nbar::Mechanism>(file.model);

    nbar::AnalysisOptions options;
    options.steps = 13;       // 13 samples of the model's sweep, ends included
    options.dynamics = true;  // joint forces and driver efforts at every sample
    const nbar::Analysis analysis = nbar::analyse(mechanism, options);

    const nbar::Model& model = analysis.model();
    if (model.drivers.empty()) {
      std::fprintf(stderr, "the model has no driver\n");
      return 1;
    }
    const double to_unit = model.drivers[0].is_angular() ? model.units.angle_scale : model.units.length_scale;
    const char* unit = model.drivers[0].is_angular() ? model.units.angle.c_str() : model.units.length.c_str();
    std::printf("%s: effort of driver '%s'\n", model.name.c_str(), model.drivers[0].name.c_str());
    for (std::size_t i = 0; i < analysis.sweep.samples.size(); i += 3) {
      const nbar::Sample& sample = analysis.sweep.samples[i];
      const nbar::DynamicsResult& forces = analysis.dynamics->samples[i];
      std::printf("  %s = %8.3f %s: %10.4f %s\n", model.drivers[0].name.c_str(), sample.driver_values[0] / to_unit,
                  unit, forces.driver_effort[0], model.drivers[0].is_angular() ? "N m" : "N");
    }
    if (!analysis.complete()) std::printf("stopped early: %s\n", analysis.sweep.stop_reason.c_str());
  } catch (const nbar::Error& e) {  // every problem nbar reports, with its kind and place
    std::fprintf(stderr, "error (%s): %s\n", nbar::to_string(e.kind()), e.what());
    return 1;
  }
  return 0;
}
