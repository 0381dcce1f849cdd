#include "nbar/request/outline_request.hpp"

#include <fmt/format.h>

#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar::request {

namespace {

std::array<double, 4> guide_line(const Model& m, const std::array<int, 2>& along) {
  const double k = m.units.length_scale;
  const Eigen::Vector2d& a = m.points[along[0]].position;
  const Eigen::Vector2d& b = m.points[along[1]].position;
  return {a.x() / k, a.y() / k, b.x() / k, b.y() / k};
}

void read_geometry(const Model& m, Outline& out) {
  const double k = m.units.length_scale;
  for (const Point& p : m.points)
    if (!p.guide_direction) out.points.push_back({p.name, p.position.x() / k, p.position.y() / k, p.ground});
  for (const Body& b : m.bodies) {
    OutlineBody body{b.name, {}};
    for (int p : b.points) body.points.push_back(m.points[p].name);
    out.bodies.push_back(std::move(body));
  }
  for (const Slider& s : m.sliders)
    out.guides.push_back({"slider", m.bodies[s.body].name, m.points[s.point].name, guide_line(m, s.along)});
  for (const Slot& s : m.slots) out.guides.push_back({"slot", "", m.points[s.point].name, guide_line(m, s.along)});
}

// A model whose joints leave no freedom is no mechanism: said with the counts that show it.
std::string immobility(const Outline& out) {
  if (out.mobility) {
    if (out.mobility->dof > 0) return "";
    return fmt::format(
        "the joints leave no freedom: 0 degrees of freedom (Gruebler-Kutzbach count {}), so nothing "
        "can move",
        out.count.dof);
  }
  if (out.bodies.empty() || out.count.dof > 0) return "";
  return fmt::format("the joints leave no freedom: the Gruebler-Kutzbach count is {}, so nothing can move",
                     out.count.dof);
}

}  // namespace

Outline outline_model(const std::string& text, const std::string& file_name) {
  const io::DraftModel draft = io::parse_draft_model(text, file_name);
  const Model& m = draft.loaded.model;
  Outline out;
  out.name = m.name;
  out.units = m.units;
  out.drivers = static_cast<int>(m.drivers.size());
  read_geometry(m, out);
  out.joints = joint_descriptions(m);
  out.count = count_pairs(m);
  if (draft.problem) {
    out.problem = draft.problem->message();
    out.problem_at = draft.problem->mark();
  } else {
    const auto located = [&](const ModelError& e) {
      out.problem = e.message();
      out.problem_at = draft.loaded.source.find(e.where());
    };
    try {
      out.mobility = Mechanism::joint_mobility(m);
      Mechanism checked(m);  // the drivers' verdict: their number, their independence
    } catch (const ModelError& e) {
      located(e);
    }
  }
  out.immobile = immobility(out);
  return out;
}

}  // namespace nbar::request
