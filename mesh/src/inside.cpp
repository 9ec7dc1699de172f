#include "dresskit/mesh/inside.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dresskit/mesh/errors.h"

namespace dresskit::mesh {
namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Ray = Kernel::Ray_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct InsideTest::Impl {
  std::vector<Triangle> triangles;
  Tree tree;
};

InsideTest::InsideTest(const TriangleMesh& surface) : impl_(std::make_unique<Impl>()) {
  if (surface.num_faces() == 0) throw InputError("inside test: the surface has no faces");
  impl_->triangles.reserve(static_cast<std::size_t>(surface.num_faces()));
  for (int f = 0; f < surface.num_faces(); ++f) {
    Point p[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::RowVector3d v = surface.V.row(surface.F(f, k));
      p[k] = Point(v.x(), v.y(), v.z());
    }
    if (!CGAL::collinear(p[0], p[1], p[2])) impl_->triangles.emplace_back(p[0], p[1], p[2]);
  }
  if (impl_->triangles.empty()) throw InputError("inside test: every face of the surface is degenerate");
  impl_->tree.rebuild(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.accelerate_distance_queries();
}

InsideTest::~InsideTest() = default;
InsideTest::InsideTest(InsideTest&&) noexcept = default;
InsideTest& InsideTest::operator=(InsideTest&&) noexcept = default;

double InsideTest::signed_distance(const Eigen::Vector3d& p) const {
  const Point q(p.x(), p.y(), p.z());
  const double d = std::sqrt(impl_->tree.squared_distance(q));
  // Three directions no mesh is aligned with, so that a ray rarely grazes an edge or a vertex (a
  // grazing ray may count a crossing twice or miss it; the majority outvotes one such ray).
  static const Kernel::Vector_3 directions[3] = {{0.5773, 0.5813, 0.5734}, {-0.7071, 0.0123, 0.7070},
                                                 {0.1234, -0.9876, 0.0972}};
  int votes = 0;
  for (const auto& dir : directions)
    votes += impl_->tree.number_of_intersected_primitives(Ray(q, dir)) % 2;
  return votes >= 2 ? -d : d;
}

int InsideTest::count_deeper(const Eigen::MatrixX3d& points, double depth, double* deepest) const {
  int count = 0;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double d = signed_distance(points.row(i).transpose());
    if (d < 0.0) worst = std::max(worst, -d);
    if (d < -depth) ++count;
  }
  if (deepest) *deepest = worst;
  return count;
}

}  // namespace dresskit::mesh
