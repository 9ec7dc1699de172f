#include "commands/clean.h"

#include <filesystem>
#include <iostream>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::cli {

void CleanCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("clean", "repair a mesh and write it; prints what it fixed");
  mesh.add_to(command);
  command->add_option("-o,--output", output, "output mesh (obj, ply, off, stl, glb, gltf, fbx)")->required();
  command->add_option("--remesh", options.remesh_edge_length,
                      "isotropic remeshing to this edge length [m, after unit conversion]")
      ->check(positive_number());
  command->add_flag("--fill-holes", options.fill_holes, "fill small holes");
  command->add_option("--max-hole-edges", options.max_hole_edges, "largest hole to fill [boundary edges]")
      ->capture_default_str()
      ->check(positive_number());
  command->add_flag("--largest-component", options.keep_largest_component,
                    "keep only the largest connected component");
  command->add_flag("--json", as_json, "print JSON");
}

namespace {
// Refuses an output path that is the input, whose extension cannot be written, or that lies under
// a file (its missing folders are made when the result is written).
void check_output(const std::string& out, const std::string& input) {
  std::error_code ec;
  if (fs::exists(out, ec) && fs::equivalent(out, input, ec)) throw InputError(out + ": refusing to overwrite the input");
  if (!is_saveable(out)) {
    std::string list;
    for (const auto& e : saveable_extensions()) list += (list.empty() ? "" : ", ") + e;
    throw InputError(out + ": cannot write '" + fs::path(out).extension().string() + "' files (supported: " + list + ")");
  }
  for (fs::path dir = fs::path(out).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::exists(dir, ec)) {
      if (!fs::is_directory(dir, ec)) throw OutputError(out + ": " + dir.string() + " is not a directory");
      break;
    }
    if (dir == dir.parent_path()) break;
  }
}
}  // namespace

int CleanCommand::run() {
  check_output(output, mesh.path);
  const CleanupResult r = cleanup_mesh(mesh.load(), options);
  validate_mesh(r.mesh, mesh.path + " after cleanup");  // never write an empty or broken result
  // The missing folders are made, and removed again if the mesh cannot be written.
  fs::path made;
  std::error_code ec;
  for (fs::path dir = fs::path(output).parent_path(); !dir.empty() && !fs::exists(dir, ec); dir = dir.parent_path()) {
    made = dir;
    if (dir == dir.parent_path()) break;
  }
  if (!made.empty() && (!fs::create_directories(fs::path(output).parent_path(), ec) || ec))
    throw OutputError(output + ": cannot make the folder " + fs::path(output).parent_path().string() +
                      (ec ? ": " + ec.message() : ""));
  try {
    save_mesh(r.mesh, output);
  } catch (...) {
    if (!made.empty()) fs::remove_all(made, ec);
    throw;
  }
  if (as_json) {
    const json j = {{"input", mesh.path}, {"output", output}, {"changes", r.changes()}, {"result", topology_json(r.mesh)}};
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "cleaned " << mesh.path << " -> " << output << "\n";
  if (r.changes().empty()) std::cout << "  nothing to fix\n";
  for (const auto& line : r.changes()) std::cout << "  " << line << "\n";
  const TopologyReport t = analyse_topology(r.mesh);
  std::cout << "  result: " << t.num_vertices << " vertices, " << t.num_faces << " faces, " << t.num_components
            << " components, " << t.num_boundary_loops << " boundary loops, "
            << (t.manifold ? "manifold" : "NOT manifold") << ", "
            << (t.closed ? (t.outward ? "closed and outward" : "closed") : "open") << "\n";
  return 0;
}

}  // namespace dresskit::cli
