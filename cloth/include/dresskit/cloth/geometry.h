#pragma once
// Pure geometric kernels for collisions: closest points on triangles and segments, and the exact
// segment–triangle crossing test behind the intersection counts, and sparse-grid cell keys. No
// state, no allocation.
#include <Eigen/Core>
#include <cstdint>

namespace dresskit::cloth {

/// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5), with its
/// barycentric coordinates in bary (u, v, w: q = u a + v b + w c) if bary is not null.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          Eigen::Vector3d* bary = nullptr);

/// Closest points of segments p0–p1 and q0–q1: parameters s, t in [0, 1] (Ericson §5.1.9); returns
/// the squared distance.
double closest_points_of_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, double* s, double* t);

/// True when segment p–q crosses triangle (a, b, c) at a point strictly inside both (a touch at an
/// end or on an edge counts as no crossing). Orientation signs of the five tetrahedra.
bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, const Eigen::Vector3d& c);


/// A hash key for the cell q of a sparse uniform grid, 21 bits per axis (cells 2²¹ apart share one);
/// the cell of a point p is (p / cell size) floored.
inline std::int64_t grid_cell_key(const Eigen::Vector3i& q) {
  return (static_cast<std::int64_t>(q.x() & 0x1fffff) << 42) | (static_cast<std::int64_t>(q.y() & 0x1fffff) << 21) |
         static_cast<std::int64_t>(q.z() & 0x1fffff);
}
inline std::int64_t grid_cell_key(const Eigen::Vector3d& p, double cell_size) {
  return grid_cell_key(Eigen::Vector3i((p / cell_size).array().floor().cast<int>()));
}

/// The first contact of two primitives moving linearly from their start (…0) to their end (…1)
/// positions over t ∈ [0, 1] (continuous collision detection).
struct Contact {
  double t = -1.0;  ///< time of contact in [0, 1]; −1: none
  /// Weights of the contact points: vertex–triangle (1, w0, w1, w2) with q = Σ w x_triangle;
  /// edge–edge (1 − s, s, 1 − u, u). The first pair belongs to side A, the rest to side B.
  double w[4] = {0, 0, 0, 0};
  /// Unit normal at contact, pointing from side B towards side A at the start.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  explicit operator bool() const { return t >= 0.0; }
};

/// Vertex p against triangle (a, b, c): the earliest t where p comes closer than eta to the
/// triangle. Candidate times are the roots of the coplanarity cubic ((b−a)×(c−a))·(p−a) = 0 in [0, 1]
/// (found by bisection on its monotone pieces), its extrema and both ends; each is confirmed by the
/// exact distance, so a flat sheet moving in its own plane gives no false contact.
Contact vertex_triangle_ccd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& a0,
                            const Eigen::Vector3d& a1, const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                            const Eigen::Vector3d& c0, const Eigen::Vector3d& c1, double eta);

/// Edge p–q against edge r–s, the same way (coplanarity of the four points).
Contact edge_edge_ccd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                      const Eigen::Vector3d& q1, const Eigen::Vector3d& r0, const Eigen::Vector3d& r1,
                      const Eigen::Vector3d& s0, const Eigen::Vector3d& s1, double eta);

/// Changes the weighted point difference P = Σ alpha[k] x[idx[k]] by `change`, each particle moving
/// in proportion to alpha[k] × its inverse mass (momentum is kept when Σ alpha = 0; particles of
/// inverse mass 0 — pinned — stay). The response of contacts and of seams closing.
void shift_weighted_difference(Eigen::MatrixX3d& x, const Eigen::VectorXd& inverse_mass, const int idx[4],
                               const double alpha[4], const Eigen::Vector3d& change);

/// Real roots in [0, 1] of c[0] + c[1] t + c[2] t² + c[3] t³ where the sign changes, plus the
/// interior extrema (touching roots are among them), ascending; returns how many (at most 5).
int cubic_candidates(const double c[4], double out[5]);

}  // namespace dresskit::cloth
