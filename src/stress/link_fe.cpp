#include "nbar/stress/link_fe.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>

#include "model/plane_vectors.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

// The rotation of a body since its starting pose, as (cos, sin).
Eigen::Vector2d body_rotation(const BodyMotion& bm) {
  const double scale = bm.drawn_direction.norm() * bm.direction[0].norm();
  if (scale == 0.0) return {1.0, 0.0};
  return Eigen::Vector2d(bm.drawn_direction.dot(bm.direction[0]), cross(bm.drawn_direction, bm.direction[0])) / scale;
}
// World vector into the plate's frame (rotated back) and out of it.
Eigen::Vector2d unrotate(const Eigen::Vector2d& rot, const Eigen::Vector2d& v) {
  return {rot.x() * v.x() + rot.y() * v.y(), -rot.y() * v.x() + rot.x() * v.y()};
}
Eigen::Vector2d rotate(const Eigen::Vector2d& rot, const Eigen::Vector2d& v) {
  return {rot.x() * v.x() - rot.y() * v.y(), rot.y() * v.x() + rot.x() * v.y()};
}

std::string body_name(const Model& m, int body) { return "body '" + m.bodies[body].name + "'"; }

[[noreturn]] void fail_at_body(int body, const std::string& message) {
  throw Error(ErrorKind::InvalidModel, message, EntityRef{EntityRef::Kind::Body, body});
}

[[noreturn]] void fail_plate(const Model& m, int body, const Error& e) {
  fail_at_body(body, "the plate of " + body_name(m, body) + " cannot be analysed by finite elements: " + e.what());
}

fe::ElasticMaterial elastic_material(const Model& m, int body, const MassProperties& mass) {
  const Body& b = m.bodies[body];
  if (!b.material || !b.material->youngs_modulus || !b.material->poisson_ratio) {
    const std::string what = !b.material ? body_name(m, body) + " has no material"
                             : b.material->name.empty()
                                 ? "the material of " + body_name(m, body)
                                 : "material '" + b.material->name + "' of " + body_name(m, body);
    fail_at_body(body, what + (b.material ? " has no " : ", so no ") +
                           (b.material && b.material->youngs_modulus ? "" : "Young's modulus (`youngs_modulus`) and ") +
                           "Poisson's ratio (`poisson_ratio`), which finite-element stresses need; give them in the "
                           "material, or use a built-in material");
  }
  fe::ElasticMaterial e;
  e.youngs_modulus = *b.material->youngs_modulus;
  e.poisson_ratio = *b.material->poisson_ratio;
  e.thickness = b.thickness;
  // The body's mass (given or from its material) spread evenly over its plate, as the beam
  // model spreads it, so that the d'Alembert forces balance the dynamics' pin forces.
  const double area = area_properties(*b.shape).area;
  e.density = area > 0.0 ? mass.mass / (area * b.thickness) : 0.0;
  return e;
}

double default_mesh_size(const Region& r) { return fe::automatic_mesh_size(r); }

bool in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 double tolerance) {
  const double area = cross(b - a, c - a);
  if (area == 0.0) return false;
  const double u = cross(b - p, c - p) / area, v = cross(c - p, a - p) / area, w = cross(a - p, b - p) / area;
  return u >= -tolerance && v >= -tolerance && w >= -tolerance;
}

// Spreads couple `moment` over `patch` as forces perpendicular to each node's arm from the
// patch's centre, proportional to the arm (a rigid patch twisted): they add to no force and to
// exactly `moment`.
// Nodal forces, so that the solver need not look for the element of each.
void add_patch_couple(const fe::TriMesh& mesh, const std::vector<int>& patch, double moment, fe::LoadCase& loads) {
  if (patch.empty()) return;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int n : patch) centre += mesh.nodes[n];
  centre /= static_cast<double>(patch.size());
  double arms = 0.0;
  for (int n : patch) arms += (mesh.nodes[n] - centre).squaredNorm();
  if (arms <= 0.0) return;
  for (int n : patch) loads.nodal.push_back({n, moment / arms * perp(mesh.nodes[n] - centre)});
}

constexpr int kPatchNodes = 8;

}  // namespace

struct LinkFe::Link {
  int body = -1;
  Region region;
  fe::PlateModel plate;
  double mesh_size = 0.0;
  double tolerance = 0.0;                 // for matching points, m
  std::vector<int> interior_corners;      // corner nodes off the boundary
  std::vector<PlatePlacement> at_points;  // one per point of the body, in its order
  Link(int b, Region r, fe::PlateModel p, double size)
      : body(b), region(std::move(r)), plate(std::move(p)), mesh_size(size) {}

  PlatePlacement place(const Eigen::Vector2d& x) const {
    PlatePlacement out;
    out.at = x;
    for (std::size_t h = 0; h < region.circle_holes.size(); ++h)
      if ((x - region.circle_holes[h].centre).norm() < region.circle_holes[h].radius) out.hole = static_cast<int>(h);
    if (out.hole >= 0) return out;
    const fe::TriMesh& mesh = plate.mesh();
    out.inside = false;
    for (const auto& t : mesh.triangles)
      if (in_triangle(x, mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], 1e-9)) {
        out.inside = true;
        break;
      }
    std::vector<std::pair<double, int>> by_distance;
    by_distance.reserve(interior_corners.size());
    for (int n : interior_corners) by_distance.push_back({(mesh.nodes[n] - x).squaredNorm(), n});
    const std::size_t keep = std::min<std::size_t>(kPatchNodes, by_distance.size());
    std::partial_sort(by_distance.begin(), by_distance.begin() + static_cast<std::ptrdiff_t>(keep), by_distance.end());
    for (std::size_t k = 0; k < keep; ++k) out.patch.push_back(by_distance[k].second);
    if (!out.patch.empty()) out.node = out.patch.front();
    return out;
  }
};

LinkFe::LinkFe(std::shared_ptr<const InverseDynamics> dynamics, const FeOptions& options, const RunControl& control)
    : dynamics_(std::move(dynamics)), options_(options) {
  const Model& m = dynamics_->mechanism().model();
  if (!(options.mesh_size >= 0.0) || !std::isfinite(options.mesh_size))
    throw Error(ErrorKind::BadInput, "the mesh size must be a positive length (or 0 for the default)");
  if (!(options.refinement >= 1.0) || !std::isfinite(options.refinement))
    throw Error(ErrorKind::BadInput, "the mesh refinement must be a finite number >= 1");
  links_.resize(m.bodies.size());
  const auto mesh_options_of = [&](const Body& body) {
    fe::MeshOptions mesh_options;
    mesh_options.size =
        (options.mesh_size > 0.0 ? options.mesh_size : default_mesh_size(*body.shape)) / options.refinement;
    mesh_options.max_nodes = options.max_nodes;
    mesh_options.segments_per_hole = options.segments_per_hole;
    mesh_options.edge_size = options.edge_size / options.refinement;
    return mesh_options;
  };
  // Every plate's size is checked before any is meshed: a size too fine for the last plate
  // was refused only after the others had been meshed (54 s and 2 GB for the steel four-bar).
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (!body.shape || body.thickness <= 0.0) continue;
    try {
      fe::check_mesh_budget(*body.shape, mesh_options_of(body));
    } catch (const Error& e) {
      fail_plate(m, static_cast<int>(b), e);
    }
  }
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (!body.shape || body.thickness <= 0.0) continue;
    control.checkpoint("mesh", static_cast<long>(b), static_cast<long>(m.bodies.size()));
    const int index = static_cast<int>(b);
    const fe::ElasticMaterial material = elastic_material(m, index, dynamics_->masses()[b]);
    const fe::MeshOptions mesh_options = mesh_options_of(body);
    std::unique_ptr<Link> link;
    try {
      link = std::make_unique<Link>(
          index, *body.shape, fe::PlateModel(fe::mesh_region(*body.shape, mesh_options), material), mesh_options.size);
    } catch (const Error& e) {
      fail_plate(m, index, e);
    }
    const fe::TriMesh& mesh = link->plate.mesh();
    std::vector<bool> on_boundary(mesh.nodes.size(), false);
    for (const fe::BoundaryEdge& e : mesh.boundary)
      for (int n : e.nodes) on_boundary[n] = true;
    for (int n = 0; n < mesh.corner_count; ++n)
      if (!on_boundary[n]) link->interior_corners.push_back(n);
    link->tolerance = 1e-6 * default_mesh_size(*body.shape);
    for (int p : body.points) link->at_points.push_back(link->place(m.points[p].position));
    links_[b] = std::move(link);
  }
}

LinkFe::~LinkFe() = default;

bool LinkFe::analysed(int body) const {
  return body >= 0 && body < static_cast<int>(links_.size()) && links_[body] != nullptr;
}

const fe::PlateModel& LinkFe::plate(int body) const {
  if (!analysed(body)) throw Error(ErrorKind::BadInput, "body " + std::to_string(body) + " has no plate model");
  return links_[body]->plate;
}

double LinkFe::mesh_size(int body) const { return analysed(body) ? links_[body]->mesh_size : 0.0; }

Eigen::Vector2d LinkFe::to_plate(const DynamicsResult& forces, int body, const Eigen::Vector2d& world) const {
  const BodyMotion bm = body_motion(dynamics_->mechanism().model(), forces.motion, body);
  return bm.drawn_origin + unrotate(body_rotation(bm), world - bm.origin[0]);
}

Eigen::Vector2d LinkFe::to_world(const DynamicsResult& forces, int body, const Eigen::Vector2d& plate_point) const {
  const BodyMotion bm = body_motion(dynamics_->mechanism().model(), forces.motion, body);
  return bm.origin[0] + rotate(body_rotation(bm), plate_point - bm.drawn_origin);
}

const PlatePlacement& LinkFe::placement(const Link& link, const Eigen::Vector2d& at, PlatePlacement& scratch) const {
  const Model& m = dynamics_->mechanism().model();
  const Body& body = m.bodies[link.body];
  for (std::size_t k = 0; k < body.points.size(); ++k)
    if ((m.points[body.points[k]].position - at).norm() <= link.tolerance) return link.at_points[k];
  scratch = link.place(at);
  return scratch;
}

fe::LoadCase LinkFe::load_case(const DynamicsResult& forces, int body) const {
  if (!analysed(body)) throw Error(ErrorKind::BadInput, "body " + std::to_string(body) + " has no plate model");
  const Link& link = *links_[body];
  const Model& m = dynamics_->mechanism().model();
  const BodyMotion bm = body_motion(m, forces.motion, body);
  const Eigen::Vector2d rot = body_rotation(bm);
  const auto plate_point = [&](const Eigen::Vector2d& world) {
    return Eigen::Vector2d(bm.drawn_origin + unrotate(rot, world - bm.origin[0]));
  };

  fe::LoadCase loads;
  // Per hole, in hole order so that the load case does not depend on the order of the loads.
  std::map<int, Eigen::Vector2d> hole_force;
  std::map<int, double> hole_couple;
  PlatePlacement scratch;
  const auto add = [&](const Eigen::Vector2d& at_world, const Eigen::Vector2d& force_world, double couple) {
    const PlatePlacement& place = placement(link, plate_point(at_world), scratch);
    const Eigen::Vector2d force = unrotate(rot, force_world);
    if (place.hole >= 0) {
      hole_force.try_emplace(place.hole, Eigen::Vector2d::Zero()).first->second += force;
      hole_couple[place.hole] += couple;
      return;
    }
    if (!force.isZero(0.0)) {
      if (place.inside) {
        loads.forces.push_back({place.at, force});
      } else if (place.node >= 0) {
        const Eigen::Vector2d& node = link.plate.mesh().nodes[place.node];
        loads.nodal.push_back({place.node, force});
        couple += cross(place.at - node, force);  // carried rigidly to the node
      }
    }
    if (couple != 0.0) add_patch_couple(link.plate.mesh(), place.patch, couple, loads);
  };
  const auto& joint_links = dynamics_->joint_links();
  for (std::size_t i = 0; i < joint_links.size(); ++i)
    if (joint_links[i].link == body) add(forces.motion.r[joint_links[i].point], forces.pin_forces[i], 0.0);
  for (const AppliedLoad& l : forces.applied)
    if (l.body == body) add(l.at, l.force, l.couple);
  for (const auto& [hole, force] : hole_force)
    if (!force.isZero(0.0)) loads.bearings.push_back({hole, force});
  for (const auto& [hole, moment] : hole_couple)
    if (moment != 0.0) loads.couples.push_back({hole, moment});

  if (link.plate.material().density > 0.0) {
    fe::RigidBodyField field;
    field.origin = bm.drawn_origin;
    field.origin_acceleration = unrotate(rot, bm.origin[2]);
    field.omega = bm.omega;
    field.alpha = bm.alpha;
    field.gravity = unrotate(rot, m.gravity);
    loads.body = field;
  }
  return loads;
}

fe::StressField LinkFe::solve(const DynamicsResult& forces, int body) const {
  return plate(body).solve(load_case(forces, body));
}

Eigen::Vector2d body_frame_point(const Model& m, int body, const Eigen::Vector2d& drawn) {
  const BodyFrame f = body_frame(m, body);
  const Eigen::Vector2d origin = m.points[f.origin].position;
  Eigen::Vector2d axis(1, 0);
  if (f.from >= 0 && f.to >= 0 && m.points[f.to].position != m.points[f.from].position)
    axis = (m.points[f.to].position - m.points[f.from].position).normalized();
  const Eigen::Vector2d d = drawn - origin;
  return {axis.dot(d), cross(axis, d)};
}

LoadResultant load_resultant(const fe::LoadCase& loads, const Region& plate, const fe::ElasticMaterial& material,
                             const fe::TriMesh& mesh) {
  LoadResultant out;
  for (const fe::NodalForce& f : loads.nodal) {
    out.force += f.force;
    out.moment += cross(mesh.nodes.at(f.node), f.force);
  }
  for (const fe::BearingLoad& b : loads.bearings) {
    // A bearing pressure is radial, so its resultant passes through the hole's centre.
    const Eigen::Vector2d& centre = plate.circle_holes.at(b.hole).centre;
    out.force += b.force;
    out.moment += cross(centre, b.force);
  }
  for (const fe::HoleCouple& c : loads.couples) out.moment += c.moment;
  for (const fe::PointForce& f : loads.forces) {
    out.force += f.force;
    out.moment += cross(f.at, f.force);
  }
  if (loads.body) {
    const fe::RigidBodyField& b = *loads.body;
    const AreaProperties a = area_properties(plate);
    const double mass = material.density * material.thickness * a.area;
    const Eigen::Vector2d arm = a.centroid - b.origin;
    const Eigen::Vector2d force =
        mass * (b.gravity - b.origin_acceleration - b.alpha * perp(arm) + b.omega * b.omega * arm);
    out.force += force;
    // About the centroid the field's moment is that of the angular acceleration alone.
    out.moment += cross(a.centroid, force) - b.alpha * material.density * material.thickness * a.polar();
  }
  return out;
}

namespace {

// The peaks one worker saw over its share of the samples.
struct PartialPeaks {
  std::vector<FePeak> peaks;
};

bool worse(double vm, int step, const FePeak& than) {
  if (than.step < 0) return true;
  if (!std::isfinite(vm)) return std::isfinite(than.von_mises) || step < than.step;
  if (!std::isfinite(than.von_mises)) return false;
  return vm > than.von_mises || (vm == than.von_mises && step < than.step);
}

void merge_peak(FePeak& into, const FePeak& from) {
  if (from.step >= 0 && worse(from.von_mises, from.step, into)) {
    into.step = from.step;
    into.von_mises = from.von_mises;
    into.at = from.at;
    into.node = from.node;
  }
  into.load_unbalance = std::max(into.load_unbalance, from.load_unbalance);
  into.support_reaction = std::max(into.support_reaction, from.support_reaction);
}

}  // namespace

namespace {

// Each peak on a hole's edge gets the arc around it within kFlatPeak: one more solve per link, at
// the peak's step.
void add_flat_arcs(const LinkFe& fe, const SweepResult& sweep, const std::vector<DynamicsResult>& per_sample,
                   std::vector<FePeak>& peaks) {
  const std::size_t samples = std::min(sweep.samples.size(), per_sample.size());
  for (FePeak& peak : peaks) {
    if (peak.node < 0) continue;
    for (std::size_t i = 0; i < samples; ++i)
      if (sweep.samples[i].step == peak.step) {
        peak.flat = fe::flat_arc_at_hole(fe.plate(peak.body), fe.solve(per_sample[i], peak.body), peak.node, kFlatPeak);
        break;
      }
  }
}

}  // namespace

std::vector<FePeak> fe_peaks(const LinkFe& fe, const SweepResult& sweep, const std::vector<DynamicsResult>& per_sample,
                             const RunControl& control) {
  const Model& m = fe.dynamics().mechanism().model();
  std::vector<FePeak> peaks;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (!fe.analysed(static_cast<int>(b))) continue;
    FePeak p;
    p.body = static_cast<int>(b);
    const fe::TriMesh& mesh = fe.plate(p.body).mesh();
    p.nodes = static_cast<int>(mesh.nodes.size());
    p.elements = static_cast<int>(mesh.triangles.size());
    p.mesh_size = fe.mesh_size(p.body);
    p.min_angle_deg = fe::mesh_quality(mesh).min_angle_deg;
    peaks.push_back(p);
  }
  const long samples = static_cast<long>(std::min(sweep.samples.size(), per_sample.size()));
  int threads = fe.options().threads;
  if (threads <= 0) threads = static_cast<int>(std::min(2u, std::max(1u, std::thread::hardware_concurrency())));
  threads = static_cast<int>(std::max<long>(1, std::min<long>(threads, samples)));

  std::vector<PartialPeaks> partial(threads, PartialPeaks{peaks});
  std::atomic<bool> stop{false};
  std::vector<std::exception_ptr> errors(threads);
  // Each worker takes every threads-th sample, in blocks that one solve_many back-substitutes
  // together (one read of each link's factor per block).
  constexpr long kBlock = 16;
  const auto work = [&](int worker) {
    try {
      std::vector<long> block;
      std::vector<fe::LoadCase> cases;
      for (long first = worker; first < samples && !stop.load(); first += kBlock * threads) {
        block.clear();
        for (long i = first; i < samples && static_cast<long>(block.size()) < kBlock; i += threads) block.push_back(i);
        control.checkpoint("stress", block.front(), samples);
        for (FePeak& peak : partial[worker].peaks) {
          cases.clear();
          for (long i : block) cases.push_back(fe.load_case(per_sample[i], peak.body));
          const std::vector<fe::StressField> fields = fe.plate(peak.body).solve_many(cases);
          for (std::size_t k = 0; k < block.size(); ++k) {
            FePeak seen;
            seen.step = sweep.samples[block[k]].step;
            seen.von_mises = fields[k].peak;
            seen.at = fields[k].peak_at;
            seen.node = fields[k].peak_node;
            seen.load_unbalance = fields[k].load_unbalance;
            seen.support_reaction = fields[k].support_reaction;
            merge_peak(peak, seen);
          }
        }
      }
    } catch (...) {
      errors[worker] = std::current_exception();
      stop = true;
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& t : pool) t.join();
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  for (const PartialPeaks& part : partial)
    for (std::size_t k = 0; k < peaks.size(); ++k) merge_peak(peaks[k], part.peaks[k]);
  add_flat_arcs(fe, sweep, per_sample, peaks);
  for (FePeak& peak : peaks) {
    const auto& material = m.bodies[peak.body].material;
    if (material && material->yield_strength && peak.von_mises > 0.0)
      peak.safety_factor = *material->yield_strength / peak.von_mises;
  }
  return peaks;
}

namespace {

// |b - a| / b per link, the links of a and b in the same order.
std::vector<double> peak_changes(const std::vector<FePeak>& a, const std::vector<FePeak>& b) {
  std::vector<double> change;
  for (std::size_t k = 0; k < b.size(); ++k)
    change.push_back(b[k].von_mises > 0.0 ? std::abs(b[k].von_mises - a[k].von_mises) / b[k].von_mises : 0.0);
  return change;
}

}  // namespace

FeConvergence converge_fe_peaks(const std::shared_ptr<const InverseDynamics>& dynamics, const FeOptions& options,
                                std::vector<FePeak> first, const SweepResult& sweep,
                                const std::vector<DynamicsResult>& per_sample, double tolerance, int max_meshes,
                                const RunControl& control) {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw Error(ErrorKind::BadInput, "the convergence tolerance must be above 0 and below 100 %");
  FeConvergence out;
  out.tolerance = tolerance;
  out.meshes.push_back({options.refinement, std::move(first), {}});
  FeOptions next = options;
  while (true) {
    if (static_cast<int>(out.meshes.size()) >= max_meshes) {
      out.stopped = "stopped after " + std::to_string(max_meshes) + " meshes";
      return out;
    }
    next.refinement *= 2;
    std::unique_ptr<LinkFe> fe;
    try {
      fe = std::make_unique<LinkFe>(dynamics, next, control);
    } catch (const Error& e) {
      // The budget is checked before any plate is meshed; any other error is the caller's.
      if (std::string(e.what()).find("max_nodes") == std::string::npos) throw;
      out.stopped = std::string("stopped at the node budget: the next mesh is refused (") + e.what() + ")";
      return out;
    }
    FeConvergence::Mesh mesh{next.refinement, fe_peaks(*fe, sweep, per_sample, control), {}};
    mesh.change = peak_changes(out.meshes.back().peaks, mesh.peaks);
    out.converged = std::all_of(mesh.change.begin(), mesh.change.end(), [&](double c) { return c < tolerance; });
    out.meshes.push_back(std::move(mesh));
    if (out.converged) return out;
  }
}

}  // namespace nbar
