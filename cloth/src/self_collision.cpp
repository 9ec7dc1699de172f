#include "dresskit/cloth/self_collision.h"

#include "dresskit/mesh/union_find.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "dresskit/cloth/geometry.h"
#include "self_collision_internal.h"

namespace dresskit::cloth {

EdgeList triangle_edges(const Eigen::MatrixX3i& F) {
  EdgeList e;
  e.face_edges.resize(F.rows(), 3);
  std::unordered_map<long long, int> index;
  index.reserve(static_cast<std::size_t>(F.rows()) * 2);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(F(f, k), F(f, (k + 1) % 3)), b = std::max(F(f, k), F(f, (k + 1) % 3));
      const long long key = (static_cast<long long>(a) << 32) | static_cast<unsigned>(b);
      auto [it, fresh] = index.try_emplace(key, static_cast<int>(e.i.size()));
      if (fresh) {
        e.i.push_back(a);
        e.j.push_back(b);
        e.owner.push_back(f);
      }
      e.face_edges(f, k) = it->second;
    }
  }
  return e;
}

std::vector<int> detail::representatives(std::vector<int> joined, int particles) {
  if (joined.empty()) {
    joined.resize(static_cast<std::size_t>(particles));
    std::iota(joined.begin(), joined.end(), 0);
  }
  return joined;
}

namespace {

Eigen::Vector3d row(const Eigen::MatrixX3d& m, int i) { return m.row(i).transpose(); }

/// The weights of a pair's points in P = A − B: side A positive, side B negative.
void signed_weights(int kind, const double w[4], double alpha[4]) {
  const int side_a = kind == 0 ? 1 : 2;
  for (int k = 0; k < 4; ++k) alpha[k] = k < side_a ? w[k] : -w[k];
}

Eigen::Vector3d weighted(const Eigen::MatrixX3d& x, const int idx[4], const double alpha[4]) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) p += alpha[k] * row(x, idx[k]);
  return p;
}

}  // namespace

SelfCollision::SelfCollision(const Eigen::MatrixX3i& faces, int particles, std::vector<int> joined,
                             SelfCollisionOptions options)
    : faces_(faces),
      edges_(triangle_edges(faces)),
      rep_(detail::representatives(std::move(joined), particles)),
      vertex_owner_(static_cast<std::size_t>(particles), -1),
      options_(options) {
  for (int f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (vertex_owner_[faces_(f, k)] < 0) vertex_owner_[faces_(f, k)] = f;
  face_records_.resize(static_cast<std::size_t>(faces_.rows()));
  for (int f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      FaceRecord& r = face_records_[static_cast<std::size_t>(f)];
      const int v = faces_(f, k), e = edges_.face_edges(f, k);
      r.rep[k] = rep_[v];
      r.vertex[k] = vertex_owner_[v] == f ? v : -1;
      r.edge[k] = edges_.owner[e] == f ? e : -1;
    }
  edge_reps_.resize(edges_.i.size());
  for (std::size_t e = 0; e < edges_.i.size(); ++e)
    edge_reps_[e] = {rep_[edges_.i[e]], rep_[edges_.j[e]]};
  vertex_faces_start_.assign(static_cast<std::size_t>(particles) + 1, 0);
  for (int f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++vertex_faces_start_[faces_(f, k) + 1];
  for (int v = 0; v < particles; ++v) vertex_faces_start_[v + 1] += vertex_faces_start_[v];
  vertex_faces_.resize(static_cast<std::size_t>(vertex_faces_start_.back()));
  std::vector<int> fill(vertex_faces_start_.begin(), vertex_faces_start_.end() - 1);
  for (int f = 0; f < faces_.rows(); ++f)
    for (int k = 0; k < 3; ++k) vertex_faces_[fill[faces_(f, k)]++] = f;
}

bool SelfCollision::vertex_in_face(int v, int f) const {
  const int r = rep_[v];
  return rep_[faces_(f, 0)] == r || rep_[faces_(f, 1)] == r || rep_[faces_(f, 2)] == r;
}

bool SelfCollision::edges_touch(int e1, int e2) const {
  const std::array<int, 2>&a = edge_reps_[static_cast<std::size_t>(e1)],
                         &b = edge_reps_[static_cast<std::size_t>(e2)];
  return a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1];
}

void SelfCollision::indices(const Pair& p, int idx[4]) const {
  if (p.kind == 0) {
    idx[0] = p.a, idx[1] = faces_(p.b, 0), idx[2] = faces_(p.b, 1), idx[3] = faces_(p.b, 2);
  } else {
    idx[0] = edges_.i[p.a], idx[1] = edges_.j[p.a], idx[2] = edges_.i[p.b], idx[3] = edges_.j[p.b];
  }
}

// The candidate list is made for each particle's listed box: the box of its path x0 → x1 when it
// was last listed, grown by the path's extent on each side (lb_lo_, lb_hi_). It holds every pair of primitives whose listed boxes, padded
// by the thickness h each, overlap: the pairs whose listed boxes are at most 2h apart. While each
// particle's path stays within its listed box grown by h/2, every pair that is not listed stays
// more than h apart on the way, so the list holds every pair that a pass needs (within h at x0, or
// eta < h on the paths) — across the passes, the calls and the steps: a cloth at rest keeps its
// list from step to step. A particle whose path leaves its box is stale: its box becomes its
// current path's and its pairs are found again (update_candidates), or the whole list is made anew
// (candidates) when many are.

// The whole list from one traversal of the tree against itself: for each pair of distinct
// triangles whose padded boxes overlap, the particles and edges that the one owns against the other
// triangle and its owned edges. Every primitive has one owning triangle, and a primitive's box lies
// inside its owner's, so every pair comes exactly once. (Measured against a box query per particle
// and per edge: that was 23 % of a sewn-tube run, most of it node visits.)
void SelfCollision::candidates(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                               std::vector<Pair>& out) {
  out.clear();
  const double h = options_.thickness;
  // Each particle's box is its path's, grown by the path once more on each side: a particle that
  // keeps its velocity stays in it for the next step, so a moving cloth makes its list every other
  // step instead of at every step (the full list was 40 % of a cloth draped onto a head).
  const Eigen::MatrixX3d ahead = (x1 - x0).cwiseAbs();
  lb_lo_ = x0.cwiseMin(x1) - ahead;
  lb_hi_ = x0.cwiseMax(x1) + ahead;
  if (bvh_.empty()) bvh_ = TriangleBvh(x0, faces_);
  bvh_.refit(lb_hi_, &lb_lo_, h);
  // Boxes padded by h (two overlap when their listed boxes are at most 2h apart): the particles',
  // the triangles' (the tree's) and the edges'.
  const Eigen::MatrixX3d lo = lb_lo_.array() - h, hi = lb_hi_.array() + h;
  const int ne = static_cast<int>(edges_.i.size());
  std::vector<Eigen::AlignedBox3d> edge_box(static_cast<std::size_t>(ne));
  for (int e = 0; e < ne; ++e) {
    const int a = edges_.i[e], b = edges_.j[e];
    edge_box[e] = Eigen::AlignedBox3d(lo.row(a).cwiseMin(lo.row(b)).transpose(),
                                      hi.row(a).cwiseMax(hi.row(b)).transpose());
  }
  auto vertex_meets = [&](int v, int t) {
    const Eigen::AlignedBox3d& b = bvh_.box(t);
    for (int c = 0; c < 3; ++c)
      if (lo(v, c) > b.max()[c] || hi(v, c) < b.min()[c]) return false;
    return true;
  };
  // The vertex of corner k of A, when A owns it, against face B (not a corner of B's).
  auto vertex_pair = [&](const FaceRecord& A, int k, const FaceRecord& B, int tb) {
    const int v = A.vertex[k], r = A.rep[k];
    if (v >= 0 && r != B.rep[0] && r != B.rep[1] && r != B.rep[2] && vertex_meets(v, tb))
      out.push_back({0, v, tb, 0.0});
  };
  bvh_.self_pairs([&](int ta, int tb) {
    const FaceRecord &A = face_records_[static_cast<std::size_t>(ta)],
                     &B = face_records_[static_cast<std::size_t>(tb)];
    for (int k = 0; k < 3; ++k) {
      vertex_pair(A, k, B, tb);
      const int e = A.edge[k];
      if (e < 0) continue;
      for (int m = 0; m < 3; ++m) {
        const int e2 = B.edge[m];
        if (e2 < 0 || edges_touch(e, e2)) continue;
        if (edge_box[e].intersects(edge_box[e2])) out.push_back({1, e, e2, 0.0});
      }
    }
    // The edge–edge pairs came once above; the reverse adds only the other side's particles.
    for (int k = 0; k < 3; ++k) vertex_pair(B, k, A, ta);
  });
  keep_reachable(x0, out, 0);
}

// The pairs from `first` on get their distances at x0 and only those that can come within h while
// their particles stay in their listed boxes grown by h/2 are kept: a primitive's points move by at
// most the largest reach of its particles (the farthest point of the grown box from x0), so a pair
// farther apart than h plus both sides' reaches never needs a pass. On a cloth in contact the boxes
// alone also list neighbours of neighbours (a vertex against the triangle across its quad): most of
// a list of ~25,000 pairs on the 64² cloth-onto-sphere scene.
void SelfCollision::keep_reachable(const Eigen::MatrixX3d& x0, std::vector<Pair>& out,
                                   std::size_t first) {
  const double h = options_.thickness, grow = 0.5 * h;
  const int nv = static_cast<int>(x0.rows());
  reach_.resize(nv);
  for (int p = 0; p < nv; ++p) {
    double r2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double r = std::max(x0(p, c) - (lb_lo_(p, c) - grow), lb_hi_(p, c) + grow - x0(p, c));
      r2 += r * r;
    }
    reach_[p] = std::sqrt(r2);
  }
  double w[4];
  for (auto it = out.begin() + static_cast<std::ptrdiff_t>(first); it != out.end(); ++it)
    it->d0 = closest(*it, x0, w).norm();
  int idx[4];
  auto far = [&](const Pair& p) {
    indices(p, idx);
    const int side_a = p.kind == 0 ? 1 : 2;
    double ra = 0.0, rb = 0.0;
    for (int k = 0; k < 4; ++k) (k < side_a ? ra : rb) = std::max(k < side_a ? ra : rb, reach_[idx[k]]);
    return p.d0 - ra - rb > h;
  };
  out.erase(std::remove_if(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(), far), out.end());
}

// The list brought up to date for the particles flagged in stale_: their listed boxes become their
// current paths' boxes, their pairs are dropped and found again. Each primitive pair comes once: a
// vertex's own query gives its vertex–triangle pairs, a face's query the vertices that are not
// stale against it, an edge's query the edges that are not stale or have a larger index.
void SelfCollision::update_candidates(const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                      std::vector<Pair>& out) {
  const double h = options_.thickness;
  auto stale_pair = [&](const Pair& p) {
    int idx[4];
    indices(p, idx);
    return stale_[idx[0]] || stale_[idx[1]] || stale_[idx[2]] || stale_[idx[3]];
  };
  out.erase(std::remove_if(out.begin(), out.end(), stale_pair), out.end());
  const std::size_t first_new = out.size();
  const int nv = static_cast<int>(x1.rows());
  for (int p = 0; p < nv; ++p)
    if (stale_[p]) {
      const Eigen::RowVector3d ahead = (x1.row(p) - x0.row(p)).cwiseAbs();
      lb_lo_.row(p) = x0.row(p).cwiseMin(x1.row(p)) - ahead;
      lb_hi_.row(p) = x0.row(p).cwiseMax(x1.row(p)) + ahead;
    }
  bvh_.refit(lb_hi_, &lb_lo_, h);
  // Boxes padded by h: two overlap when their listed boxes are at most 2h apart.
  auto box_of = [&](std::initializer_list<int> ps) {
    Eigen::AlignedBox3d b;
    for (int p : ps)
      b.extend(Eigen::AlignedBox3d(lb_lo_.row(p).transpose().array() - h,
                                   lb_hi_.row(p).transpose().array() + h));
    return b;
  };
  auto overlap = [&](const Eigen::AlignedBox3d& a, std::initializer_list<int> ps) {
    return a.intersects(box_of(ps));
  };
  std::vector<char> face_flag(static_cast<std::size_t>(faces_.rows()), 0),
      edge_flag(edges_.i.size(), 0);
  std::vector<int> stale_faces, stale_edges;
  for (int p = 0; p < nv; ++p) {
    if (!stale_[p]) continue;
    for (int k = vertex_faces_start_[p]; k < vertex_faces_start_[p + 1]; ++k) {
      const int f = vertex_faces_[k];
      if (!face_flag[f]) face_flag[f] = 1, stale_faces.push_back(f);
      for (int m = 0; m < 3; ++m) {
        const int e = edges_.face_edges(f, m);
        if (!edge_flag[e] && (edges_.i[e] == p || edges_.j[e] == p))
          edge_flag[e] = 1, stale_edges.push_back(e);
      }
    }
    if (vertex_owner_[p] < 0) continue;
    const Eigen::AlignedBox3d box = box_of({p});
    bvh_.query(box, [&](int tb) {
      if (!vertex_in_face(p, tb) && overlap(box, {faces_(tb, 0), faces_(tb, 1), faces_(tb, 2)}))
        out.push_back({0, p, tb, 0.0});
    });
  }
  for (int f : stale_faces) {
    const Eigen::AlignedBox3d box = box_of({faces_(f, 0), faces_(f, 1), faces_(f, 2)});
    bvh_.query(box, [&](int tb) {
      for (int k = 0; k < 3; ++k) {
        const int v = faces_(tb, k);
        if (vertex_owner_[v] == tb && !stale_[v] && !vertex_in_face(v, f) && overlap(box, {v}))
          out.push_back({0, v, f, 0.0});
      }
    });
  }
  for (int e : stale_edges) {
    const Eigen::AlignedBox3d box = box_of({edges_.i[e], edges_.j[e]});
    bvh_.query(box, [&](int tb) {
      for (int m = 0; m < 3; ++m) {
        const int e2 = edges_.face_edges(tb, m);
        if (edges_.owner[e2] != tb || (edge_flag[e2] && e2 <= e) || edges_touch(e, e2)) continue;
        if (overlap(box, {edges_.i[e2], edges_.j[e2]})) out.push_back({1, e, e2, 0.0});
      }
    });
  }
  keep_reachable(x0, out, first_new);
}

// The closest points of a pair's two primitives at x: their weights (side A's, then side B's) and
// the gap from B's point to A's.
Eigen::Vector3d SelfCollision::closest(const Pair& pair, const Eigen::MatrixX3d& x,
                                       double w[4]) const {
  int idx[4];
  indices(pair, idx);
  if (pair.kind == 0) {
    Eigen::Vector3d bary;
    const Eigen::Vector3d q = closest_point_on_triangle(row(x, idx[0]), row(x, idx[1]),
                                                        row(x, idx[2]), row(x, idx[3]), &bary);
    w[0] = 1.0, w[1] = bary[0], w[2] = bary[1], w[3] = bary[2];
    return row(x, idx[0]) - q;
  }
  double s, u;
  closest_points_of_segments(row(x, idx[0]), row(x, idx[1]), row(x, idx[2]), row(x, idx[3]), &s,
                             &u);
  w[0] = 1.0 - s, w[1] = s, w[2] = 1.0 - u, w[3] = u;
  return (w[0] * row(x, idx[0]) + w[1] * row(x, idx[1])) -
         (w[2] * row(x, idx[2]) + w[3] * row(x, idx[3]));
}

// The candidate pairs closer than the thickness at x0 (their distances d0 are in the list), with
// their closest points' weights, distance and normal (B to A; for touching pairs the surface
// normal, to be turned against the approach).
void SelfCollision::find_close_pairs(const Eigen::MatrixX3d& x0, const std::vector<Pair>& pairs) {
  close_.clear();
  const double h = options_.thickness;
  int idx[4];
  for (const Pair& pair : pairs) {
    if (pair.d0 >= h) continue;
    Close c;
    c.pair = pair;
    const Eigen::Vector3d gap = closest(pair, x0, c.w);
    c.d = gap.norm();
    if (c.d > 1e-6 * h) {
      c.normal = gap / c.d;
    } else {
      indices(pair, idx);
      c.touching = true;
      c.normal =
          pair.kind == 0
              ? Eigen::Vector3d(
                    (row(x0, idx[2]) - row(x0, idx[1])).cross(row(x0, idx[3]) - row(x0, idx[1])))
              : Eigen::Vector3d(
                    (row(x0, idx[1]) - row(x0, idx[0])).cross(row(x0, idx[3]) - row(x0, idx[2])));
      if (c.normal.squaredNorm() < 1e-40) continue;
      c.normal.normalize();
    }
    close_.push_back(c);
  }
}

SelfCollisionResult SelfCollision::resolve(const Eigen::MatrixX3d& x0, Eigen::MatrixX3d& x1,
                                           const Eigen::VectorXd& inverse_mass) {
  SelfCollisionResult result;
  if (faces_.rows() == 0) return result;
  const double h = options_.thickness;
  // Contact distance of the path test; corrections leave pairs at least twice this apart, so that
  // a corrected pair is not found again at the end of its path.
  const double eta = 0.05 * h;
  std::vector<Pair>& pairs = pairs_;
  int idx[4];
  double alpha[4];
  // A new step: the pairs' distances at its start, and the pairs within h there, are found again;
  // nothing is verified yet.
  const int nv = static_cast<int>(x0.rows());
  const bool new_step = !(step_x0_.rows() == nv && step_x0_ == x0);
  if (new_step) {
    // Crossings at the start (a cloth that begins tangled, as a placed outfit can): their
    // particles are flagged, and a pair with a flagged particle on both its sides is left out
    // below, so that the passes do not fight a crossing they cannot undo (a placed t-shirt with 12
    // of them stopped within 0.01 s), while a tangled part still collides with the rest, so that a
    // tangle does not spread through it. A step that starts where the last one ended, verified,
    // starts without new ones: looked for again only while there are.
    const bool continued = verified_.rows() == nv && verified_ == x0;
    if (!continued || tangled_count_ > 0) find_tangles(x0);
    result.tangled_particles = tangled_count_;
    step_x0_ = x0;
    verified_.resize(0, 3);
  }
  // The candidate list (see candidates()): particles whose paths have left their listed boxes grown
  // by h/2 are stale; a few (under 5 %) get their pairs found again (update_candidates: on the
  // 100² cape on gc_mean_all, ~6 full lists a step had been made for a handful of particles each),
  // many the whole list.
  bool rebuilt = false;
  int updated = 0;  // particles whose pairs the last refresh() found again (flagged in stale_)
  auto refresh = [&] {
    updated = 0;
    if (lb_lo_.rows() == nv) {
      stale_.assign(static_cast<std::size_t>(nv), 0);
      const double grow = 0.5 * h;
      for (int p = 0; p < nv; ++p)
        for (int c = 0; c < 3; ++c) {
          const double lo = std::min(x0(p, c), x1(p, c)), hi = std::max(x0(p, c), x1(p, c));
          if (lo < lb_lo_(p, c) - grow || hi > lb_hi_(p, c) + grow) {
            stale_[p] = 1, ++updated;
            break;
          }
        }
      if (updated == 0) return false;
      if (updated * 20 < nv) {
        update_candidates(x0, x1, pairs);
        return false;
      }
      updated = 0;
    }
    candidates(x0, x1, pairs);
    rebuilt = true;
    return true;
  };

  // 1. Proximity at the start: stop approach and ease apart towards the thickness, with friction.
  // The pairs within h at x0, with their closest points, depend on x0 alone: found once a step.
  if (!refresh() && new_step) {  // the kept pairs' distances at the new start
    double w[4];
    for (Pair& p : pairs) p.d0 = closest(p, x0, w).norm();
  }
  if (new_step) find_close_pairs(x0, pairs);
  auto tangled = [&](const int ids[4], int kind) {
    if (tangled_count_ == 0) return false;
    const int split = kind == 0 ? 1 : 2;  // vertex | triangle, or edge | edge
    bool a = false, b = false;
    for (int k = 0; k < 4; ++k) (k < split ? a : b) |= tangled_[ids[k]] != 0;
    return a && b;
  };
  for (const Close& close : close_) {
    indices(close.pair, idx);
    if (tangled(idx, close.pair.kind)) continue;
    signed_weights(close.pair.kind, close.w, alpha);
    ++result.proximity_pairs;
    Eigen::Vector3d n = close.normal;
    if (close.touching && n.dot(weighted(x1, idx, alpha)) < 0.0) n = -n;  // against the approach
    const double s1 = n.dot(weighted(x1, idx, alpha));
    const double delta = close.d + 0.1 * (h - close.d) - s1;
    if (delta <= 0.0) continue;
    shift_weighted_difference(x1, inverse_mass, idx, alpha, delta * n);
    ++result.repulsions;
    // Coulomb friction: the sliding of the two points against each other loses up to μ × the
    // normal correction.
    const Eigen::Vector3d rel = weighted(x1, idx, alpha) - weighted(x0, idx, alpha);
    const Eigen::Vector3d slide = rel - n.dot(rel) * n;
    const double len = slide.norm();
    if (len > 0.0)
      shift_weighted_difference(x1, inverse_mass, idx, alpha,
                                -std::min(1.0, options_.friction * delta / len) * slide);
  }

  // A contact on the paths that the end state does not already clear: the pair's correction (the
  // change of P along the normal), or 0.
  auto contact_correction = [&](const Pair& pair, Contact& c) {
    indices(pair, idx);
    if (tangled(idx, pair.kind)) {
      c = Contact();
      return 0.0;
    }
    // The distance between the two primitives changes by at most the largest relative motion of a
    // point of one against a point of the other (both move linearly; their points are convex
    // combinations): a pair that starts farther apart than eta plus that cannot touch on the way.
    // On a cloth at rest, or falling as a whole, this skips nearly every pair's path test.
    const int side_a = pair.kind == 0 ? 1 : 2;
    double reach2 = 0.0;
    for (int i = 0; i < side_a; ++i)
      for (int j = side_a; j < 4; ++j)
        reach2 = std::max(
            reach2,
            ((x1.row(idx[i]) - x0.row(idx[i])) - (x1.row(idx[j]) - x0.row(idx[j]))).squaredNorm());
    if (pair.d0 - std::sqrt(reach2) > eta) {
      c = Contact();
      return 0.0;
    }
    c = pair.kind == 0 ? vertex_triangle_ccd(row(x0, idx[0]), row(x1, idx[0]), row(x0, idx[1]),
                                             row(x1, idx[1]), row(x0, idx[2]), row(x1, idx[2]),
                                             row(x0, idx[3]), row(x1, idx[3]), eta)
                       : edge_edge_ccd(row(x0, idx[0]), row(x1, idx[0]), row(x0, idx[1]),
                                       row(x1, idx[1]), row(x0, idx[2]), row(x1, idx[2]),
                                       row(x0, idx[3]), row(x1, idx[3]), eta);
    if (!c) return 0.0;
    signed_weights(pair.kind, c.w, alpha);
    const double s0 = c.normal.dot(weighted(x0, idx, alpha)),
                 s1 = c.normal.dot(weighted(x1, idx, alpha));
    return std::clamp(s0, 2.0 * eta, h) - s1;
  };

  // 2. Collision passes: inelastic corrections, Gauss–Seidel. A pass after the first tests only the
  // pairs with a particle that the previous pass moved (the others' paths are unchanged), unless
  // the candidate list was made anew. (The 71² cape on gc_mean_all took 7–12 passes a step over
  // ~6,000 pairs in proximity.)
  Contact c;
  // At the end of a call every listed pair is clear of contact (the last pass found none, or the
  // zones resolved them all, or nothing moved). So a later call for the same step, with the same
  // list, need test only the pairs with a particle that has moved since (the proximity phase or the
  // caller's collider pass and length limits moved a few).
  std::vector<char> moved(static_cast<std::size_t>(nv), 1), moving(static_cast<std::size_t>(nv), 0);
  const bool all_first = rebuilt || verified_.rows() != nv;
  if (!all_first)
    for (int p = 0; p < nv; ++p) moved[p] = (x1.row(p) != verified_.row(p));
  auto done = [&](const SelfCollisionResult& r) {
    verified_ = x1;
    return r;
  };
  for (int pass = 0; pass < options_.impulse_passes; ++pass) {
    const bool all = refresh() || (pass == 0 && all_first);
    if (updated)  // the pairs found again are tested in this pass
      for (int p = 0; p < nv; ++p) moved[p] = moved[p] || stale_[p];
    std::fill(moving.begin(), moving.end(), 0);
    int found = 0;
    for (const Pair& pair : pairs) {
      if (!all) {
        indices(pair, idx);
        if (!moved[idx[0]] && !moved[idx[1]] && !moved[idx[2]] && !moved[idx[3]]) continue;
      }
      const double delta = contact_correction(pair, c);
      if (delta <= 0.0) continue;
      shift_weighted_difference(x1, inverse_mass, idx, alpha, delta * c.normal);
      for (int k = 0; k < 4; ++k) moving[idx[k]] = 1;
      ++found;
    }
    moved.swap(moving);
    result.ccd_collisions += found;
    ++result.ccd_passes;
    if (found == 0) return done(result);
  }

  // 3. Rigid impact zones.
  mesh::UnionFind zones(nv);
  std::vector<char> in_zone(static_cast<std::size_t>(nv), 0);
  for (int pass = 0; pass < options_.zone_passes; ++pass) {
    refresh();
    bool any = false;
    for (const Pair& pair : pairs) {
      if (contact_correction(pair, c) <= 0.0) continue;
      const int z = zones.find(idx[0]);
      if (in_zone[idx[0]] && zones.find(idx[1]) == z && zones.find(idx[2]) == z &&
          zones.find(idx[3]) == z)
        continue;
      any = true;
      for (int k = 0; k < 4; ++k) {
        in_zone[idx[k]] = 1;
        if (k) zones.unite(idx[k], idx[0]);
      }
    }
    if (!any) {
      std::vector<char> counted(static_cast<std::size_t>(nv), 0);
      for (int p = 0; p < nv; ++p) {
        if (!in_zone[p]) continue;
        ++result.zone_particles;
        const int z = zones.find(p);
        if (!counted[z]) ++result.zones, counted[z] = 1;
      }
      return done(result);
    }
    // Each zone moves rigidly from x0 with the momentum and angular momentum of its particles'
    // proposed motion; a zone holding a pinned particle stays where it was.
    std::unordered_map<int, std::vector<int>> members;
    for (int p = 0; p < nv; ++p)
      if (in_zone[p]) members[zones.find(p)].push_back(p);
    for (const auto& [root, list] : members) {
      (void)root;
      bool fixed = false;
      double mass = 0.0;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero(), move = Eigen::Vector3d::Zero();
      for (int p : list) {
        if (!(inverse_mass[p] > 0.0)) {
          fixed = true;
          break;
        }
        const double m = 1.0 / inverse_mass[p];
        mass += m;
        centre += m * row(x0, p);
        move += m * (row(x1, p) - row(x0, p));
      }
      if (fixed) {
        for (int p : list)
          if (inverse_mass[p] > 0.0) x1.row(p) = x0.row(p);
        continue;
      }
      centre /= mass;
      move /= mass;
      Eigen::Vector3d L = Eigen::Vector3d::Zero();
      Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
      for (int p : list) {
        const double m = 1.0 / inverse_mass[p];
        const Eigen::Vector3d r = row(x0, p) - centre;
        L += m * r.cross(row(x1, p) - row(x0, p) - move);
        I += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
      }
      // ω = I⁻¹ L, by the pseudo-inverse: a zone on a line has no inertia about that line.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
      Eigen::Vector3d omega = Eigen::Vector3d::Zero();
      const double top = eig.eigenvalues().maxCoeff();
      for (int k = 0; k < 3; ++k) {
        const double lambda = eig.eigenvalues()[k];
        if (lambda > 1e-12 * top)
          omega += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(L) / lambda);
      }
      // Below half a turn the straight path between a point and its rotated self stays an
      // invertible map of space: the zone cannot cut itself on the way.
      const double angle = std::min(omega.norm(), 3.0);
      const Eigen::Matrix3d R =
          angle > 0.0 ? Eigen::AngleAxisd(angle, omega.normalized()).toRotationMatrix()
                      : Eigen::Matrix3d::Identity();
      for (int p : list) x1.row(p) = (centre + move + R * (row(x0, p) - centre)).transpose();
    }
  }
  // Last resort: nothing free moves this step.
  for (int p = 0; p < nv; ++p)
    if (inverse_mass[p] > 0.0) x1.row(p) = x0.row(p);
  result.held = true;
  return done(result);
}

std::vector<std::array<int, 3>> SelfCollision::listed_pairs() const {
  std::vector<std::array<int, 3>> out;
  out.reserve(pairs_.size());
  for (const Pair& p : pairs_)
    out.push_back({p.kind, p.kind ? std::min(p.a, p.b) : p.a, p.kind ? std::max(p.a, p.b) : p.b});
  return out;
}

// One traversal of the tree against itself: for each pair of triangles whose boxes overlap, the
// edges that each owns against the other (an edge and a triangle sharing a particle excluded). An edge's box lies inside
// its owner's, so every crossing edge–triangle pair is met once. (A box query per edge took ~7 ms
// on a 64² cloth, 18 % of a cloth-onto-sphere run that counted at every frame.)
}  // namespace dresskit::cloth
