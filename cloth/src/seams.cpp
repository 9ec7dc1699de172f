#include "dresskit/cloth/seams.h"

#include <algorithm>
#include <numeric>
#include <set>
#include <string>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/union_find.h"

using namespace dresskit::mesh;

namespace dresskit::cloth {
namespace {

void add_stitch(SeamSet& s, int a, int b0, int b1, double t, StitchLaw law) {
  s.a.push_back(a);
  s.b0.push_back(b0);
  s.b1.push_back(b1);
  s.t.push_back(t);
  s.stiffness.push_back(law.stiffness);
  s.max_force.push_back(law.max_force);
}

/// Cumulative arc-length fractions along a chain; throws for a short or zero-length chain.
std::vector<double> fractions(const Eigen::MatrixX3d& x, const std::vector<int>& chain,
                              const char* name) {
  if (chain.size() < 2)
    throw InputError(std::string("seam chain ") + name + ": needs at least two particles");
  for (int p : chain) {
    if (p < 0 || p >= x.rows()) {
      throw InputError(std::string("seam chain ") + name + ": particle " + std::to_string(p) +
                       " is out of range (" + std::to_string(x.rows()) + " particles)");
    }
  }
  std::vector<double> f(chain.size(), 0.0);
  for (std::size_t k = 1; k < chain.size(); ++k)
    f[k] = f[k - 1] + (x.row(chain[k]) - x.row(chain[k - 1])).norm();
  if (!(f.back() > 0.0)) throw InputError(std::string("seam chain ") + name + ": has zero length");
  for (double& v : f) v /= f.back();
  return f;
}

}  // namespace

void add_seam_pairs(SeamSet& seams, const std::vector<std::array<int, 2>>& pairs, int particles,
                    StitchLaw law) {
  for (const auto& [a, b] : pairs) {
    const std::string name = "seam pair [" + std::to_string(a) + ", " + std::to_string(b) + "]";
    if (a < 0 || b < 0 || a >= particles || b >= particles) {
      throw InputError(name + ": index out of range (" + std::to_string(particles) + " particles)");
    }
    if (a == b) throw InputError(name + ": joins a particle to itself");
    add_stitch(seams, a, b, b, 0.0, law);
  }
}

void add_seam_chains(SeamSet& seams, const Eigen::MatrixX3d& x, const std::vector<int>& a,
                     const std::vector<int>& b, StitchLaw law) {
  const std::vector<double> fa = fractions(x, a, "a"), fb = fractions(x, b, "b");
  std::set<std::pair<int, int>> particle_pairs;
  // Stitches from every particle of `from` to the point at its fraction on `to`.
  auto sew = [&](const std::vector<int>& from, const std::vector<double>& ff,
                 const std::vector<int>& to, const std::vector<double>& ft) {
    for (std::size_t k = 0; k < from.size(); ++k) {
      const std::size_t m = std::min<std::size_t>(
          std::upper_bound(ft.begin(), ft.end(), ff[k]) - ft.begin(), ft.size() - 1);
      const std::size_t lo = m - 1;  // ft[lo] ≤ ff[k] ≤ ft[m]
      const double span = ft[m] - ft[lo];
      const double t = span > 0.0 ? std::clamp((ff[k] - ft[lo]) / span, 0.0, 1.0) : 0.0;
      const double snap = 1e-6;
      if (t < snap || t > 1.0 - snap) {
        const int other = to[t < snap ? lo : m];
        if (other == from[k]) continue;  // a dart's tip
        if (!particle_pairs.insert({std::min(other, from[k]), std::max(other, from[k])}).second)
          continue;
        add_stitch(seams, from[k], other, other, 0.0, law);
      } else {
        add_stitch(seams, from[k], to[lo], to[m], t, law);
      }
    }
  };
  sew(a, fa, b, fb);
  sew(b, fb, a, fa);
}

void seam_weights(const SeamSet& s, int k, int idx[3], double weight[3]) {
  idx[0] = s.a[k], idx[1] = s.b0[k], idx[2] = s.b1[k];
  weight[0] = 1.0, weight[1] = -(1.0 - s.t[k]), weight[2] = -s.t[k];
}

Eigen::Vector3d seam_gap(const SeamSet& s, int k, const Eigen::MatrixX3d& x) {
  return (x.row(s.a[k]) - (1.0 - s.t[k]) * x.row(s.b0[k]) - s.t[k] * x.row(s.b1[k])).transpose();
}

double default_stitch_stiffness(const SpringSet& springs) {
  double k = 0.0;
  int n = 0;
  for (int s = 0; s < springs.size(); ++s) {
    if (springs.type[s] != SpringType::structural) continue;
    k += springs.k_rest[s];
    ++n;
  }
  return n ? k / n : 1.0;
}

void cap_stitches_by_acceleration(SeamSet& seams, int first, const Eigen::VectorXd& mass,
                                  double acceleration) {
  const int n = seams.size() - first;
  for (int k = first; k < seams.size(); ++k) seams.max_force[k] = acceleration * mass.sum() / n;
}

Eigen::Vector3d stitch_force(const SeamSet& s, int k, const Eigen::Vector3d& c,
                             Eigen::Matrix3d* stiffness) {
  const double len = c.norm(), cap = s.max_force[k];
  if (s.stiffness[k] * len <= cap) {
    if (stiffness) *stiffness = s.stiffness[k] * Eigen::Matrix3d::Identity();
    return -s.stiffness[k] * c;
  }
  const Eigen::Vector3d u = c / len;
  if (stiffness) *stiffness = cap / len * (Eigen::Matrix3d::Identity() - u * u.transpose());
  return -cap * u;
}

Eigen::Vector3d stitch_target(const SeamSet& s, int k, const Eigen::Vector3d& c) {
  const double len = c.norm(), shrink = s.max_force[k] / s.stiffness[k];
  return len > shrink ? Eigen::Vector3d((1.0 - shrink / len) * c) : Eigen::Vector3d::Zero();
}

double seam_energy(const SeamSet& s, const Eigen::MatrixX3d& x) {
  double e = 0.0;
  for (int k = 0; k < s.size(); ++k) {
    const double len = seam_gap(s, k, x).norm(), c0 = s.max_force[k] / s.stiffness[k];
    e += len <= c0 ? 0.5 * s.stiffness[k] * len * len : s.max_force[k] * (len - 0.5 * c0);
  }
  return e;
}

void add_seam_forces(const SeamSet& s, const Eigen::MatrixX3d& x, Eigen::MatrixX3d& f) {
  int idx[3];
  double w[3];
  for (int k = 0; k < s.size(); ++k) {
    const Eigen::RowVector3d F = stitch_force(s, k, seam_gap(s, k, x)).transpose();
    seam_weights(s, k, idx, w);
    for (int m = 0; m < 3; ++m) f.row(idx[m]) += w[m] * F;
  }
}

SeamGaps seam_gaps(const SeamSet& s, const Eigen::MatrixX3d& x, double tolerance) {
  SeamGaps g;
  g.stitches = s.size();
  for (int k = 0; k < s.size(); ++k) {
    const double d = seam_gap(s, k, x).norm();
    g.max = std::max(g.max, d);
    g.mean += d;
    g.closed += d <= tolerance;
  }
  if (g.stitches) g.mean /= g.stitches;
  return g;
}

std::vector<int> seam_representatives(const SeamSet& s, int particles) {
  UnionFind sets(particles);
  for (int k = 0; k < s.size(); ++k) {
    sets.unite(s.a[k], s.b0[k]);
    sets.unite(s.b1[k], s.b0[k]);
  }
  std::vector<int> representative(static_cast<std::size_t>(particles));
  for (int p = 0; p < particles; ++p) representative[static_cast<std::size_t>(p)] = sets.find(p);
  return representative;
}

void weld_seams(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, const SeamSet& s,
                double tolerance, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F, std::vector<int>& to) {
  const int n = static_cast<int>(x.rows());
  UnionFind sets(n);
  for (int k = 0; k < s.size(); ++k) {
    const int other = s.t[k] == 0.0 ? s.b0[k] : s.t[k] == 1.0 ? s.b1[k] : -1;
    if (other >= 0 && seam_gap(s, k, x).norm() <= tolerance) sets.unite(s.a[k], other);
  }
  to.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> count;
  std::vector<Eigen::RowVector3d> sum;
  for (int p = 0; p < n; ++p) {
    const int r = sets.find(p);
    if (to[r] < 0) {
      to[r] = static_cast<int>(sum.size());
      sum.emplace_back(Eigen::RowVector3d::Zero());
      count.push_back(0);
    }
    to[p] = to[r];
    sum[to[p]] += x.row(p);
    ++count[to[p]];
  }
  V.resize(static_cast<Eigen::Index>(sum.size()), 3);
  for (std::size_t v = 0; v < sum.size(); ++v)
    V.row(static_cast<Eigen::Index>(v)) = sum[v] / count[v];
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3i t(to[faces(f, 0)], to[faces(f, 1)], to[faces(f, 2)]);
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) kept.push_back(t);
  }
  F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f) F.row(static_cast<Eigen::Index>(f)) = kept[f];
}

}  // namespace dresskit::cloth
