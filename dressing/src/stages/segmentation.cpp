// Segmentation: the body cut into named parts, from its label file where one is given and by
// spectral segmentation otherwise; a body needs arms or legs among its parts. A garment takes its
// label file's parts; a garment mesh without one is labelled by the body parts its wearer's lie
// under (wearer), a sewn pattern by spectral segmentation.
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"

namespace dresskit::dressing::detail::stages {

namespace {

/// The same vertices and faces (a mesh that cleaning left as it was).
bool same_mesh(const mesh::TriangleMesh& a, const mesh::TriangleMesh& b) {
  return a.V.rows() == b.V.rows() && a.F.rows() == b.F.rows() && a.V == b.V && a.F == b.F;
}

std::string part_list(const std::vector<DressPart>& parts) {
  std::string s;
  for (const DressPart& p : parts) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

}  // namespace

StageReport segmentation(Outfit& outfit, const DressOptions& options) {
  DressResult& result = outfit.result;
  if (outfit.labelled_body && same_mesh(*outfit.labelled_body, result.body)) {  // labelled at load
    result.body.labels = outfit.labelled_body->labels;
    result.body.label_names = outfit.labelled_body->label_names;
    result.body_parts = outfit.labelled_body_parts;
    result.body_labels_from_file = outfit.labelled_body_from_file;
  } else {
    result.body_parts = label(result.body, outfit.body_file, options.segmentation, result.body_labels_from_file);
  }
  int segmented = !result.body_labels_from_file;
  bool limbs = false;
  for (const DressPart& p : result.body_parts)
    limbs = limbs || p.name.find("arm") != std::string::npos || p.name.find("leg") != std::string::npos;
  if (!limbs)
    throw InputError(outfit.body_file.path + ": does not look like a body: no arms or legs among its parts (" +
                     part_list(result.body_parts) + ")");
  int unlabelled = 0;
  for (DressedGarment& g : result.garments) {
    const bool labelled = !g.file.labels.empty() || (!g.mesh.label_names.empty() && g.mesh.labels.size() == g.mesh.num_vertices());
    if (!labelled && !g.from_pattern) {  // labelled by its wearer
      ++unlabelled;
      continue;
    }
    g.parts = label(g.mesh, g.file, options.segmentation, g.labels_from_file);
    segmented += !g.labels_from_file;
  }
  const int meshes = 1 + static_cast<int>(result.garments.size()) - unlabelled;
  const std::string later = unlabelled == 0 ? "" : "; " + counted(unlabelled, "garment", "garments") + " to be labelled by the wearer's parts";
  if (segmented == 0) return left_out("every mesh has part labels" + later);
  return ran((segmented == meshes ? std::string(meshes == 1 ? "the body cut into parts" : "every mesh cut into parts")
                                  : std::to_string(segmented) + " of " + std::to_string(meshes) +
                                        " meshes cut into parts (the others have part labels)") +
             later);
}

}  // namespace dresskit::dressing::detail::stages
