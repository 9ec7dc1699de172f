#include "dresskit/dressing/dress.h"

#include <chrono>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/names.h"
#include "measures.h"
#include "outfit.h"

namespace dresskit::dressing {

using namespace detail;

MeshFile MeshFile::file(std::string path, mesh::LoadOptions load, std::string labels) {
  MeshFile f;
  f.path = std::move(path);
  f.load = std::move(load);
  f.labels = std::move(labels);
  return f;
}

MeshFile MeshFile::given(std::string name, mesh::TriangleMesh mesh) {
  MeshFile f;
  f.path = std::move(name);
  f.mesh = std::move(mesh);
  return f;
}

const NameTable<DressQuality> kQualities = {{"fast", DressQuality::fast}, {"balanced", DressQuality::balanced},
                                            {"accurate", DressQuality::accurate}};
DressQuality parse_quality(const std::string& text) { return parse_name(text, kQualities, "quality"); }
std::string to_string(DressQuality quality) { return name_of(quality, kQualities); }

namespace {

using Clock = std::chrono::steady_clock;

/// The pipeline: each stage reads what the stages before it left in the outfit (stages/*.cpp).
struct StageEntry {
  const char* name;
  StageReport (*run)(Outfit&, const DressOptions&);
};
constexpr StageEntry kStages[] = {
    {"load", stages::load},                  // meshes read; sewing patterns cut, sewn and welded
    {"clean", stages::clean},                // meshes the later stages cannot take repaired
    {"units", stages::units},                // a body of a person's height, garments of its size
    {"segmentation", stages::segmentation},  // the body cut into named parts
    {"wearer", stages::wearer},              // where each garment's wearer stood; its parts
    {"layers", stages::layers},              // garments ordered inside to outside
    {"placement", stages::placement},        // garments not on the body carried onto it
    {"thickness", stages::thickness},        // each cloth's thickness; padding's by heat conduction
    {"grading", stages::grading},            // outer garments moved out over inner ones
    {"settle", stages::settle},              // the garments settled on the body in the simulator
    {"padding", stages::padding},            // padded garments grown into double layers
};

}  // namespace

DressResult dress(const MeshFile& body_file, const std::vector<GarmentFile>& garment_files, const DressOptions& options) {
  const auto start = Clock::now();
  if (garment_files.empty()) throw InputError("dress: no garment given");
  if (!(options.settle_seconds >= 0.0 && options.settle_seconds < 1e6))
    throw InputError("settle seconds: " + number(options.settle_seconds) + " is not between 0 and 1e6");
  Outfit outfit(body_file, garment_files);
  DressResult& result = outfit.result;
  result.body_file = body_file;
  result.body_file.mesh.reset();
  result.quality = options.quality;
  for (const StageEntry& entry : kStages) {
    const auto begun = Clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - begun).count(); };
    StageReport report;
    try {
      report = entry.run(outfit, options);
    } catch (const InputError& e) {
      if (&entry == &kStages[0]) throw;  // the meshes could not be read: nothing was tried
      result.stages.push_back(DressStage{entry.name, true, seconds(), e.what()});
      result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
      throw DressRefused(e.what(), std::move(result));
    }
    const DressStage stage{entry.name, report.ran, seconds(), report.reason};
    result.stages.push_back(stage);
    if (options.on_stage) options.on_stage(stage);
  }
  measure_dressed(outfit);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return std::move(result);
}

}  // namespace dresskit::dressing
