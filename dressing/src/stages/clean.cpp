// Clean: only the meshes with defects the later stages cannot take are repaired.
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::mesh;

namespace {

/// What makes a mesh unfit for the later stages, or "" when nothing does: degenerate faces, edges
/// with more than two faces, faces turned against their neighbours. (A pinched vertex or a vertex
/// used by no face is harmless.)
std::string defects(const TriangleMesh& m) {
  const TopologyReport t = analyse_topology(m);
  std::string why;
  auto add = [&](int count, const char* what) {
    if (count > 0) why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + what;
  };
  add(t.num_degenerate_faces, "degenerate faces");
  add(t.num_non_manifold_edges, "edges with more than two faces");
  add(t.num_inconsistent_edges, "edges between faces turned against each other");
  return why;
}

}  // namespace

StageReport clean(Outfit& outfit, const DressOptions&) {
  std::string done;
  auto clean_mesh = [&](TriangleMesh& m, const std::string& name) {
    const std::string why = defects(m);
    if (why.empty()) return;
    CleanupOptions o;
    o.stitch_borders = false;  // a garment's openings stay open
    m = cleanup_mesh(m, o).mesh;
    done += (done.empty() ? "" : "; ") + name + ": " + why;
  };
  clean_mesh(outfit.result.body, stem(outfit.body_file.path));
  if (!done.empty()) outfit.forget_body();  // its distance and inside test, if built, are of the body as loaded
  for (DressedGarment& g : outfit.result.garments) clean_mesh(g.mesh, g.name);
  if (done.empty()) return left_out("no mesh has degenerate faces, non-manifold or inconsistent edges");
  return ran(done);
}

}  // namespace dresskit::dressing::detail::stages
