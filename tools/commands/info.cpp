#include "commands/info.h"

#include <iostream>

#include "dresskit/mesh/io.h"

namespace dresskit::cli {

void InfoCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("info", "print vertices, faces, bounding box, components, "
                                       "boundary loops, manifoldness and closedness");
  mesh.add_to(command);
  command->add_flag("--json", as_json, "print JSON");
}

int InfoCommand::run() {
  json j = topology_json(mesh.load());
  j["file"] = mesh.path;
  j["units"] = Units::parse(mesh.units).name;
  j["up"] = mesh.up;
  if (as_json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  const auto& b = j["bounding_box_m"];
  std::cout << "file: " << mesh.path << " (units " << j["units"].get<std::string>() << ", up " << mesh.up
            << "; converted to metres, +Y up)\n"
            << "vertices: " << j["vertices"] << "\nfaces: " << j["faces"] << " (" << j["quads"]
            << " quads in the source)\nbounding box [m]: min " << b["min"].dump() << " max " << b["max"].dump()
            << "\ncomponents: " << j["components"] << "\nboundary loops: " << j["boundary_loops"] << " ("
            << j["boundary_edges"] << " edges)\nmanifold: " << (j["manifold"].get<bool>() ? "yes" : "no") << " ("
            << j["non_manifold_edges"] << " non-manifold edges, " << j["non_manifold_vertices"]
            << " non-manifold vertices)\nclosed: " << (j["closed"].get<bool>() ? "yes" : "no")
            << "\nconsistently oriented: " << (j["consistently_oriented"].get<bool>() ? "yes" : "no")
            << "\noutward: " << (j["outward"].get<bool>() ? "yes" : "no")
            << "\nisolated vertices: " << j["isolated_vertices"] << "\ndegenerate faces: " << j["degenerate_faces"]
            << "\narea [m^2]: " << j["area_m2"] << "\n";
  return 0;
}

}  // namespace dresskit::cli
