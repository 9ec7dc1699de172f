#include "common/mesh.h"

#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"

using namespace dresskit::mesh;

namespace dresskit::cli {
using json = nlohmann::json;

void MeshArgument::add_to(CLI::App* command) {
  command->add_option("MESH", path, "input mesh (obj, ply, off, stl, gltf, glb, fbx)")->required();
  command->add_option("--units", units, "source length unit: m, dm, cm, mm or metres per unit")->capture_default_str();
  command->add_option("--up", up, "source up axis: +x, -x, +y, -y, +z, -z")->capture_default_str();
}

TriangleMesh MeshArgument::load() const {
  LoadOptions options;
  options.units = Units::parse(units);
  options.up = parse_up_axis(up);
  return load_mesh(path, options);
}

json topology_json(const TriangleMesh& mesh) {
  const TopologyReport t = analyse_topology(mesh);
  const Eigen::AlignedBox3d box = bounding_box(mesh);
  return {{"vertices", t.num_vertices},
          {"faces", t.num_faces},
          {"quads", mesh.quads.rows()},
          {"edges", t.num_edges},
          {"bounding_box_m", {{"min", {box.min().x(), box.min().y(), box.min().z()}},
                              {"max", {box.max().x(), box.max().y(), box.max().z()}}}},
          {"components", t.num_components},
          {"boundary_loops", t.num_boundary_loops},
          {"boundary_edges", t.num_boundary_edges},
          {"non_manifold_edges", t.num_non_manifold_edges},
          {"non_manifold_vertices", t.num_non_manifold_vertices},
          {"isolated_vertices", t.num_isolated_vertices},
          {"degenerate_faces", t.num_degenerate_faces},
          {"inconsistent_edges", t.num_inconsistent_edges},
          {"manifold", t.manifold},
          {"closed", t.closed},
          {"consistently_oriented", t.consistently_oriented},
          {"outward", t.outward},
          {"area_m2", t.area},
          {"volume_m3", t.closed ? json(t.signed_volume) : json(nullptr)},
          {"euler_characteristic", t.euler_characteristic}};
}

}  // namespace dresskit::cli
