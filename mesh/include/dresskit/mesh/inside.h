#pragma once
// Inside or outside a body surface, and how deep: CGAL's AABB tree over the surface's triangles,
// inside by the majority of three ray parities in fixed generic directions, depth as the exact
// distance to the nearest triangle. Independent of the cloth module's distance grid, so that it can
// check what the simulator did (how many cloth vertices ended inside the body).
#include <Eigen/Core>
#include <memory>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::mesh {

class InsideTest {
 public:
  /// Throws InputError for a surface without faces.
  explicit InsideTest(const TriangleMesh& surface);
  ~InsideTest();
  InsideTest(InsideTest&&) noexcept;
  InsideTest& operator=(InsideTest&&) noexcept;

  /// Signed distance from p to the surface [m], negative inside. On a surface that is not
  /// watertight, inside is the majority of the three parities.
  double signed_distance(const Eigen::Vector3d& p) const;
  /// Of the rows of `points` (#P×3 [m]), how many lie inside deeper than `depth` [m], and the
  /// deepest of them (0 when none is inside) [m].
  int count_deeper(const Eigen::MatrixX3d& points, double depth, double* deepest = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dresskit::mesh
