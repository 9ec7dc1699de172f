#include "commands/demo.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>

#include "commands/dress.h"
#include "dresskit/dressing/outputs.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "common/mesh.h"
#include "common/output_folder.h"

namespace dresskit::cli {

void DemoCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("demo", "the embedded default scene: a procedural mannequin and garments made on "
                                       "it (obj, ply, glb), the mannequin dressed in trousers and a t-shirt by "
                                       "the dressing pipeline (report.json, dressed.glb)");
  command->add_option("-o,--output", dir, "output directory")->required();
  command->add_option("--dress-seconds", seconds,
                      "simulated settling at most [s], up to 60 (default: the quality's, 0.5, 1 or 2 s)");
  command->add_flag("--no-settle", no_settle, "write the garments as made, not settled");
  option_with_default(command, "--quality", quality, "fast, balanced or accurate")
      ->check(CLI::IsMember({"fast", "balanced", "accurate"}));
  option_with_default(command, "--height", body.height, "mannequin height [m]");
  option_with_default(command, "--girth", body.girth, "mannequin girth scale");
  option_with_default(command, "--pose", pose, "a-pose or t-pose");
  option_with_default(command, "--edge", body.edge_length, "target edge length [m]");
  option_with_default(command, "--ease", garments.ease, "garment ease over the body [m]");
}

int DemoCommand::run() {
  body.pose = parse_pose(pose);
  garments.edge_length = body.edge_length;
  const BodyShape shape(body);  // checks the options before anything is made
  const OutputLock lock = check_output_folder(dir, {});
  check_options(garments);
  GarmentOptions over = garments;
  over.ease += over_ease;
  try {
    check_options(over);
  } catch (const InputError&) {
    throw InputError("--ease " + std::to_string(garments.ease) + ": the t-shirt, worn over the trousers, takes " +
                     std::to_string(over_ease) + " m more, and its ease would leave the garments' range");
  }
  if (!(seconds >= 0.0 && seconds <= 60.0))
    throw InputError("--dress-seconds " + std::to_string(seconds) + ": must be between 0 and 60");
  DressOptions options;
  options.quality = parse_quality(quality);
  options.settle = !no_settle;
  options.settle_seconds = seconds;

  // The scene: every garment kind made on the mannequin; the t-shirt with a little more ease, as it
  // is worn over the trousers.
  std::vector<NamedMesh> made;
  made.push_back({"mannequin", make_mannequin(shape)});
  for (GarmentKind kind : all_garment_kinds())
    made.push_back({to_string(kind), make_garment(shape, kind, kind == GarmentKind::tshirt ? over : garments)});
  auto mesh_named = [&](const std::string& name) {
    for (const NamedMesh& m : made)
      if (m.name == name) return m.mesh;
    throw std::logic_error("demo: no mesh " + name);
  };
  json meshes;
  for (const NamedMesh& m : made) {
    meshes[m.name] = topology_json(m.mesh);
    std::cout << m.name << ": " << m.mesh.num_vertices() << " vertices, " << m.mesh.num_faces() << " faces, "
              << meshes[m.name]["boundary_loops"] << " boundary loops\n";
  }

  // Dressed by the pipeline, as any user's meshes: the parts come with the meshes (no segmentation)
  // and the garments are made on this body (no placement).
  const MeshFile mannequin = MeshFile::given("mannequin", mesh_named("mannequin"));
  const std::vector<GarmentFile> outfit = {{MeshFile::given("trousers", mesh_named("trousers")), "11oz-black-denim"},
                                           {MeshFile::given("tshirt", mesh_named("tshirt")), "gray-interlock"}};
  Progress progress("settle", 1.0, "s simulated");
  show_progress("demo", options, progress);
  const DressResult r = dress(mannequin, outfit, options);
  progress.finish();
  if (r.settled && !r.settle.ok) {
    std::cerr << "dress-a-mesh: demo: settling stopped: " << r.settle.failure << " ("
              << write_failure_page(dir, r, "demo") << ")\n";
    return static_cast<int>(ExitCode::simulation_failed);
  }

  const json scene = {{"scene", "embedded default: procedural mannequin and garments made on it"},
                      {"mannequin_options",
                       {{"height_m", body.height},
                        {"girth", body.girth},
                        {"pose", body.pose == Pose::a_pose ? "a-pose" : "t-pose"},
                        {"edge_length_m", body.edge_length}}},
                      {"garment_options", {{"ease_m", garments.ease}, {"tshirt_ease_m", over.ease}}},
                      {"meshes", meshes}};
  write_folder(dir, [&](const fs::path& folder) {
    for (const NamedMesh& m : made)
      for (const char* ext : {"obj", "ply", "glb"}) save_mesh(m.mesh, (folder / (m.name + "." + ext)).string());
    DressOutputOptions o;
    o.report_extra = scene.dump();
    o.command = "demo";
    write_dress_outputs(folder.string(), r, o);
  });
  for (const DressedGarment& g : r.garments) {
    std::cout << g.name << " (" << g.fabric << "): " << g.crossings_dressed << " crossings, " << g.inside_dressed
              << " vertices inside the body, largest strain " << g.max_strain_dressed << "\n";
  }
  std::cout << "layers: " << r.layer_crossings << " crossings between them (" << (r.settled ? "settled" : "as made")
            << ")\n"
            << "wrote " << dir << " in " << r.seconds << " s\n";
  return 0;
}

}  // namespace dresskit::cli
