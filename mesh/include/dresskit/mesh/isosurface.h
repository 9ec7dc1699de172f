#pragma once
// Pure kernels that make surfaces from scalar fields: used by the procedural scene, and by anything
// else that needs a watertight surface of an implicit shape.
#include <functional>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::mesh {

/// A scalar field evaluated on a batch of points: values(i) = f(points.row(i)).
using ScalarField = std::function<void(const Eigen::MatrixX3d& points, Eigen::VectorXd& values)>;

/// The surface f = 0 of a field that is negative inside, by marching tetrahedra on a regular grid of the
/// given spacing [m] over box (each cube split into six tetrahedra around its main diagonal, so that
/// neighbouring cubes agree). The result is watertight and manifold, with one vertex per crossed grid
/// edge, and its triangles face towards positive f (outwards). Grid values of exactly zero are nudged
/// to a tiny positive value so that the surface stays manifold. Triangles can be thin: remesh if
/// quality matters. The box must enclose the zero set.
TriangleMesh marching_tetrahedra(const ScalarField& field, const Eigen::AlignedBox3d& box,
                                 double spacing);

/// Cuts a mesh along the zero line of a per-vertex scalar (linear along edges) and keeps the part where
/// value < 0. Crossed edges get one new vertex each (shared by both faces), whose attributes are
/// interpolated (labels: from the kept end); source_vertex of new vertices is -1. Quads are dropped.
TriangleMesh cut_mesh(const TriangleMesh& mesh, const Eigen::VectorXd& value);

/// Moves each vertex onto the zero set of a field with a few Newton steps along the numerical
/// gradient (x ← x − f ∇f / |∇f|²); steps are clamped to max_step [m]. Returns the largest |f| left.
double project_to_zero_set(const ScalarField& field, Eigen::MatrixX3d& V, int iterations = 3,
                           double max_step = 0.01);

}  // namespace dresskit::mesh
