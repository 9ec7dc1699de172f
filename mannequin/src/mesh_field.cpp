#include "mesh_field.h"

#include <algorithm>

#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/isosurface.h"

using namespace dresskit::mesh;

namespace dresskit::mannequin {

TriangleMesh mesh_implicit(const ImplicitUnion& shape, double edge, double max_spacing,
                           const std::function<double(const Eigen::Vector3d&)>& cut) {
  // The grid is finer than the target edge and than the thinnest part; remeshing then brings the
  // triangles to the target size and a good shape.
  const double spacing = std::min(0.6 * edge, max_spacing);
  const ScalarField field = [&shape](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    shape.evaluate(p, v);
  };
  TriangleMesh mesh = marching_tetrahedra(field, shape.bounds(2 * spacing), spacing);
  if (cut) {
    Eigen::VectorXd value(mesh.num_vertices());
    for (int i = 0; i < mesh.num_vertices(); ++i) value(i) = cut(mesh.V.row(i).transpose());
    mesh = cut_mesh(mesh, value);
  }
  CleanupOptions options;
  options.remesh_edge_length = edge;
  options.remesh_iterations = 5;
  mesh = cleanup_mesh(mesh, options).mesh;
  project_to_zero_set(field, mesh.V);
  mesh.source_vertex = Eigen::VectorXi::LinSpaced(mesh.num_vertices(), 0, mesh.num_vertices() - 1);
  return mesh;
}

}  // namespace dresskit::mannequin
