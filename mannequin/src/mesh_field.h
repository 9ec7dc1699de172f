#pragma once
// Meshing of the scene's implicit shapes, shared by the mannequin and the garments.
#include <functional>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/mannequin/implicit.h"

namespace dresskit::mannequin {

/// Marching tetrahedra at min(0.6 × edge, max_spacing) [m], then optionally a cut (keep where
/// cut(p) < 0), isotropic remeshing to `edge` [m] and projection back onto the zero set.
/// max_spacing must resolve the shape's thinnest part, or the grid aliases it (handles, holes).
/// source_vertex = the mesh's own order.
mesh::TriangleMesh mesh_implicit(const ImplicitUnion& shape, double edge, double max_spacing,
                           const std::function<double(const Eigen::Vector3d&)>& cut = nullptr);

/// Grid spacing that resolves the thinnest parts (wrists, ankles) of a body of this height [m].
inline double feature_spacing(double height) { return 0.012 * height / 1.75; }

}  // namespace dresskit::mannequin
