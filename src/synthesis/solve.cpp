#include "nbar/synthesis/solve.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>

#include "linear_algebra.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/tracker.hpp"

namespace nbar::synthesis {
namespace {

Complex random_complex(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const double re = normal(rng);
  const double im = normal(rng);
  return {re, im};
}

Complex random_unit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0.0, 2.0 * 3.14159265358979323846);
  return std::polar(1.0, angle(rng));
}

double relative_imaginary(const CVector& x) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i].imag()) / (1.0 + std::abs(x[i])));
  return worst;
}

bool same_point(const CVector& a, const CVector& b, double tolerance) {
  return (a - b).norm() <= tolerance * (1.0 + std::max(a.norm(), b.norm()));
}

TrackSettings track_settings(const SolverOptions& options) {
  TrackSettings s;
  s.final_tolerance = std::min(1e-12, options.tolerance);
  s.singular_condition = options.singular_condition;
  s.max_steps = options.max_steps;
  return s;
}

// Harder settings for paths suspected of having jumped.
TrackSettings tighter(TrackSettings s, int round) {
  const double f = std::pow(0.1, round);
  s.max_step *= 0.25 * f;
  s.initial_step *= 0.1 * f;
  s.corrector_tolerance *= 1e-2 * f;
  s.contraction = 0.1;
  s.corrector_iterations = 4;
  s.max_steps *= 4;
  return s;
}

// Classifies a tracked endpoint; `infinity` is the smallest relative homogenizing coordinate.
using Classifier = std::function<void(const CVector& x, Endpoint& e)>;

// What every homotopy's classification shares: singular or not, at infinity or finite.
// Returns whether the endpoint is finite (then the caller adds residual and realness).
bool finite_endpoint(Endpoint& e, const CVector& x, double infinity_measure, const SolverOptions& options) {
  e.singular = e.winding > 1 || !(e.condition < options.singular_condition);
  e.x = x;
  e.kind = infinity_measure < options.infinity_threshold ? EndpointKind::AtInfinity : EndpointKind::Finite;
  return e.kind == EndpointKind::Finite;
}

unsigned thread_count(const SolverOptions& options, size_t jobs) {
  unsigned n = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::min<size_t>(n, std::max<size_t>(1, jobs)));
}

Endpoint track_one(const Homotopy& h, const CVector& start, int path, const TrackSettings& s,
                   const Classifier& classify) {
  Endpoint e;
  e.path = path;
  TrackResult r = track_path(h, start, s);
  e.steps = r.steps;
  e.winding = r.winding;
  e.condition = r.condition;
  e.x = r.x;
  if (r.status != TrackStatus::Success || !r.x.allFinite()) {
    e.kind = EndpointKind::Failed;
    e.failure = r.failure.empty() ? "non-finite endpoint" : r.failure;
    return e;
  }
  classify(r.x, e);
  return e;
}

// Runs every path (on all threads), then re-tracks, with tighter settings, pairs of regular
// endpoints (finite or at infinity) that coincide (two paths cannot end at one regular
// solution, so one jumped) and, when asked, paths that failed.
SolveResult run_paths(const Homotopy& h, const std::vector<CVector>& starts, const Classifier& classify,
                      const SolverOptions& options) {
  SolveResult result;
  result.endpoints.resize(starts.size());
  const TrackSettings settings = track_settings(options);
  std::atomic<size_t> next{0}, done{0};
  auto worker = [&] {
    for (size_t i = next++; i < starts.size(); i = next++) {
      if (options.stop && options.stop()) {
        result.endpoints[i].path = static_cast<int>(i);
        result.endpoints[i].failure = "stopped";
        continue;
      }
      result.endpoints[i] = track_one(h, starts[i], static_cast<int>(i), settings, classify);
      const size_t finished = ++done;
      if (options.progress) options.progress(static_cast<int>(finished), static_cast<int>(starts.size()));
    }
  };
  const unsigned threads = thread_count(options, starts.size());
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned k = 0; k < threads; ++k) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }

  for (int round = 1; round <= 2; ++round) {
    if (options.stop && options.stop()) break;
    std::vector<size_t> suspects;
    const auto& ends = result.endpoints;
    if (options.retrack_failures)
      for (size_t i = 0; i < ends.size(); ++i)
        if (ends[i].kind == EndpointKind::Failed) suspects.push_back(i);
    for (size_t i = 0; i < ends.size(); ++i) {
      if (ends[i].kind == EndpointKind::Failed || ends[i].singular) continue;
      for (size_t j = i + 1; j < ends.size(); ++j) {
        if (ends[j].kind != ends[i].kind || ends[j].singular) continue;
        if (same_point(ends[i].x, ends[j].x, 1e-7)) {
          suspects.push_back(i);
          suspects.push_back(j);
        }
      }
    }
    if (suspects.empty()) break;
    std::sort(suspects.begin(), suspects.end());
    suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
    const TrackSettings careful = tighter(settings, round - 1);
    for (size_t i : suspects) {
      result.endpoints[i] = track_one(h, starts[i], static_cast<int>(i), careful, classify);
      result.endpoints[i].retracked = true;
    }
    result.retracked += static_cast<int>(suspects.size());
  }
  return result;
}

// ---------------------------------------------------------------------------------------
// Homogenization and the linear-product start system.

struct Homogenized {
  int n = 0;                             // affine variables
  VariableGroups groups;                 // affine variables of each group
  std::vector<int> group_of;             // group of each affine variable
  PolynomialSystem target;               // homogenized, in n + groups variables
  std::vector<std::vector<int>> degree;  // degree[i][g]
  std::vector<CVector> patch;            // per group: coefficients over (group vars..., h_g)

  int size() const { return n + static_cast<int>(groups.size()); }
  int h_index(int g) const { return n + g; }
  std::vector<int> coordinates(int g) const {  // group variables followed by its h
    std::vector<int> c = groups[g];
    c.push_back(h_index(g));
    return c;
  }
};

Homogenized homogenize(const PolynomialSystem& f, const VariableGroups& groups, std::mt19937_64& rng) {
  Homogenized hom;
  hom.n = f.variables();
  hom.groups = groups;
  hom.group_of.assign(hom.n, -1);
  for (size_t g = 0; g < groups.size(); ++g)
    for (int v : groups[g]) {
      if (v < 0 || v >= hom.n) throw Error(ErrorKind::BadInput, "variable groups: index out of range");
      if (hom.group_of[v] != -1) throw Error(ErrorKind::BadInput, "variable groups: a variable is in two groups");
      hom.group_of[v] = static_cast<int>(g);
    }
  for (int v = 0; v < hom.n; ++v)
    if (hom.group_of[v] == -1) throw Error(ErrorKind::BadInput, "variable groups: a variable is in no group");
  if (f.equations() != f.variables())
    throw Error(ErrorKind::BadInput, "homotopy solver: the system must be square (as many equations as unknowns)");

  const int G = static_cast<int>(groups.size());
  const int N = hom.n + G;
  std::vector<Polynomial> equations;
  for (int i = 0; i < f.equations(); ++i) {
    std::vector<int> deg(G);
    for (int g = 0; g < G; ++g) deg[g] = std::max(0, f[i].degree_in(groups[g]));
    hom.degree.push_back(deg);
    Polynomial p(N);
    for (const auto& [e, c] : f[i].terms()) {
      Polynomial::Exponents he(N, 0);
      std::copy(e.begin(), e.end(), he.begin());
      for (int g = 0; g < G; ++g) {
        int d = 0;
        for (int v : groups[g]) d += e[v];
        he[hom.n + g] = static_cast<std::uint16_t>(deg[g] - d);
      }
      p.add_term(he, c);
    }
    equations.push_back(std::move(p));
  }
  hom.target = PolynomialSystem(std::move(equations));
  for (int g = 0; g < G; ++g) {
    CVector a(static_cast<Eigen::Index>(groups[g].size() + 1));
    for (Eigen::Index k = 0; k < a.size(); ++k) a[k] = random_complex(rng);
    hom.patch.push_back(a);
  }
  return hom;
}

// G_i = product over groups g, factors k < degree[i][g], of a random linear form in the
// homogeneous coordinates of group g.
struct LinearProductStart {
  const Homogenized* hom = nullptr;
  // forms[i] = list of (group, coefficients over hom->coordinates(group))
  std::vector<std::vector<std::pair<int, CVector>>> forms;
};

LinearProductStart make_start(const Homogenized& hom, std::mt19937_64& rng) {
  LinearProductStart start;
  start.hom = &hom;
  for (const auto& deg : hom.degree) {
    std::vector<std::pair<int, CVector>> factors;
    for (size_t g = 0; g < deg.size(); ++g)
      for (int k = 0; k < deg[g]; ++k) {
        CVector c(static_cast<Eigen::Index>(hom.groups[g].size() + 1));
        for (Eigen::Index j = 0; j < c.size(); ++j) c[j] = random_complex(rng);
        factors.emplace_back(static_cast<int>(g), c);
      }
    start.forms.push_back(std::move(factors));
  }
  return start;
}

// Every start solution: each equation picks one factor to vanish, group g receiving exactly
// as many equations as it has variables; each group's linear system then fixes its point.
std::vector<CVector> start_solutions(const LinearProductStart& start) {
  const Homogenized& hom = *start.hom;
  const int G = static_cast<int>(hom.groups.size());
  const int n = hom.n;
  std::vector<int> capacity(G);
  for (int g = 0; g < G; ++g) capacity[g] = static_cast<int>(hom.groups[g].size());
  std::vector<int> choice(n, -1);
  std::vector<CVector> solutions;

  auto solve_assignment = [&] {
    CVector x(hom.size());
    for (int g = 0; g < G; ++g) {
      const int m = static_cast<int>(hom.groups[g].size()) + 1;
      CMatrix a(m, m);
      CVector b = CVector::Zero(m);
      int row = 0;
      for (int i = 0; i < n; ++i)
        if (start.forms[i][choice[i]].first == g) a.row(row++) = start.forms[i][choice[i]].second.transpose();
      a.row(row) = hom.patch[g].transpose();
      b[row] = 1.0;
      const CVector y = a.partialPivLu().solve(b);
      const auto coords = hom.coordinates(g);
      for (int k = 0; k < m; ++k) x[coords[k]] = y[k];
    }
    solutions.push_back(x);
  };

  auto recurse = [&](auto&& self, int i) -> void {
    if (i == n) {
      solve_assignment();
      return;
    }
    for (size_t k = 0; k < start.forms[i].size(); ++k) {
      const int g = start.forms[i][k].first;
      if (capacity[g] == 0) continue;
      --capacity[g];
      choice[i] = static_cast<int>(k);
      self(self, i + 1);
      ++capacity[g];
    }
  };
  recurse(recurse, 0);
  return solutions;
}

class LinearProductHomotopy final : public Homotopy {
 public:
  LinearProductHomotopy(const Homogenized& hom, const LinearProductStart& start, Complex gamma)
      : hom_(hom), start_(start), gamma_(gamma) {}

  int size() const override { return hom_.size(); }

  void evaluate(const CVector& x, Complex t, CVector& h, CMatrix* hx, CVector* ht) const override {
    const int N = hom_.size(), n = hom_.n;
    h.resize(N);
    CVector f, g(n);
    CMatrix jf, jg = CMatrix::Zero(n, N);
    if (hx)
      hom_.target.evaluate(x, f, jf);
    else
      hom_.target.evaluate(x, f);
    for (int i = 0; i < n; ++i) start_value(i, x, g[i], hx ? &jg : nullptr);
    h.head(n) = (1.0 - t) * gamma_ * g + t * f;
    if (hx) {
      hx->setZero(N, N);
      hx->topRows(n) = (1.0 - t) * gamma_ * jg + t * jf;
    }
    for (int gr = 0; gr < static_cast<int>(hom_.groups.size()); ++gr) {
      const auto coords = hom_.coordinates(gr);
      Complex value = -1.0;
      for (size_t k = 0; k < coords.size(); ++k) {
        value += hom_.patch[gr][static_cast<Eigen::Index>(k)] * x[coords[k]];
        if (hx) (*hx)(n + gr, coords[k]) = hom_.patch[gr][static_cast<Eigen::Index>(k)];
      }
      h[n + gr] = value;
    }
    if (ht) {
      ht->setZero(N);
      ht->head(n) = f - gamma_ * g;
    }
  }

 private:
  void start_value(int i, const CVector& x, Complex& value, CMatrix* jg) const {
    const auto& factors = start_.forms[i];
    const size_t m = factors.size();
    std::vector<Complex> l(m);
    for (size_t k = 0; k < m; ++k) {
      const auto coords = hom_.coordinates(factors[k].first);
      Complex s = 0.0;
      for (size_t j = 0; j < coords.size(); ++j) s += factors[k].second[static_cast<Eigen::Index>(j)] * x[coords[j]];
      l[k] = s;
    }
    // prefix/suffix products give every "all but one" product without division
    std::vector<Complex> prefix(m + 1, 1.0), suffix(m + 1, 1.0);
    for (size_t k = 0; k < m; ++k) prefix[k + 1] = prefix[k] * l[k];
    for (size_t k = m; k-- > 0;) suffix[k] = suffix[k + 1] * l[k];
    value = prefix[m];
    if (!jg) return;
    for (size_t k = 0; k < m; ++k) {
      const Complex others = prefix[k] * suffix[k + 1];
      const auto coords = hom_.coordinates(factors[k].first);
      for (size_t j = 0; j < coords.size(); ++j)
        (*jg)(i, coords[j]) += others * factors[k].second[static_cast<Eigen::Index>(j)];
    }
  }

  const Homogenized& hom_;
  const LinearProductStart& start_;
  Complex gamma_;
};

SolveResult solve_grouped(const PolynomialSystem& f, const VariableGroups& groups, const SolverOptions& options) {
  std::mt19937_64 rng(options.seed);
  const Homogenized hom = homogenize(f, groups, rng);
  const LinearProductStart start = make_start(hom, rng);
  const LinearProductHomotopy homotopy(hom, start, random_unit(rng));
  const std::vector<CVector> starts = start_solutions(start);

  const Classifier classify = [&](const CVector& X, Endpoint& e) {
    double measure = 1.0;
    CVector x(hom.n);
    for (int g = 0; g < static_cast<int>(hom.groups.size()); ++g) {
      Eigen::Index m = static_cast<Eigen::Index>(hom.groups[g].size() + 1);
      CVector part(m);
      const auto coords = hom.coordinates(g);
      for (Eigen::Index k = 0; k < m; ++k) part[k] = X[coords[k]];
      const Complex hg = X[hom.h_index(g)];
      measure = std::min(measure, std::abs(hg) / part.norm());
      for (int v : hom.groups[g]) x[v] = X[v] / hg;
    }
    if (!finite_endpoint(e, X, measure, options)) return;
    e.x = x;
    CVector value;
    f.evaluate(x, value);
    e.residual = value.cwiseAbs().maxCoeff();
    e.real = relative_imaginary(x) < 1e-8;
  };
  return run_paths(homotopy, starts, classify, options);
}

// ---------------------------------------------------------------------------------------
// Parameter homotopy: H(x, t) = F(x; (1 - t) from + t to).

class ParameterHomotopy final : public Homotopy {
 public:
  ParameterHomotopy(const ParameterizedSystem& f, CVector from, CVector to)
      : f_(f), from_(std::move(from)), to_(std::move(to)), direction_(to_ - from_) {}
  int size() const override { return f_.variables(); }
  bool linear_solve(const CVector& x, Complex t, bool velocity, CVector& y) const override {
    thread_local CVector p;  // the tracker's innermost call: no allocation per step
    p.noalias() = (1.0 - t) * from_ + t * to_;
    return f_.linear_solve(x, p, velocity ? &direction_ : nullptr, y);
  }
  void evaluate(const CVector& x, Complex t, CVector& h, CMatrix* hx, CVector* ht) const override {
    const CVector p = (1.0 - t) * from_ + t * to_;
    if (ht) {
      CMatrix jp;
      f_.evaluate(x, p, h, hx, &jp);
      *ht = jp * (to_ - from_);
    } else {
      f_.evaluate(x, p, h, hx, nullptr);
    }
  }

 private:
  const ParameterizedSystem& f_;
  CVector from_, to_, direction_;
};

Classifier parameter_classifier(const ParameterizedSystem& f, const CVector& to, const SolverOptions& options) {
  return [&f, to, options](const CVector& x, Endpoint& e) {
    if (!finite_endpoint(e, x, f.infinity_measure(x), options)) return;
    CVector value;
    f.evaluate(x, to, value, nullptr, nullptr);
    e.residual = value.cwiseAbs().maxCoeff();
    e.real = f.is_real(f.to_affine(x));
  };
}

}  // namespace

bool ParameterizedSystem::linear_solve(const CVector& x, const CVector& p, const CVector* dp, CVector& y) const {
  CVector f;
  CMatrix jx, jp;
  evaluate(x, p, f, &jx, dp ? &jp : nullptr);
  const Eigen::PartialPivLU<CMatrix> lu(jx);
  y = dp ? CVector(lu.solve(jp * *dp)) : CVector(lu.solve(f));
  return y.allFinite();
}

bool ParameterizedSystem::is_real(const CVector& affine) const { return relative_imaginary(affine) < 1e-8; }

int SolveResult::count(EndpointKind kind) const {
  return static_cast<int>(
      std::count_if(endpoints.begin(), endpoints.end(), [kind](const Endpoint& e) { return e.kind == kind; }));
}

std::vector<const Endpoint*> SolveResult::finite_regular() const {
  std::vector<const Endpoint*> out;
  for (const auto& e : endpoints) {
    if (e.kind != EndpointKind::Finite || e.singular) continue;
    const bool duplicate =
        std::any_of(out.begin(), out.end(), [&](const Endpoint* o) { return same_point(o->x, e.x, 1e-7); });
    if (!duplicate) out.push_back(&e);
  }
  return out;
}

std::vector<CVector> SolveResult::solutions(bool real_only) const {
  std::vector<CVector> out;
  for (const Endpoint* e : finite_regular())
    if (!real_only || e->real) out.push_back(e->x);
  return out;
}

long total_degree_count(const PolynomialSystem& f) {
  long count = 1;
  for (const auto& p : f.polynomials()) count *= std::max(0, p.degree());
  return count;
}

long multihomogeneous_count(const PolynomialSystem& f, const VariableGroups& groups) {
  std::mt19937_64 rng(0);
  const Homogenized hom = homogenize(f, groups, rng);
  // Sum over assignments of equations to groups (group g receiving |g| equations) of the
  // product of the chosen degrees.
  const int G = static_cast<int>(groups.size());
  std::vector<int> capacity(G);
  for (int g = 0; g < G; ++g) capacity[g] = static_cast<int>(groups[g].size());
  auto recurse = [&](auto&& self, int i) -> long {
    if (i == hom.n) return 1;
    long total = 0;
    for (int g = 0; g < G; ++g) {
      if (capacity[g] == 0 || hom.degree[i][g] == 0) continue;
      --capacity[g];
      total += hom.degree[i][g] * self(self, i + 1);
      ++capacity[g];
    }
    return total;
  };
  return recurse(recurse, 0);
}

SolveResult solve_total_degree(const PolynomialSystem& f, const SolverOptions& options) {
  VariableGroups one(1);
  one[0].resize(f.variables());
  std::iota(one[0].begin(), one[0].end(), 0);
  return solve_grouped(f, one, options);
}

SolveResult solve_linear_product(const PolynomialSystem& f, const VariableGroups& groups,
                                 const SolverOptions& options) {
  return solve_grouped(f, groups, options);
}

SolveResult solve_parameter_homotopy(const ParameterizedSystem& f, const CVector& from,
                                     const std::vector<CVector>& from_solutions, const CVector& to,
                                     const SolverOptions& options) {
  if (from.size() != f.parameters() || to.size() != f.parameters())
    throw Error(ErrorKind::BadInput, "parameter homotopy: wrong number of parameters");
  const ParameterHomotopy homotopy(f, from, to);
  return run_paths(homotopy, from_solutions, parameter_classifier(f, to, options), options);
}

MonodromyResult monodromy_solve(const ParameterizedSystem& f, const CVector& p, const std::vector<CVector>& seeds,
                                int target, const SolverOptions& options, int stale_loops, int max_loops) {
  MonodromyResult result;
  result.solutions = seeds;
  std::mt19937_64 rng(options.seed);
  SolverOptions quiet = options;
  quiet.progress = nullptr;
  const double scale = std::max(1.0, p.norm() / std::sqrt(static_cast<double>(p.size())));
  int stale = 0;
  auto add_new = [&](const SolveResult& r) {
    int added = 0;
    for (const auto& e : r.endpoints) {
      if (e.kind != EndpointKind::Finite || e.singular) continue;
      const bool known = std::any_of(result.solutions.begin(), result.solutions.end(),
                                     [&](const CVector& s) { return same_point(s, e.x, 1e-7); });
      if (!known) {
        result.solutions.push_back(e.x);
        ++added;
      }
    }
    return added;
  };
  while (result.loops < max_loops) {
    if (target > 0 && static_cast<int>(result.solutions.size()) >= target) {
      result.stable = true;
      break;
    }
    if (stale >= stale_loops) {
      result.stable = true;
      break;
    }
    ++result.loops;
    CVector p1(p.size()), p2(p.size());
    for (Eigen::Index k = 0; k < p.size(); ++k) {
      p1[k] = scale * random_complex(rng);
      p2[k] = scale * random_complex(rng);
    }
    std::vector<CVector> at1, at2;
    for (const auto& e : solve_parameter_homotopy(f, p, result.solutions, p1, quiet).endpoints)
      if (e.kind == EndpointKind::Finite && !e.singular) at1.push_back(e.x);
    for (const auto& e : solve_parameter_homotopy(f, p1, at1, p2, quiet).endpoints)
      if (e.kind == EndpointKind::Finite && !e.singular) at2.push_back(e.x);
    const int added = add_new(solve_parameter_homotopy(f, p2, at2, p, quiet));
    stale = added > 0 ? 0 : stale + 1;
  }
  return result;
}

}  // namespace nbar::synthesis
