#include "commands/pattern.h"

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/output_folder.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/pattern/curves.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/pattern/svg.h"

namespace dresskit::cli {

void PatternCommand::add_to(CLI::App& app) {
  command =
      app.add_subcommand("pattern",
                         "read and check a sewing pattern (GarmentCode JSON), draw it and cut its "
                         "panels into triangles; writes pattern.svg, the panels flat and placed in "
                         "3D, and pattern.json (docs/pattern.md)");
  command->add_option("PATTERN", path, "pattern file (GarmentCode *_specification.json)")
      ->required();
  command->add_option("-o,--output", output, "output directory")->required();
  command->add_option("--edge", edge, "triangle edge length [m]")->capture_default_str();
  command
      ->add_option("--length-ratio", length_ratio,
                   "warn about stitched edges whose lengths differ by more than this ratio")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e9));
  command->add_flag("--json", as_json, "print the summary as JSON on stdout");
}

int PatternCommand::run() {
  if (!(edge > 0.0 && edge < 1e3))  // NaN too
    throw InputError("--edge: " + std::to_string(edge) + " is not a positive length below 1000 m");
  const OutputLock lock = check_output_folder(output, {path});  // the output folder is the pattern, or cannot be: before any work
  pattern::ReadOptions read;
  read.max_length_ratio = length_ratio;
  const pattern::Pattern p = pattern::read_pattern(path, read);
  for (const std::string& w : p.warnings) std::cerr << "dress-a-mesh: warning: " << w << "\n";
  pattern::CutOptions cut_options;
  cut_options.edge_length = edge;
  const pattern::CutPattern cut = pattern::cut_pattern(p, cut_options);

  json panels = json::array();
  for (std::size_t i = 0; i < p.panels.size(); ++i) {
    json edges = json::array();
    for (std::size_t e = 0; e < p.panels[i].edges.size(); ++e)
      edges.push_back({{"length_m", pattern::edge_length(p.panels[i], int(e))},
                       {"points", cut.edge_vertices[i][e].size()}});
    int vertices = int((cut.panel_of_vertex.array() == int(i)).count());
    int faces = int((cut.panel_of_face.array() == int(i)).count());
    panels.push_back({{"name", p.panels[i].name},
                      {"area_m2", cut.outline_area[i]},
                      {"triangle_area_m2", cut.triangle_area[i]},
                      {"vertices", vertices},
                      {"triangles", faces},
                      {"edges", edges}});
  }
  const json summary = {{"pattern", p.name},
                        {"input", path},
                        {"units_in_meter", p.units_in_meter},
                        {"edge_length_m", edge},
                        {"panels", panels},
                        {"stitches", p.stitches.size()},
                        {"stitch_pairs", cut.stitch_pairs.size()},
                        {"vertices", cut.placed.rows()},
                        {"triangles", cut.faces.rows()},
                        {"warnings", p.warnings},
                        {"seconds_cutting", cut.seconds}};
  write_folder(output,
               [&](const fs::path& folder) {
                 pattern::write_pattern_svg((folder / "pattern.svg").string(), p);
                 save_mesh(pattern::flat_mesh(p, cut), (folder / (p.name + ".flat.obj")).string());
                 save_mesh(pattern::placed_mesh(p, cut),
                           (folder / (p.name + ".placed.obj")).string());
                 write_file_atomically((folder / "pattern.json").string(), summary.dump(2) + "\n");
               },
               {path});
  if (as_json) {
    std::cout << summary.dump(2) << "\n";
  } else {
    std::cout << p.name << ": " << p.panels.size() << " panels, " << p.stitches.size()
              << " stitches, " << cut.faces.rows() << " triangles at " << edge << " m; wrote "
              << output << "\n";
  }
  return 0;
}

}  // namespace dresskit::cli
