#include "outfit.h"

#include <algorithm>

#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "garments.h"
#include "pattern_garment.h"
#include "measures.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail {

Outfit::Outfit(const MeshFile& body, const std::vector<GarmentFile>& garments)
    : body_file(body), garment_files(garments) {
  for (const GarmentFile& g : garments) fabrics.push_back(cloth::fabric_by_name(g.fabric.empty() ? "gray-interlock" : g.fabric));
}

const std::shared_ptr<const cloth::MeshDistance>& Outfit::body_distance() {
  if (!body_distance_) body_distance_ = std::make_shared<const cloth::MeshDistance>(result.body);
  return body_distance_;
}

const mesh::InsideTest& Outfit::inside() {
  if (!inside_) inside_.emplace(result.body);
  return *inside_;
}

void Outfit::forget_body() {
  body_distance_.reset();
  inside_.reset();
}

namespace {

/// Where two layers overlap (the outer one's vertices within `overlap` of the inner one), the 5th
/// and 50th percentiles of the distance from those vertices to the inner one's triangles [m], and
/// their count.
struct Gap {
  double p5 = 0.0, median = 0.0;
  int vertices = 0;
};
Gap layer_gap(const Eigen::MatrixX3d& outer, const Eigen::MatrixX3d& inner, const Eigen::MatrixX3i& inner_faces,
              double overlap) {
  const cloth::TriangleBvh tree(inner, inner_faces);
  std::vector<double> d;
  for (Eigen::Index i = 0; i < outer.rows(); ++i) {
    Eigen::Vector3d q;
    double d2 = 0.0;
    tree.closest(outer.row(i).transpose(), &q, &d2);
    if (d2 < overlap * overlap) d.push_back(std::sqrt(d2));
  }
  if (d.empty()) return {};
  std::sort(d.begin(), d.end());
  return {d[d.size() / 20], d[d.size() / 2], static_cast<int>(d.size())};
}

}  // namespace

void measure_dressed(Outfit& outfit) {
  DressResult& result = outfit.result;
  result.layer_crossings = crossings_between(result.garments, &DressedGarment::dressed);
  if (result.layer_crossings > 0)
    result.warnings.push_back("the garments cross each other " + counted(result.layer_crossings, "time", "times"));
  for (std::size_t k = 0; k < result.garments.size(); ++k) {
    DressedGarment& g = result.garments[k];
    g.crossings_dressed = cloth::count_intersections(g.dressed, g.mesh.F);
    g.inside_dressed = surface_fit(g.dressed, outfit.inside()).inside;
    const std::vector<double> strain = structural_strains(garment_cloth(g, outfit.fabrics[k]), g.dressed);
    if (!strain.empty()) {
      g.max_strain_dressed = std::max(0.0, strain.back());
      g.strain_p99_dressed = std::max(0.0, strain[strain.size() * 99 / 100]);
      g.springs_over_limit = static_cast<int>(strain.end() - std::upper_bound(strain.begin(), strain.end(), kOverLimit));
    }
    if (g.from_pattern && result.settled) measure_dressed_panels(g);
    g.warnings = dressed_warnings(g, result.padding_ran && result.padding_settle.stalled ? result.padding_settle.stopped_reason : "");
    if (k == 0) continue;
    const DressedGarment& inner = result.garments[k - 1];
    const Gap gap = layer_gap(g.dressed, inner.padded && inner.dressed_outer.rows() > 0 ? inner.dressed_outer : inner.dressed,
                              inner.mesh.F, 0.02);
    result.layer_gap_p5.push_back(gap.p5);
    result.layer_gap_median.push_back(gap.median);
    result.layer_gap_vertices.push_back(gap.vertices);
    result.layer_gap_asked.push_back(outfit.separation);
  }
}

}  // namespace dresskit::dressing::detail
