#include "dresskit/testing/drops.h"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "dresskit/cloth/scene.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/testing/data.h"

using namespace dresskit::cloth;
using namespace dresskit::mesh;

namespace dresskit::testing {

std::vector<DropCase> drop_cases(int resolution) {
  const int n = resolution;
  auto scaled = [&](double size) { return std::max(8, static_cast<int>(n * size / 0.8 + 0.5)); };
  std::vector<DropCase> cases;
  // gc_mean_all: metres, feet at y = 0, head top at 1.72 m centred near (0, 0.04); shoulders at
  // 1.43 m at x = 0.17; the T-pose arm lies along +x at y 1.33–1.43 m, z −0.07–0.04 m.
  cases.push_back({"head", "gc_mean_all.obj", "m", "m", {0.0, 1.87, 0.04}, 0.8, n, "camel-ponte-roma"});
  cases.push_back({"shoulder", "gc_mean_all.obj", "m", "m", {0.26, 1.70, 0.0}, 0.36, scaled(0.36), "gray-interlock"});
  cases.push_back({"tpose_arm", "gc_mean_all_tpose.obj", "m", "m", {0.6, 1.55, -0.015}, 0.3, scaled(0.3),
                   "white-swim-solid"});
  cases.push_back({"head_from_3.5m", "gc_mean_all.obj", "m", "m", {0.0, 3.5, 0.04}, 0.8, n, "camel-ponte-roma"});
  cases.push_back({"head_stiff", "gc_mean_all.obj", "m", "m", {0.0, 1.87, 0.04}, 0.8, n, "royal-target"});
  // MakeHuman bodies: decimetres, head top of the young man at 9.30 dm, centred near z = 1.0 dm;
  // the young woman's head top at 7.86 dm (scene in centimetres: 78.6 cm), centred near z = 1.1 dm.
  cases.push_back({"mh_man_dm_head", "mh_man_young_average.obj", "dm", "dm", {0.0, 10.8, 1.0}, 8.0, n,
                   "11oz-black-denim"});
  cases.push_back({"mh_woman_cm_head", "mh_woman_young_average.obj", "cm", "dm", {0.0, 95.0, 11.0}, 60.0,
                   scaled(0.6), "navy-sparkle-sweat"});
  return cases;
}

const DropCase& drop_case(const std::string& name, int resolution) {
  static std::vector<DropCase> cases;
  cases = drop_cases(resolution);
  for (const DropCase& c : cases)
    if (c.name == name) return c;
  throw std::invalid_argument("no drop case named " + name);
}

std::string drop_scene(const DropCase& c, const std::string& simulation, double duration) {
  nlohmann::json sim = nlohmann::json::parse(simulation);
  sim["duration"] = duration;
  const nlohmann::json scene = {
      {"units", c.units},
      {"cloth", {{"grid", {{"size", {c.size, c.size}}, {"resolution", {c.resolution, c.resolution}},
                           {"center", {c.center.x(), c.center.y(), c.center.z()}}}},
                 {"fabric", c.fabric}}},
      {"colliders", {{{"type", "mesh"}, {"path", data_dir() + "/bodies/" + c.body}, {"units", c.body_units}}}},
      {"simulation", sim}};
  return scene.dump(2);
}

bool DropOutcome::passed() const {
  return run.ok && inside == 0 && crossings == 0 && max_strain <= 0.12 && drop >= 0.02;
}

DropOutcome run_drop(const DropCase& c, const std::string& simulation, const std::string& dir, double duration) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + c.name + ".json";
  std::ofstream(path) << drop_scene(c, simulation, duration);
  const ClothScene scene = load_cloth_scene(path);
  ClothSimulator sim(scene.model, scene.simulation);
  sim.set_pinned(scene.pins);
  const Eigen::Vector3d start = scene.model.mass.transpose() * sim.positions() / scene.model.mass.sum();
  DropOutcome out;
  const std::clock_t t0 = std::clock();
  out.run = run(sim, scene.run);
  out.seconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  out.steps = out.run.totals.steps;
  out.simulated = sim.time();
  const Eigen::Vector3d end = scene.model.mass.transpose() * sim.positions() / scene.model.mass.sum();
  out.drop = start.y() - end.y();
  out.max_strain = sim.max_strain();
  out.crossings = count_intersections(sim.positions(), scene.model.faces);
  const InsideTest inside(scene.simulation.colliders.front().body->mesh());
  out.inside = inside.count_deeper(sim.positions(), 0.002, &out.deepest);
  return out;
}

}  // namespace dresskit::testing
