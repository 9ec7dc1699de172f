#include "commands/dress.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>

#include "dresskit/cloth/fabric.h"
#include "dresskit/dressing/dress.h"
#include "dresskit/dressing/outputs.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/mesh/names.h"
#include "dresskit/pattern/pattern.h"
#include "common/output_folder.h"
#include "common/progress.h"

namespace dresskit::cli {

void DressCommand::add_to(CLI::App& app) {
  command = app.add_subcommand("dress", "dress BODY in GARMENT(s), given inside to outside: segment, place, "
                                        "settle; writes report.json, dressed.glb and each garment placed "
                                        "and dressed (docs/dressing.md)");
  command->add_option("BODY", body, "body mesh")->required();
  command->add_option("GARMENT", garments,
                      "garment meshes or sewing patterns (GarmentCode .json, docs/pattern.md), inside to outside")
      ->required();
  command->add_option("-o,--output", dir, "output directory")->required();
  command->add_option("--units", units, "length unit of every input: m, dm, cm, mm or metres per unit");
  command->add_option("--body-units", body_units, "length unit of BODY (overrides --units)");
  command->add_option("--garment-units", garment_units, "length unit of the garments (overrides --units)");
  option_with_default(command, "--up", up, "up axis of every input: +x, -x, +y, -y, +z, -z");
  command->add_option("--body-up", body_up, "up axis of BODY (overrides --up)");
  command->add_option("--garment-up", garment_up, "up axis of the garments (overrides --up)");
  // One value per --fabric, --padding or --garment-labels, each repeated per garment: a list after one
  // would take the body and garments given after it.
  command->add_option("--fabric", fabrics,
                      "fabric of each garment in order, one per --fabric (one: all of them); default gray-interlock")
      ->allow_extra_args(false)
      ->check(CLI::IsMember(fabric_names()));
  command->add_option("--padding", paddings,
                      "padding of each garment in order (one: all of them): none, or heat (a double layer "
                      "as thick as heat conduction gives for its fabric, docs/dressing.md); default none")
      ->allow_extra_args(false);
  command->add_option("--body-labels", body_labels, "part labels of the body (labels JSON): no segmentation");
  command->add_option("--garment-labels", garment_labels,
                      "part labels of each garment in order (one file: all of them, keyed by file stem)")
      ->allow_extra_args(false);
  command->add_option("--pattern-body", pattern_body,
                      "the body the sewing patterns are placed around (GarmentCode's body mesh): their panels "
                      "are carried to BODY part by part (docs/pattern.md); default: by the bodies' frames");
  command->add_option("--pattern-body-units", pattern_body_units,
                      "length unit of --pattern-body (overrides --units)");
  command->add_option("--pattern-body-labels", pattern_body_labels,
                      "part labels of --pattern-body (labels JSON): no segmentation of it");
  option_with_default(command, "--quality", quality, "fast, balanced or accurate")
      ->check(CLI::IsMember({"fast", "balanced", "accurate"}));
  option_with_default(command, "--layers", layers,
                      "given: worn inside to outside in the order given; inferred: from the "
                      "garments' kinds (bottoms under tops; of one kind, the one lying farther out)");
  command->add_flag("--no-settle", no_settle, "stop after placement (dressed = placed)");
  command->add_flag("--json", as_json, "print the report as JSON on stdout (nothing else)");
  command->add_flag("--segments", segments, "also write segments.ply: every mesh coloured by part");
}

namespace {
/// The units of one kind of input: its own option (named `option`) where given, else --units, else
/// metres. A bad value is named with the option that gave it.
LoadOptions load_options(const char* option, const std::string& specific, const std::string& common,
                         const char* up_option, const std::string& up_specific, const std::string& up) {
  LoadOptions o;
  const std::string value = !specific.empty() ? specific : !common.empty() ? common : "m";
  try {
    o.units = Units::parse(value);
  } catch (const InputError& e) {  // "units: '…' is not …", named by the option instead
    const std::string what = e.what();
    throw InputError(std::string(!specific.empty() ? option : "--units") + what.substr(what.find(':')));
  }
  try {
    o.up = parse_up_axis(!up_specific.empty() ? up_specific : up);
  } catch (const InputError& e) {  // "up axis: '…' is not …", named by the option
    const std::string what = e.what();
    throw InputError(std::string(!up_specific.empty() ? up_option : "--up") + what.substr(what.find(':')));
  }
  return o;
}

/// Picks the i-th of a per-garment option: one value serves every garment.
std::string per_garment(const std::vector<std::string>& values, std::size_t i, const char* option,
                        std::size_t garments) {
  if (values.empty()) return "";
  if (values.size() == 1) return values[0];
  if (values.size() != garments)
    throw InputError(std::string(option) + ": give one value, or one per garment (" + std::to_string(garments) +
                     "), not " + std::to_string(values.size()));
  return values[i];
}

}  // namespace

void show_progress(const std::string& command, DressOptions& options, Progress& progress) {
  // Sewing a pattern can take a minute, inside the load stage: a line when it starts, then a bar
  // (ended by the next line).
  auto sewing = std::make_shared<std::unique_ptr<Progress>>();
  options.on_stage = [command, sewing](const DressStage& s) {
    sewing->reset();
    char line[64];
    std::snprintf(line, sizeof line, "%7.2f s", s.seconds);
    std::cerr << command << ": " << s.name << (s.ran ? "" : " (left out)") << " " << line << "  " << s.reason << "\n";
  };
  options.on_settle = [&progress](double done, double total) {
    if (!progress.terminal()) return;
    progress.set_total(total);
    progress.update(done);
  };
  options.on_sew = [command, sewing](const std::string& garment, int pairs, double done, double total) {
    if (done == 0.0) {
      sewing->reset();
      std::cerr << command << ": sewing " << garment << " (" << pairs << " stitch pairs; a try sews for at most "
                << total << " s simulated)\n";
      *sewing = std::make_unique<Progress>("sew", total, "s simulated");
    } else if (*sewing && (*sewing)->terminal()) {
      (*sewing)->update(done);
    }
  };
}

std::string write_failure_page(const std::string& dir, const DressResult& r, const std::string& command,
                               const std::vector<std::string>& inputs, const std::string& refused) {
  try {
    write_folder(
        dir,
        [&](const fs::path& folder) {
          DressOutputOptions o;
          o.command = command;
          write_dress_failure_page(folder.string(), r, o, refused);
        },
        inputs);
  } catch (const std::exception& e) {
    return std::string("nothing written: ") + e.what();
  }
  return "only " + (fs::path(dir) / "report.html").string() + " written: " +
         (refused.empty() ? "what failed and the last good state" : "what was tried");
}

int DressCommand::run() {
  const MeshFile body_file = MeshFile::file(body, load_options("--body-units", body_units, units, "--body-up", body_up, up), body_labels);
  std::vector<GarmentFile> garment_files;
  std::set<std::string> stems;
  for (std::size_t i = 0; i < garments.size(); ++i) {
    GarmentFile g;
    g.file = MeshFile::file(garments[i], load_options("--garment-units", garment_units, units, "--garment-up", garment_up, up),
                            per_garment(garment_labels, i, "--garment-labels", garments.size()));
    g.fabric = per_garment(fabrics, i, "--fabric", garments.size());
    const std::string padding = per_garment(paddings, i, "--padding", garments.size());
    if (padding != "" && padding != "none" && padding != "heat")
      throw InputError("--padding: '" + padding + "' is not none or heat");
    g.padded = padding == "heat";
    if (!pattern_body.empty())
      g.pattern_body = MeshFile::file(pattern_body, load_options("--pattern-body-units", pattern_body_units, units, "--up", "", up), pattern_body_labels);
    if (!stems.insert(fs::path(garments[i]).stem().string()).second)
      throw InputError(garments[i] + ": another garment has the same file name; outputs are named by it");
    garment_files.push_back(g);
  }
  // Options for the patterns' body that nothing uses are said, not silently dropped.
  const bool any_pattern = std::any_of(garments.begin(), garments.end(), pattern::is_pattern_file);
  if (!pattern_body.empty() && !any_pattern)
    std::cerr << "dress-a-mesh: warning: --pattern-body " << pattern_body
              << ": no garment is a sewing pattern (.json); not used\n";
  if (no_settle && std::find(paddings.begin(), paddings.end(), "heat") != paddings.end())
    std::cerr << "dress-a-mesh: warning: --padding heat is settled with the garment; not used with --no-settle\n";
  if (pattern_body.empty() && (!pattern_body_units.empty() || !pattern_body_labels.empty())) {
    const std::string given = !pattern_body_units.empty() && !pattern_body_labels.empty()
                                  ? "--pattern-body-units and --pattern-body-labels apply"
                              : !pattern_body_units.empty() ? "--pattern-body-units applies"
                                                            : "--pattern-body-labels applies";
    std::cerr << "dress-a-mesh: warning: " << given << " to --pattern-body, which is not given; not used\n";
  }
  std::vector<std::string> inputs = garments;
  inputs.push_back(body);
  inputs.push_back(body_labels);
  inputs.push_back(pattern_body);
  inputs.push_back(pattern_body_labels);
  inputs.insert(inputs.end(), garment_labels.begin(), garment_labels.end());
  // The files the run writes into dir, none of which may be an input.
  std::vector<std::string> outputs = {"report.json", "report.html", "dressed.glb", "segments.ply"};
  for (const std::string& s : stems)
    for (const char* kind : {".placed.obj", ".dressed.obj", ".outer.obj"}) outputs.push_back(s + kind);
  const OutputLock lock = check_output_folder(dir, inputs, outputs);
  DressOptions options;
  options.quality = parse_quality(quality);
  options.settle = !no_settle;
  if (layers != "given" && layers != "inferred")
    throw InputError("--layers: '" + layers + "' is not given or inferred");
  options.infer_layers = layers == "inferred";
  Progress progress("settle", 1.0, "s simulated");
  show_progress("dress", options, progress);
  DressResult r;
  try {
    r = dress(body_file, garment_files, options);
  } catch (const DressRefused& e) {
    progress.finish();
    throw InputError(std::string(e.what()) + " (" + write_failure_page(dir, e.result(), "dress", inputs, e.what()) + ")");
  }
  progress.finish();
  for (const DressedGarment& g : r.garments)
    for (const std::string& w : g.pattern.warnings) std::cerr << "dress-a-mesh: warning: " << w << "\n";
  std::string report;
  if ((r.settled && !r.settle.ok) || (r.padding_ran && !r.padding_settle.ok && !r.padding_settle.stalled)) {
    const std::string failure = !r.settle.ok ? r.settle.failure : "padding: " + r.padding_settle.failure;
    std::cerr << "dress-a-mesh: " << body << ": settling stopped: " << failure << " ("
              << write_failure_page(dir, r, "dress", inputs) << ")\n";
    return static_cast<int>(ExitCode::simulation_failed);
  }
  for (const std::string& w : r.settle.warnings) std::cerr << "dress-a-mesh: warning: " << w << "\n";
  for (const std::string& w : r.padding_settle.warnings) std::cerr << "dress-a-mesh: warning: padding " << w << "\n";
  for (const std::string& w : r.warnings) std::cerr << "dress-a-mesh: warning: " << w << "\n";
  for (const DressedGarment& g : r.garments)
    for (const std::string& w : g.warnings) std::cerr << "dress-a-mesh: warning: " << w << "\n";
  write_folder(
      dir,
      [&](const fs::path& folder) {
        DressOutputOptions o;
        o.segments = segments;
        report = write_dress_outputs(folder.string(), r, o);
      },
      inputs);
  const json written = json::parse(report);
  const json& write_stage = written["stages"].back();  // timed by the writer: its line like the others'
  options.on_stage(DressStage{write_stage["name"], write_stage["ran"], write_stage["seconds"], write_stage["reason"]});
  if (as_json) {
    std::cout << report;
  } else {
    for (const DressedGarment& g : r.garments) {
      std::cout << g.name << ": " << (g.placed_by_placement ? "placed" : "already on the body") << ", "
                << counted(g.crossings_dressed, "crossing", "crossings") << ", "
                << counted(g.inside_dressed, "vertex", "vertices") << " inside, largest strain " << g.max_strain_dressed
                << " (" << counted(g.springs_over_limit, "spring", "springs") << " over " << kOverLimit << ")";
      if (g.from_pattern)
        std::cout << ", sewn from " << counted(static_cast<long long>(g.pattern.panels.size()), "panel", "panels") << " ("
                  << counted(g.pattern.stitches, "seam", "seams") << ", largest gap " << 1e3 * g.pattern.max_gap << " mm)";
      std::cout << "\n";
    }
    std::cout << "wrote " << dir << " in " << written["seconds"].get<double>() << " s\n";
  }
  return 0;
}

}  // namespace dresskit::cli
