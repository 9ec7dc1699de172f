// dress-a-mesh: the command-line front of dresskit. Exit codes: docs/cli.md.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <cmath>
#include <iostream>
#include <limits>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/scene/garments.h"
#include "dresskit/scene/mannequin.h"
#include "dress_command.h"
#include "segment_command.h"
#include "simulate_command.h"
#include "align_command.h"
#include "demo_command.h"
#include "mesh_json.h"
#include "thickness_command.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace dresskit;
using dresskit::cli::topology_json;

namespace {

struct LoadArgs {
  std::string path, units = "m", up = "+y";
  void add_to(CLI::App* cmd) {
    cmd->add_option("MESH", path, "input mesh (obj, ply, off, stl, gltf, glb, fbx)")->required();
    cmd->add_option("--units", units, "source length unit: m, dm, cm, mm or metres per unit")
        ->capture_default_str();
    cmd->add_option("--up", up, "source up axis: +x, -x, +y, -y, +z, -z")->capture_default_str();
  }
  TriangleMesh load() const {
    LoadOptions options;
    options.units = Units::parse(units);
    options.up = parse_up_axis(up);
    return load_mesh(path, options);
  }
};

void print_topology(const json& j) {
  const auto& b = j["bounding_box_m"];
  std::cout << "vertices: " << j["vertices"] << "\nfaces: " << j["faces"] << " (" << j["quads"]
            << " quads in the source)\nbounding box [m]: min " << b["min"].dump() << " max "
            << b["max"].dump() << "\ncomponents: " << j["components"]
            << "\nboundary loops: " << j["boundary_loops"] << " (" << j["boundary_edges"]
            << " edges)\nmanifold: " << (j["manifold"].get<bool>() ? "yes" : "no") << " ("
            << j["non_manifold_edges"] << " non-manifold edges, " << j["non_manifold_vertices"]
            << " non-manifold vertices)\nclosed: " << (j["closed"].get<bool>() ? "yes" : "no")
            << "\nconsistently oriented: " << (j["consistently_oriented"].get<bool>() ? "yes" : "no")
            << "\noutward: " << (j["outward"].get<bool>() ? "yes" : "no")
            << "\nisolated vertices: " << j["isolated_vertices"]
            << "\ndegenerate faces: " << j["degenerate_faces"] << "\narea [m^2]: " << j["area_m2"]
            << "\n";
}

// Refuses an output path that is one of the inputs, or whose extension cannot be written.
void check_output(const std::string& out, const std::string& input) {
  std::error_code ec;
  if (fs::exists(out, ec) && fs::equivalent(out, input, ec)) {
    throw InputError(out + ": refusing to overwrite the input");
  }
  if (!is_saveable(out)) {
    std::string list;
    for (const auto& e : saveable_extensions()) list += (list.empty() ? "" : ", ") + e;
    throw InputError(out + ": cannot write '" + fs::path(out).extension().string() +
                     "' files (supported: " + list + ")");
  }
  const fs::path dir = fs::path(out).parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec)) throw OutputError(out + ": no such directory");
}

int run_info(const LoadArgs& args, bool as_json) {
  const TriangleMesh mesh = args.load();
  json j = topology_json(mesh);
  j["file"] = args.path;
  j["units"] = Units::parse(args.units).name;
  j["up"] = args.up;
  if (as_json) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "file: " << args.path << " (units " << j["units"].get<std::string>() << ", up "
              << args.up << "; converted to metres, +Y up)\n";
    print_topology(j);
  }
  return 0;
}

int run_clean(const LoadArgs& args, const std::string& out, const CleanupOptions& options,
              bool as_json) {
  check_output(out, args.path);
  const TriangleMesh mesh = args.load();
  const CleanupResult r = cleanup_mesh(mesh, options);
  validate_mesh(r.mesh, args.path + " after cleanup");  // never write an empty or broken result
  save_mesh(r.mesh, out);
  if (as_json) {
    json j = {{"input", args.path}, {"output", out}, {"changes", r.changes()},
              {"result", topology_json(r.mesh)}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "cleaned " << args.path << " -> " << out << "\n";
    if (r.changes().empty()) std::cout << "  nothing to fix\n";
    for (const auto& line : r.changes()) std::cout << "  " << line << "\n";
    const TopologyReport t = analyse_topology(r.mesh);
    std::cout << "  result: " << t.num_vertices << " vertices, " << t.num_faces << " faces, "
              << t.num_components << " components, " << t.num_boundary_loops << " boundary loops, "
              << (t.manifold ? "manifold" : "NOT manifold") << ", "
              << (t.closed ? (t.outward ? "closed and outward" : "closed") : "open") << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dress-a-mesh: dress 3D human bodies in garments (dresskit)"};
  app.set_version_flag("--version", std::string("dress-a-mesh ") + DRESSKIT_VERSION);
  app.require_subcommand(1);

  LoadArgs info_args, clean_args;
  bool info_json = false, clean_json = false;
  auto* info = app.add_subcommand("info", "print vertices, faces, bounding box, components, "
                                          "boundary loops, manifoldness and closedness");
  info_args.add_to(info);
  info->add_flag("--json", info_json, "print JSON");

  std::string clean_out;
  CleanupOptions clean_options;
  auto* clean = app.add_subcommand("clean", "repair a mesh and write it; prints what it fixed");
  clean_args.add_to(clean);
  clean->add_option("-o,--output", clean_out, "output mesh (obj, ply, off, stl, glb, gltf, fbx)")->required();
  clean->add_option("--remesh", clean_options.remesh_edge_length,
                    "isotropic remeshing to this edge length [m, after unit conversion]")
      ->check(CLI::PositiveNumber);
  clean->add_flag("--fill-holes", clean_options.fill_holes, "fill small holes");
  clean->add_option("--max-hole-edges", clean_options.max_hole_edges,
                    "largest hole to fill [boundary edges]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  clean->add_flag("--largest-component", clean_options.keep_largest_component,
                  "keep only the largest connected component");
  clean->add_flag("--json", clean_json, "print JSON");

  cli::DemoCommand demo;
  demo.add_to(app);
  cli::SimulateCommand simulate;
  simulate.add_to(app);
  cli::DressCommand dress;
  dress.add_to(app);

  cli::ThicknessCommand thickness;
  thickness.add_to(app);
  cli::SegmentCommand segment;
  segment.add_to(app);
  cli::AlignCommand align;
  align.add_to(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "dress-a-mesh: " << e.what() << " (see --help)\n";
    return static_cast<int>(ExitCode::usage);
  }

  try {
    if (*info) return run_info(info_args, info_json);
    if (*clean) return run_clean(clean_args, clean_out, clean_options, clean_json);
    if (*simulate.command) return simulate.run();
    if (*dress.command) return dress.run();
    if (*thickness.command) return thickness.run();
    if (*segment.command) return segment.run();
    if (*align.command) return align.run();
    if (*demo.command) return demo.run();
  } catch (const CLI::ValidationError& e) {
    std::cerr << "dress-a-mesh: " << e.what() << " (see --help)\n";
    return static_cast<int>(ExitCode::usage);
  } catch (const InputError& e) {
    std::cerr << "dress-a-mesh: " << e.what() << "\n";
    return static_cast<int>(ExitCode::bad_input);
  } catch (const OutputError& e) {
    std::cerr << "dress-a-mesh: " << e.what() << "\n";
    return static_cast<int>(ExitCode::output_failed);
  } catch (const std::exception& e) {
    std::cerr << "dress-a-mesh: internal error: " << e.what() << "\n";
    return static_cast<int>(ExitCode::internal_error);
  }
  return static_cast<int>(ExitCode::internal_error);
}
