#pragma once
// Small measures and checks that several dressing stages share: how a garment lies on the body, a
// cloth's strains, a body's height and units, parts from labels or segmentation, numbers in text.
#include <string>
#include <vector>

#include "dresskit/cloth/cloth_model.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/mesh/inside.h"

namespace dresskit::dressing::detail {

/// `value` with `digits` significant digits ("%.*g").
std::string number(double value, int digits = 3);
/// A path's file name without its extension.
std::string stem(const std::string& path);
/// Extent along +Y [m].
double height(const mesh::TriangleMesh& m);

/// How a garment's vertices lie against the body: mean distance to its surface [m] and the
/// vertices deeper than 2 mm inside.
struct SurfaceFit {
  double mean_distance = 0.0;
  int inside = 0;
};
SurfaceFit surface_fit(const Eigen::MatrixX3d& V, const mesh::InsideTest& body);

/// A garment that already lies on the body: few vertices inside it, near its surface on average
/// (DressOptions::fit_inside, fit_distance).
bool on_body(const SurfaceFit& fit, Eigen::Index vertices, double body_height, const DressOptions& options);

/// Structural strains of a cloth model at positions x (quad diagonals are shear springs), sorted.
std::vector<double> structural_strains(const cloth::ClothModel& m, const Eigen::MatrixX3d& x);

/// How a mesh's size would fit in other units, after what its size is: ": give its units (OPTION)"
/// when no units fit, else "; with OPTION FITS THEN".
std::string units_hint(const std::string& option, const std::string& fits, const std::string& then);

/// A body of a person's height (0.5–2.5 m) standing along its file's up axis; otherwise an
/// InputError naming the axis, or the units, that would make it one (one --units for all where the
/// garment meshes so far are in the body's units and fit it as they are).
void check_body_units(const mesh::TriangleMesh& body, const MeshFile& body_file,
                      const std::vector<DressedGarment>& garments);

/// Parts from a label file or given with the mesh (`from_file` true), or by spectral segmentation;
/// sets the mesh's labels.
std::vector<DressPart> label(mesh::TriangleMesh& m, const MeshFile& f, const segmentation::SegmentationOptions& options,
                             bool& from_file);

}  // namespace dresskit::dressing::detail
