#include "nbar/synthesis/nine_point.hpp"

#include <Eigen/SVD>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/nine_point_start.hpp"
#include "nbar/synthesis/tracker.hpp"

namespace nbar::synthesis {
namespace {

constexpr int kPositions = 8;
// Some solutions of real tasks lie near the degenerate sets (x -> 0 while t -> infinity), with
// Jacobians of condition 1e18 and more in these coordinates; Newton still converges to them.
constexpr double kSingularCondition = 1e22;
// Whole homotopies along bent arcs tried before monodromy at the task.
constexpr int kBentArcs = 3;
// Two arrivals are one orbit when their keys agree to kSameKey, relative, or to kFarKey times
// the distance of their farthest pivot (in spreads of the points). Nearly sliders have pivots
// far away, known only to about 3e-12 times that distance (1e-6 at 1e6 spreads, 2e-2 at 6e9):
// a tolerance too tight counts such an orbit twice, which could make a short set look
// complete, while one too loose can only merge two orbits, which is reported as incomplete.
// Distinct orbits of random tasks differ by 1e-2 and more.
constexpr double kSameKey = 1e-4;
constexpr double kFarKey = 1e-10;
using Key = Eigen::Matrix<Complex, 6, 1>;

Complex random_complex(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const double re = normal(rng);
  return {re, normal(rng)};
}

CVector random_parameters(std::mt19937_64& rng, double scale) {
  CVector p(2 * kPositions);
  for (Eigen::Index k = 0; k < p.size(); ++k) p[k] = scale * random_complex(rng);
  return p;
}

double parameter_scale(const CVector& p) { return std::max(1.0, p.norm() / std::sqrt(double(p.size()))); }

// F(x; p(t)) along the arc p(t) = (1 - t) from + t to + t (1 - t) bend: a bend makes the way
// there differ from the way back, so that a round trip is a monodromy loop.
class ArcHomotopy final : public Homotopy {
 public:
  ArcHomotopy(const ParameterizedSystem& f, CVector from, CVector to, CVector bend)
      : f_(f), from_(std::move(from)), to_(std::move(to)), bend_(std::move(bend)) {}
  int size() const override { return f_.variables(); }
  bool linear_solve(const CVector& x, Complex t, bool velocity, CVector& y) const override {
    thread_local CVector p, dp;
    at(t, p, dp);
    return f_.linear_solve(x, p, velocity ? &dp : nullptr, y);
  }
  void evaluate(const CVector& x, Complex t, CVector& h, CMatrix* hx, CVector* ht) const override {
    CVector p, dp;
    at(t, p, dp);
    if (ht) {
      CMatrix jp;
      f_.evaluate(x, p, h, hx, &jp);
      *ht = jp * dp;
    } else {
      f_.evaluate(x, p, h, hx, nullptr);
    }
  }

 private:
  void at(Complex t, CVector& p, CVector& dp) const {
    p.noalias() = (1.0 - t) * from_ + t * to_ + (t * (1.0 - t)) * bend_;
    dp.noalias() = to_ - from_ + (1.0 - 2.0 * t) * bend_;
  }
  const ParameterizedSystem& f_;
  CVector from_, to_, bend_;
};

struct Arrival {
  bool ok = false;
  CVector affine;
  double condition = 0;
};

// Tracks every start (affine) along the arc on all threads; an arrival is a finite regular
// endpoint in affine coordinates.
std::vector<Arrival> track_all(const CVector& from, const CVector& to, const CVector& bend,
                               const std::vector<CVector>& starts, const NinePointOptions& options,
                               const std::function<void()>& on_path = {}, const TrackSettings& given = {}) {
  const ParameterizedSystem& f = nine_point_system();
  const ArcHomotopy homotopy(f, from, to, bend);
  std::vector<Arrival> arrivals(starts.size());
  TrackSettings settings = given;
  settings.singular_condition = kSingularCondition;
  std::atomic<size_t> next{0};
  std::atomic<bool> stopped{false}, out_of_time{false};
  auto worker = [&] {
    for (size_t i = next++; i < starts.size(); i = next++) {
      if (stopped || (options.stop && options.stop())) {
        stopped = true;
        continue;
      }
      // Past the budget the paths not started are left untracked: what arrived is kept.
      if (out_of_time || (options.out_of_time && options.out_of_time())) {
        out_of_time = true;
        continue;
      }
      const TrackResult r = track_path(homotopy, f.from_affine(starts[i]), settings);
      if (on_path) on_path();
      if (r.status != TrackStatus::Success || !r.x.allFinite() || r.winding != 1 ||
          !(r.condition < kSingularCondition) || f.infinity_measure(r.x) < 1e-10) {
        continue;
      }
      arrivals[i] = {true, f.to_affine(r.x), r.condition};
    }
  };
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = static_cast<unsigned>(
      std::min<size_t>(options.threads ? options.threads : hardware, std::max<size_t>(1, starts.size())));
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned k = 0; k < threads; ++k) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (stopped) throw Error(ErrorKind::Cancelled, "cancelled");
  return arrivals;
}

// An orbit's key with the distance of its farthest fixed pivot (from the key's symmetric
// functions of the three), which sets how well the key is known.
struct OrbitKey {
  Key key;
  double reach = 0.0;
  explicit OrbitKey(const Key& k) : key(k) {
    for (int side = 0; side < 2; ++side) {
      reach = std::max(
          {reach, std::abs(k[3 * side]), std::sqrt(std::abs(k[3 * side + 1])), std::cbrt(std::abs(k[3 * side + 2]))});
    }
  }
};

bool same_key(const OrbitKey& a, const OrbitKey& b) {
  const double tolerance = std::max(kSameKey, kFarKey * std::max(a.reach, b.reach));
  for (int k = 0; k < 6; ++k) {
    const Complex u = a.key[k], v = b.key[k];
    if (std::abs(u - v) > tolerance * (1.0 + std::max(std::abs(u), std::abs(v)))) return false;
  }
  return true;
}

// The orbits known at one parameter node.
struct OrbitSet {
  std::vector<CVector> representatives;
  std::vector<OrbitKey> keys;
  int find(const OrbitKey& key) const {
    for (size_t i = 0; i < keys.size(); ++i)
      if (same_key(keys[i], key)) return static_cast<int>(i);
    return -1;
  }
  bool add(const CVector& affine) {
    const OrbitKey key(orbit_key(affine));
    if (!key.key.allFinite() || find(key) >= 0) return false;
    representatives.push_back(affine);
    keys.push_back(key);
    return true;
  }
};

void check_points(const std::array<Eigen::Vector2d, 9>& points) {
  for (const auto& q : points)
    if (!q.allFinite()) throw Error(ErrorKind::InvalidModel, "nine-point task: a point is not a finite number");
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& q : points) centroid += q / 9.0;
  Eigen::Matrix<double, 9, 2> centred;
  for (int i = 0; i < 9; ++i) centred.row(i) = (points[i] - centroid).transpose();
  const double spread = centred.norm();
  if (!(spread > 0)) throw Error(ErrorKind::InvalidModel, "nine-point task: the nine points coincide");
  for (int i = 0; i < 9; ++i)
    for (int j = i + 1; j < 9; ++j)
      if ((points[i] - points[j]).norm() <= 1e-9 * spread)
        throw Error(ErrorKind::InvalidModel,
                    "nine-point task: points " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " coincide");
  const Eigen::JacobiSVD<Eigen::Matrix<double, 9, 2>> svd(centred);
  if (svd.singularValues()[1] <= 1e-9 * svd.singularValues()[0])
    throw Error(ErrorKind::InvalidModel,
                "nine-point task: the nine points lie on one line, which is no four-bar's coupler curve");
  if (common_circle(points))
    throw Error(ErrorKind::InvalidModel,
                "nine-point task: the nine points lie on one circle, through which infinitely many "
                "four-bars pass");
}

// |value| / sum of |terms| of each affine equation, the largest.
double relative_residual(const CVector& s, const CVector& p) {
  double worst = 0.0;
  for (int i = 0; i < kPositions; ++i) {
    const Complex t = s[i], tb = s[kPositions + i], d = p[i], db = p[kPositions + i];
    worst = std::max(worst, std::abs(t * tb - 1.0) / (1.0 + std::abs(t * tb)));
    for (int dyad = 0; dyad < 2; ++dyad) {
      const Complex x = s[16 + 4 * dyad], xb = s[17 + 4 * dyad], a = s[18 + 4 * dyad], ab = s[19 + 4 * dyad];
      const std::array<Complex, 8> terms{
          t * x * (db - ab), tb * xb * (d - a), d * db, -d * ab, -a * db, x * ab, a * xb, 0.0};
      Complex sum = 0.0;
      double size = 0.0;
      for (Complex term : terms) {
        sum += term;
        size += std::abs(term);
      }
      worst = std::max(worst, std::abs(sum) / std::max(size, 1e-300));
    }
  }
  return worst;
}

struct Frame {
  Eigen::Vector2d origin;
  double scale = 1;
  Eigen::Vector2d to_task(Complex z) const { return origin + scale * Eigen::Vector2d(z.real(), z.imag()); }
};

Frame task_frame(const std::array<Eigen::Vector2d, 9>& points) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& q : points) centroid += q / 9.0;
  double spread = 0;
  for (const auto& q : points) spread += (q - centroid).squaredNorm() / 9.0;
  return {points[0], std::sqrt(spread)};
}

FourBarDesign design_of(const CVector& s, const Frame& frame) {
  FourBarDesign d;
  d.coupler_point = frame.origin;
  d.moving_a = frame.to_task(s[16]);
  d.ground_a = frame.to_task(s[18]);
  d.moving_b = frame.to_task(s[20]);
  d.ground_b = frame.to_task(s[22]);
  return d;
}

// Failed paths, and every path whose orbit another path also reached.
std::vector<size_t> suspect_paths(const std::vector<Arrival>& arrivals) {
  OrbitSet seen;
  std::vector<size_t> owner, suspects;
  for (size_t i = 0; i < arrivals.size(); ++i) {
    const OrbitKey key(arrivals[i].ok ? orbit_key(arrivals[i].affine) : Key());
    if (!arrivals[i].ok || !key.key.allFinite()) {
      suspects.push_back(i);
      continue;
    }
    const int at = seen.find(key);
    if (at >= 0) {
      suspects.push_back(i);
      suspects.push_back(owner[static_cast<size_t>(at)]);
    } else {
      seen.keys.push_back(key);
      owner.push_back(i);
    }
  }
  std::sort(suspects.begin(), suspects.end());
  suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
  return suspects;
}

TrackSettings careful_settings(int round) {
  TrackSettings s;
  const double f = std::pow(0.1, round);
  s.max_step *= 0.25 * f;
  s.initial_step *= 0.1 * f;
  s.corrector_tolerance *= 1e-2 * f;
  s.contraction = 0.1;
  s.corrector_iterations = 4;
  s.max_steps *= 4;
  return s;
}

}  // namespace

CVector nine_point_parameters(const std::array<Eigen::Vector2d, 9>& points) {
  const Frame frame = task_frame(points);
  CVector p(2 * kPositions);
  for (int i = 0; i < kPositions; ++i) {
    const Eigen::Vector2d d = (points[i + 1] - frame.origin) / frame.scale;
    p[i] = Complex(d.x(), d.y());
    p[kPositions + i] = std::conj(p[i]);
  }
  return p;
}

bool nine_point_monodromy(const CVector& parameters, std::vector<CVector>& representatives,
                          const NinePointOptions& options, int& paths, int& loops, int enough) {
  std::mt19937_64 rng(options.seed * 7919 + 17);
  const double scale = parameter_scale(parameters);
  constexpr int kNodes = 3;
  std::vector<CVector> node{parameters};
  for (int k = 1; k < kNodes; ++k) node.push_back(random_parameters(rng, scale));
  struct Edge {
    int from, to;
    CVector bend;
    size_t sent = 0;
  };
  std::vector<Edge> edges;
  for (int i = 0; i < kNodes; ++i)
    for (int j = 0; j < kNodes; ++j)
      if (i != j) edges.push_back({i, j, random_parameters(rng, scale), 0});
  std::vector<OrbitSet> sets(kNodes);
  for (const auto& r : representatives) sets[0].add(r);
  const int max_batches = std::max(1, options.max_loops) * static_cast<int>(edges.size());
  for (int batch = 0; batch < max_batches; ++batch) {
    if (enough > 0 && static_cast<int>(sets[0].representatives.size()) >= enough) break;
    // The edge with the most orbits waiting goes next; when a count is enough, edges back to
    // the task first, so that each loop there and back can add to it.
    Edge* edge = nullptr;
    const auto better = [&](const Edge& e, const Edge& than) {
      if (enough > 0 && (e.to == 0) != (than.to == 0)) return e.to == 0;
      return sets[e.from].representatives.size() - e.sent > sets[than.from].representatives.size() - than.sent;
    };
    for (auto& e : edges) {
      if (sets[e.from].representatives.size() > e.sent && (!edge || better(e, *edge))) edge = &e;
    }
    if (!edge) break;
    const auto& source = sets[edge->from].representatives;
    const std::vector<CVector> starts(source.begin() + static_cast<std::ptrdiff_t>(edge->sent), source.end());
    edge->sent = source.size();
    const auto arrivals = track_all(node[edge->from], node[edge->to], edge->bend, starts, options);
    paths += static_cast<int>(starts.size());
    ++loops;
    for (const auto& a : arrivals)
      if (a.ok) sets[edge->to].add(a.affine);
    if (options.progress)
      options.progress("monodromy", static_cast<int>(sets[0].representatives.size()), kNinePointOrbits);
  }
  representatives = sets[0].representatives;
  for (const auto& e : edges)
    if (e.sent < sets[e.from].representatives.size()) return false;
  // Closed: the three nodes hold the same number of orbits, each sent along every edge.
  return true;
}

NinePointStart generate_nine_point_start(std::uint64_t seed, const NinePointOptions& options) {
  std::mt19937_64 rng(seed);
  // A random complex four-bar and nine poses of it: its coupler rotations t_j are chosen, the
  // coupler point's position then solves a quadratic (both dyads' circle conditions).
  CVector s(24);
  for (int k = 16; k < 24; ++k) s[k] = random_complex(rng);
  const Complex x = s[16], xb = s[17], a = s[18], ab = s[19], y = s[20], yb = s[21], b = s[22], bb = s[23];
  CVector p(2 * kPositions);
  const Complex r1 = (x - a) * (xb - ab), r2 = (y - b) * (yb - bb);
  for (int i = 0; i < kPositions; ++i) {
    const Complex t = random_complex(rng), tb = 1.0 / t;
    s[i] = t;
    s[kPositions + i] = tb;
    const Complex c = t * (y - x) - (b - a), cb = tb * (yb - xb) - (bb - ab);
    const Complex q = r2 - r1 - c * cb;
    const Complex u = (q + std::sqrt(q * q - 4.0 * cb * c * r1)) / (2.0 * cb);
    const Complex ub = r1 / u;
    p[i] = u - t * x + a;
    p[kPositions + i] = ub - tb * xb + ab;
  }
  NinePointStart start;
  start.parameters = p;
  start.representatives = {s};
  start.closed = nine_point_monodromy(p, start.representatives, options, start.paths, start.loops);
  return start;
}

NinePointStart move_nine_point_start(const NinePointStart& from, const CVector& to, const NinePointOptions& options) {
  NinePointStart moved;
  moved.parameters = to;
  OrbitSet found;
  for (const auto& a : track_all(from.parameters, to, CVector::Zero(to.size()), from.representatives, options))
    if (a.ok) found.add(a.affine);
  moved.paths = static_cast<int>(from.representatives.size());
  moved.representatives = found.representatives;
  moved.closed = from.closed && moved.representatives.size() == from.representatives.size();
  if (!moved.closed) moved.closed = nine_point_monodromy(to, moved.representatives, options, moved.paths, moved.loops);
  return moved;
}

namespace {

// The orbits reached at the task, with the condition number of the arrival that first reached
// each (0 for those monodromy found).
struct Reached {
  OrbitSet orbits;
  std::vector<double> condition;
  void add(const CVector& affine, double arrival_condition) {
    if (orbits.add(affine)) condition.push_back(arrival_condition);
  }
  void merge(const std::vector<Arrival>& arrivals) {
    for (const auto& a : arrivals)
      if (a.ok) add(a.affine, a.condition);
  }
  int count() const { return static_cast<int>(orbits.representatives.size()); }
};

// Paths that failed, or that arrived at an orbit another path reached (one of them jumped),
// are tracked again on the same segment with smaller steps and a stricter corrector.
void retrack_suspects(const NinePointStart& start, const CVector& target, const NinePointOptions& options,
                      std::vector<Arrival>& arrivals, NinePointResult& result) {
  const CVector straight = CVector::Zero(target.size());  // no bend: the same segment
  for (int round = 0; round < 2; ++round) {
    const std::vector<size_t> suspects = suspect_paths(arrivals);
    if (round == 0) result.failed_paths = static_cast<int>(suspects.size());
    if (suspects.empty()) break;
    std::vector<CVector> again;
    for (size_t i : suspects) again.push_back(start.representatives[i]);
    const auto retracked = track_all(start.parameters, target, straight, again, options, {}, careful_settings(round));
    result.paths += static_cast<int>(again.size());
    for (size_t k = 0; k < suspects.size(); ++k) arrivals[suspects[k]] = retracked[k];
  }
}

// A path that still fails may end where its representative has a dyad far away; the other
// members of its orbit (relabelled dyads, Roberts cognates) end at the same orbit elsewhere.
std::vector<CVector> other_members_of_failed(const NinePointStart& start, const std::vector<Arrival>& arrivals) {
  std::vector<CVector> members;
  for (size_t i = 0; i < arrivals.size(); ++i) {
    if (arrivals[i].ok) continue;
    const std::vector<CVector> orbit = nine_point_orbit(start.representatives[i], start.parameters);
    members.insert(members.end(), orbit.begin() + 1, orbit.end());
  }
  return members;
}

// Every real orbit as its three cognate four-bars in the task's frame.
void add_linkages(const Reached& reached, const CVector& target, const std::array<Eigen::Vector2d, 9>& points,
                  NinePointResult& result) {
  const Frame frame = task_frame(points);
  const ParameterizedSystem& f = nine_point_system();
  for (size_t k = 0; k < reached.orbits.representatives.size(); ++k) {
    const CVector& s = reached.orbits.representatives[k];
    result.representatives.push_back(s);
    if (!f.is_real(s)) continue;
    NinePointLinkage linkage;
    const CVector first = roberts_cognate(s, target), second = roberts_cognate(swap_dyads(s), target);
    linkage.designs = {design_of(s, frame), design_of(first, frame), design_of(second, frame)};
    linkage.residual = relative_residual(s, target);
    linkage.condition = reached.condition[k];
    result.linkages.push_back(linkage);
  }
  result.real_orbits = static_cast<int>(result.linkages.size());
}

}  // namespace

NinePointResult solve_nine_point(const std::array<Eigen::Vector2d, 9>& points, const NinePointOptions& given) {
  check_points(points);
  NinePointOptions options = given;
  if (given.time_budget > 0 && !given.out_of_time) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                               std::chrono::duration<double>(std::min(given.time_budget, 1e9)));
    options.out_of_time = [deadline] { return std::chrono::steady_clock::now() >= deadline; };
  }
  const auto spent = [&options] { return options.out_of_time && options.out_of_time(); };
  const CVector target = nine_point_parameters(points);
  const NinePointStart& start = nine_point_start();
  const CVector straight = CVector::Zero(target.size());
  NinePointResult result;
  std::atomic<int> done{0};
  const int total = static_cast<int>(start.representatives.size());
  const auto on_path = [&] {
    const int d = ++done;
    if (options.progress && (d % 16 == 0 || d == total)) options.progress("paths", d, total);
  };
  std::vector<Arrival> arrivals =
      track_all(start.parameters, target, straight, start.representatives, options, on_path);
  result.paths = total;
  if (!spent()) retrack_suspects(start, target, options, arrivals, result);
  Reached reached;
  reached.merge(arrivals);
  result.method = "parameter homotopy from a stored generic instance (" + std::to_string(total) + " paths)";

  if (reached.count() < total && !spent()) {
    const std::vector<CVector> members = other_members_of_failed(start, arrivals);
    reached.merge(track_all(start.parameters, target, straight, members, options));
    result.paths += static_cast<int>(members.size());
    result.method += ", the other members of failed paths' orbits";
  }
  // Still short: the whole homotopy again along bent arcs (other correspondences of the
  // orbits, so their arrivals are only merged), then monodromy at the task until the count is
  // reached. Some solutions of real tasks (moving pivots 1e5 to 1e9 spreads away) are reached
  // along some arcs only; an arc costs one path per orbit, a monodromy loop two.
  std::mt19937_64 rng(options.seed);
  for (int arc = 0; arc < kBentArcs && reached.count() < total && !spent(); ++arc) {
    reached.merge(track_all(start.parameters, target, 0.5 * random_parameters(rng, parameter_scale(target)),
                            start.representatives, options));
    result.paths += total;
    result.method += arc == 0 ? ", again along a bent arc" : ", along another";
  }
  bool closed = false;
  if (reached.count() < total && !spent()) {
    std::vector<CVector> representatives = reached.orbits.representatives;
    int paths = 0;
    closed = nine_point_monodromy(target, representatives, options, paths, result.monodromy_loops, total);
    result.paths += paths;
    for (size_t k = reached.orbits.representatives.size(); k < representatives.size(); ++k)
      reached.add(representatives[k], 0.0);
    result.method += ", then monodromy";
  }
  result.orbits = reached.count();
  result.complete = result.orbits == total && total == kNinePointOrbits;
  result.budget_spent = !result.complete && spent();
  if (result.budget_spent)
    result.certificate = fmt::format("incomplete: {} of {} orbits when the run stopped at its time budget of {:g} s",
                                     result.orbits, kNinePointOrbits, given.time_budget);
  else if (result.complete)
    result.certificate = "complete: 1442 distinct orbits, as many as the stored instance has (closed under monodromy)";
  else if (result.orbits > kNinePointOrbits)
    result.certificate = "degenerate: " + std::to_string(result.orbits) + " orbits, more than the " +
                         std::to_string(kNinePointOrbits) +
                         " of a generic task: the points are special (on a conic, or nearly on a circle?), and "
                         "their solutions are not a finite set nbar can count";
  else
    result.certificate = "incomplete: " + std::to_string(result.orbits) + " of " + std::to_string(kNinePointOrbits) +
                         " orbits" + (closed ? " (monodromy closed below the generic count: a degenerate task?)" : "");
  add_linkages(reached, target, points, result);
  return result;
}

}  // namespace nbar::synthesis
