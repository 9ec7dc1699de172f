// Load: the body and every garment read from its file (or taken as given in memory); a garment
// given as a sewing pattern is cut, sewn around the body and welded here, so that every later stage
// sees meshes only.
#include <algorithm>

#include "../measures.h"
#include "../outfit.h"
#include "../pattern_garment.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::mesh;

namespace {

/// The mesh of a file, or the one given in memory checked as a file's would be.
TriangleMesh load_file(const MeshFile& f) {
  if (!f.mesh) return load_mesh(f.path, f.load);
  validate_mesh(*f.mesh, f.path);
  const Eigen::Index names = static_cast<Eigen::Index>(f.mesh->label_names.size());
  if (f.mesh->labels.size() > 0 &&
      (f.mesh->labels.size() != f.mesh->num_vertices() || f.mesh->labels.minCoeff() < -1 ||
       f.mesh->labels.maxCoeff() >= names))
    throw InputError(f.path + ": labels must be one per vertex, each -1 or the index of one of its " +
                     std::to_string(names) + " part names");
  return *f.mesh;
}

/// The two bodies a pattern is carried between part by part, each labelled once: its own body
/// (GarmentFile::pattern_body) and this one.
PartBodies part_bodies(Outfit& outfit, const GarmentFile& g, const DressOptions& options) {
  if (g.pattern_body.path.empty() && !g.pattern_body.mesh) return {};
  auto it = outfit.pattern_bodies.find(g.pattern_body.path);
  if (it == outfit.pattern_bodies.end()) {
    TriangleMesh from = load_file(g.pattern_body);
    const double tall = height(from);
    if (!(tall >= 0.5 && tall <= 2.5)) {
      const double in_file = tall / g.pattern_body.load.units.metres_per_unit;
      const std::string fits = units_for_body(in_file);
      throw InputError(g.pattern_body.path + ": the pattern's body is " + number(tall) + " m tall in units " +
                       g.pattern_body.load.units.name +
                       units_hint("--pattern-body-units", fits,
                                  "it would be " +
                                      number(fits.empty() ? 0.0 : in_file * Units::parse(fits).metres_per_unit) + " m"));
    }
    bool from_file = false;
    label(from, g.pattern_body, options.segmentation, from_file);
    it = outfit.pattern_bodies.emplace(g.pattern_body.path, std::move(from)).first;
  }
  if (!outfit.labelled_body) {
    outfit.labelled_body = outfit.result.body;
    outfit.labelled_body_parts =
        label(*outfit.labelled_body, outfit.body_file, options.segmentation, outfit.labelled_body_from_file);
  }
  return {&it->second, &*outfit.labelled_body};
}

/// A mesh beyond the size the stages handle in seconds (segmentation, the settle) is refused at
/// once, rather than left to run for minutes.
void refuse_larger(const mesh::TriangleMesh& m, const MeshFile& file, const char* what, int most) {
  if (most > 0 && m.num_faces() > most)
    throw InputError(file.path + ": " + counted(m.num_faces(), "triangle", "triangles") + ", more than the " +
                     std::to_string(most) + " a " + what + " may have: decimate it first");
}

}  // namespace

StageReport load(Outfit& outfit, const DressOptions& options) {
  DressResult& result = outfit.result;
  result.body = load_file(outfit.body_file);
  refuse_larger(result.body, outfit.body_file, "body", options.max_body_triangles);
  for (const GarmentFile& g : outfit.garment_files) {
    DressedGarment d;
    d.in_memory = g.file.mesh.has_value();
    d.name = d.in_memory ? g.file.path : stem(g.file.path);  // a mesh in memory keeps the name given
    d.file = g.file;  // with a mesh given in memory: kept, the output's vertex order is its
    for (const DressedGarment& other : result.garments)
      if (other.name == d.name)
        throw InputError(g.file.path + ": another garment is called " + d.name + "; outputs are named by it");
    d.fabric = g.fabric.empty() ? "gray-interlock" : g.fabric;
    d.padded = g.padded;
    if (is_pattern_garment(g)) {
      // Sewn around the body: a body in the wrong units or lying down is said before, not as a
      // seam that would not close minutes later.
      check_body_units(result.body, outfit.body_file, result.garments);
      const PartBodies parts = part_bodies(outfit, g, options);
      sew_pattern_garment(g, result.body, outfit.body_file.load, outfit.body_distance(), options, parts, d);
    } else {
      d.mesh = load_file(g.file);
      refuse_larger(d.mesh, g.file, "garment", options.max_garment_triangles);
    }
    result.garments.push_back(std::move(d));
  }
  const auto& files = outfit.garment_files;
  const int from_files =
      !outfit.body_file.mesh +
      static_cast<int>(std::count_if(files.begin(), files.end(), [](const GarmentFile& g) { return !g.file.mesh; }));
  const int meshes = 1 + static_cast<int>(files.size());
  const std::string what = from_files == meshes ? counted(meshes, "mesh", "meshes")
                           : from_files == 0    ? "every mesh given in memory"
                                                : std::to_string(from_files) + " of " + counted(meshes, "mesh", "meshes") +
                                                   " from files";
  return {from_files > 0, what};
}

}  // namespace dresskit::dressing::detail::stages
