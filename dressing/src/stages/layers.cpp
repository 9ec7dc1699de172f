// Layers: the garments ordered inside to outside, as given or inferred from their kinds (bottoms
// under tops; of one kind, the one lying farther out where both already lie on the body, else one
// without legs or a skirt over one with, else the larger outside). Before placement, which pushes
// outer pieces out of inner ones.
#include <iterator>
#include <unordered_map>

#include "../garments.h"
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/cloth/geometry.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::dressing::detail::stages {

namespace {

/// The body cells [m] in which layers inferred for garments on the body compare their heights.
constexpr double kLayerCell = 0.02;

/// A garment's height over the body: its vertices' mean distance to the body in each cell of
/// `cell` [m] that their nearest body points fall in.
std::unordered_map<std::int64_t, double> height_over_body(const Eigen::MatrixX3d& V, const cloth::MeshDistance& body,
                                                          double cell) {
  std::unordered_map<std::int64_t, std::pair<double, int>> sum;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    Eigen::Vector3d outward;
    const Eigen::Vector3d p = V.row(i).transpose();
    const double d = body.distance(p, &outward);
    auto& s = sum[cloth::grid_cell_key(p - d * outward, cell)];
    s.first += d;
    ++s.second;
  }
  std::unordered_map<std::int64_t, double> height;
  for (const auto& [key, s] : sum) height[key] = s.first / s.second;
  return height;
}

/// Which of two garments lies outside the other where both cover the body: +1 when `a` lies
/// farther from it in more of the cells both cover, −1 when `b` does, 0 when they share no cell
/// or tie.
int lies_outside(const std::unordered_map<std::int64_t, double>& a, const std::unordered_map<std::int64_t, double>& b) {
  int votes = 0;
  for (const auto& [key, h] : a) {
    const auto it = b.find(key);
    if (it != b.end() && h != it->second) votes += h > it->second ? 1 : -1;
  }
  return (votes > 0) - (votes < 0);
}

/// The garments' order inside to outside, inferred from their kinds.
std::vector<std::size_t> inferred_order(Outfit& outfit, const DressOptions& options) {
  const std::vector<DressedGarment>& garments = outfit.result.garments;
  const std::size_t n = garments.size();
  std::vector<int> kind(n), legs(n);
  std::vector<double> area(n);
  std::vector<std::unordered_map<std::int64_t, double>> height(n);  // empty: not on the body
  for (std::size_t k = 0; k < n; ++k) {
    const DressedGarment& g = garments[k];
    kind[k] = is_top(g) ? 1 : 0;
    legs[k] = covers_legs(g) ? 1 : 0;
    area[k] = mesh::analyse_topology(g.mesh).area;
    if (on_body(surface_fit(g.mesh.V, outfit.inside()), g.mesh.num_vertices(), outfit.body_height, options))
      height[k] = height_over_body(g.mesh.V, *outfit.body_distance(), kLayerCell);
  }
  const auto outside = [&](std::size_t a, std::size_t b) {
    if (kind[a] != kind[b]) return kind[a] > kind[b];
    const int over = lies_outside(height[a], height[b]);
    if (over != 0) return over > 0;
    if (legs[a] != legs[b]) return legs[a] < legs[b];  // a suit or a dress under a top
    return area[a] > area[b];
  };
  // Insertion: a garment goes after every garment it lies outside (the relation need not be
  // transitive for three garments on the body, so no sort that assumes it).
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < n; ++k) {
    auto at = order.end();
    while (at != order.begin() && outside(*std::prev(at), k)) --at;
    order.insert(at, k);
  }
  return order;
}

}  // namespace

StageReport layers(Outfit& outfit, const DressOptions& options) {
  std::vector<DressedGarment>& garments = outfit.result.garments;
  if (options.infer_layers && garments.size() > 1) {
    std::vector<DressedGarment> ordered;
    std::vector<cloth::Fabric> fabrics;
    std::vector<std::optional<alignment::CarriedGarment>> carried;
    for (std::size_t k : inferred_order(outfit, options)) {
      ordered.push_back(std::move(garments[k]));
      fabrics.push_back(outfit.fabrics[k]);
      carried.push_back(std::move(outfit.carried[k]));
    }
    garments = std::move(ordered);
    outfit.fabrics = std::move(fabrics);
    outfit.carried = std::move(carried);
  }
  for (std::size_t k = 0; k < garments.size(); ++k) garments[k].layer = static_cast<int>(k);
  if (garments.size() < 2) return left_out("one garment: no layers to order");
  std::string order;
  for (const DressedGarment& g : garments)
    order += (order.empty() ? "" : " < ") + g.name + (options.infer_layers ? (is_top(g) ? " (top)" : " (bottom)") : "");
  return ran(options.infer_layers ? "inside to outside, inferred from the garments' kinds (of one kind: the one lying "
                                    "farther out where both lie on the body, else one without legs or a skirt over one "
                                    "with, else the larger): " + order
                                  : "inside to outside as given: " + order);
}

}  // namespace dresskit::dressing::detail::stages
