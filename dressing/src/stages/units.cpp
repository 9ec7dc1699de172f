// Units: a person is 0.5–2.5 m tall, stands on their feet and is one body, closed or nearly so; a
// garment is between a tenth and one and a half of its body.
#include <algorithm>
#include <map>

#include "../measures.h"
#include "../outfit.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/mesh/union_find.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::mesh;

namespace {

/// Pieces of the surface within the band [low, high] of heights: its vertices there joined by the
/// mesh's edges, counting pieces of at least a tenth of the band's vertices (a stray vertex of a
/// fold is none).
int pieces_between(const TriangleMesh& m, double low, double high) {
  const auto in = [&](int v) { return m.V(v, 1) >= low && m.V(v, 1) <= high; };
  UnionFind sets(m.num_vertices());
  int band = 0;
  for (int v = 0; v < m.num_vertices(); ++v) band += in(v);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      if (in(a) && in(b)) sets.unite(a, b);
    }
  std::map<int, int> size;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (in(v)) ++size[sets.find(v)];
  return static_cast<int>(std::count_if(size.begin(), size.end(), [&](const auto& p) { return 10 * p.second >= band; }));
}

/// A body standing on its head: across its lowest twentieth one piece (a head) and across its
/// highest two (feet, or legs). Raised hands put two pieces at the top of an upright body, but
/// then two legs stand at its bottom: only the clear case is refused.
void refuse_upside_down(const TriangleMesh& body, const MeshFile& file) {
  const double low = body.V.col(1).minCoeff(), high = body.V.col(1).maxCoeff(), h = high - low;
  const int bottom = pieces_between(body, low + 0.02 * h, low + 0.07 * h);
  const int top = pieces_between(body, high - 0.07 * h, high - 0.02 * h);
  if (bottom == 1 && top == 2)
    throw InputError(file.path + ": the body stands on its head along the up axis given (one piece at its bottom, "
                     "two at its top): give the file's up axis with --body-up (its opposite)");
}

/// Several bodies in one file: pieces of the mesh each at least 0.6 times as tall as the whole (a
/// body modelled in pieces has none so tall but its torso).
void refuse_several_bodies(const TriangleMesh& body, const MeshFile& file) {
  const double h = height(body);
  int bodies = 0;
  for (const TriangleMesh& piece : split_components(body)) bodies += height(piece) >= 0.6 * h;
  if (bodies > 1)
    throw InputError(file.path + ": holds " + std::to_string(bodies) +
                     " bodies (pieces each at least 0.6 times as tall as the whole); give one body a file");
}

}  // namespace

StageReport units(Outfit& outfit, const DressOptions&) {
  const DressResult& result = outfit.result;
  const double body_height = height(result.body);
  outfit.body_height = body_height;
  check_body_units(result.body, outfit.body_file, result.garments);
  refuse_several_bodies(result.body, outfit.body_file);
  refuse_upside_down(result.body, outfit.body_file);
  // A body is closed or nearly so (a scan may lack its soles or the top of its head); a garment's
  // openings (neck, cuffs, hem, waist) add up to more than its wearer's height.
  const double open = analyse_topology(result.body).boundary_length;
  if (open > body_height)
    throw InputError(outfit.body_file.path + ": does not look like a body: " + number(open) + " m of open edges on a mesh " +
                     number(body_height) + " m tall (a body is closed or nearly so; is it a garment?)");
  const auto fits_body = [&](double size) { return size >= 0.1 * body_height && size <= 1.5 * body_height; };
  for (const DressedGarment& g : result.garments) {
    const double size = bounding_box(g.mesh).sizes().maxCoeff();
    if (fits_body(size)) continue;
    const double in_file = size / g.file.load.units.metres_per_unit;
    std::string fits;
    for (const char* name : {"m", "dm", "cm", "mm"})
      if (fits.empty() && fits_body(in_file * Units::parse(name).metres_per_unit)) fits = name;
    throw InputError(g.file.path + ": the garment is " + number(size) + " m across in units " + g.file.load.units.name +
                     " on a body " + number(body_height) + " m tall" + units_hint("--garment-units", fits, "it fits"));
  }
  return ran("body " + number(body_height) + " m tall; garments " + std::to_string(result.garments.size()) +
             " within its size");
}

}  // namespace dresskit::dressing::detail::stages
