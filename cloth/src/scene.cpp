#include "dresskit/cloth/scene.h"

#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/seams.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/thickness/thickness.h"

using namespace dresskit::mesh;
using namespace dresskit::thickness;

namespace dresskit::cloth {
using json = nlohmann::json;

namespace {
/// A number as a person writes it: 1e-07, 0.5, 1000.
std::string compact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Reads one JSON object, naming every problem by file and key path.
class Reader {
 public:
  Reader(std::string file, const json& j, std::string path) : file_(std::move(file)), j_(j), path_(std::move(path)) {
    if (!j_.is_object()) fail("must be an object");
  }
  [[noreturn]] void fail(const std::string& what, const std::string& key = "") const {
    throw InputError(file_ + ": " + name(key) + (path_.empty() && key.empty() ? "" : ": ") + what);
  }
  std::string name(const std::string& key) const {
    return path_.empty() ? key : key.empty() ? path_ : path_ + "." + key;
  }
  void allow(std::initializer_list<const char*> keys) const {
    const std::set<std::string> ok(keys.begin(), keys.end());
    for (const auto& item : j_.items()) {
      if (ok.count(item.key())) continue;
      std::string list;
      for (const auto& k : ok) list += (list.empty() ? "" : ", ") + k;
      fail("unknown key (known: " + list + ")", item.key());
    }
  }
  bool has(const char* key) const { return j_.contains(key); }
  const json& at(const char* key) const { return j_.at(key); }
  Reader object(const char* key) const { return Reader(file_, j_.at(key), name(key)); }
  double number(const char* key, double fallback, double lo, double hi) const {
    if (!has(key)) return fallback;
    if (!j_[key].is_number()) fail("must be a number", key);
    const double v = j_[key].get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
      fail(compact(v) + " is outside " + compact(lo) + " – " + compact(hi), key);
    }
    return v;
  }
  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    if (!j_[key].is_boolean()) fail("must be true or false", key);
    return j_[key].get<bool>();
  }
  std::string text(const char* key, const std::string& fallback) const {
    if (!has(key)) return fallback;
    if (!j_[key].is_string()) fail("must be a string", key);
    return j_[key].get<std::string>();
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vector(const char* key, const Eigen::Matrix<double, N, 1>& fallback) const {
    if (!has(key)) return fallback;
    const json& a = j_[key];
    if (!a.is_array() || a.size() != N) fail("must be an array of " + std::to_string(N) + " numbers", key);
    Eigen::Matrix<double, N, 1> v;
    for (int k = 0; k < N; ++k) {
      if (!a[k].is_number() || !std::isfinite(a[k].get<double>())) fail("must hold finite numbers", key);
      v(k) = a[k].get<double>();
    }
    return v;
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  const json& j_;
  std::string path_;
};

ClothModel make_chain(const Reader& c, double scale, double total_mass) {
  c.allow({"particles", "spacing", "top", "direction"});
  const int n = static_cast<int>(c.number("particles", 10, 2, 1e6));
  const double spacing = c.number("spacing", 0.1, 1e-6, 1e6) * scale;
  const Eigen::Vector3d top = c.vector<3>("top", Eigen::Vector3d::Zero()) * scale;
  Eigen::Vector3d dir = c.vector<3>("direction", Eigen::Vector3d(0, -1, 0));
  if (dir.norm() < 1e-12) c.fail("must not be zero", "direction");
  dir.normalize();
  ClothModel m;
  m.rest_positions.resize(n, 3);
  for (int k = 0; k < n; ++k) m.rest_positions.row(k) = (top + k * spacing * dir).transpose();
  m.mass = Eigen::VectorXd::Constant(n, total_mass / n);
  return m;
}

struct Garment {
  ClothModel model;
  std::vector<int> pins;  ///< this garment's vertices (both layers of a double layer)
  PinMotion pin_motion;   ///< driven pins, this garment's vertices
  GarmentInfo info;
  std::vector<std::string> files;  ///< the files it was read from (mesh, fabric file)
};

/// The panels of a grid or panels cloth: first vertex and vertices per side of each.
struct Panel {
  int first = 0, nx = 0, ny = 0;
};

/// Reads one grid object into a mesh.
TriangleMesh read_grid(const Reader& g, double scale, Panel& panel) {
  g.allow({"size", "resolution", "center", "normal"});
  const Eigen::Vector2d size = g.vector<2>("size", Eigen::Vector2d(1, 1)) * scale;
  const Eigen::Vector2d res = g.vector<2>("resolution", Eigen::Vector2d(32, 32));
  if (res.minCoeff() < 2 || res.maxCoeff() > 4096 || res != res.array().round().matrix()) {
    g.fail("must be two whole numbers 2–4096", "resolution");
  }
  if (!(size.minCoeff() >= 1e-3 && size.maxCoeff() <= 1e3)) g.fail("must be 1 mm to 1 km (after units)", "size");
  panel.nx = static_cast<int>(res.x());
  panel.ny = static_cast<int>(res.y());
  return make_grid(size, res.cast<int>(), g.vector<3>("center", Eigen::Vector3d::Zero()) * scale,
                   g.vector<3>("normal", Eigen::Vector3d::UnitY()));
}

/// Vertex indices of a cloth as written in a scene: a vertex index; for a grid [i, j]; for panels
/// [panel, i, j]. Each is checked against the cloth's vertex count.
class IndexReader {
 public:
  IndexReader(const Reader& cloth, std::vector<Panel> panels, int vertices)
      : cloth_(cloth), panels_(std::move(panels)), vertices_(vertices) {}
  int operator()(const json& p, const char* key) const {
    auto whole = [](const json& e) {  // beyond int's range, out of range (2^32 is not vertex 0)
      return static_cast<int>(std::fmax(-2147483648.0, std::fmin(e.get<double>(), 2147483647.0)));
    };
    int index = -1;
    const bool grid = panels_.size() == 1 && panels_[0].nx > 0;
    if (p.is_number_integer()) {
      index = whole(p);
    } else if (p.is_array() && (p.size() == 2 || p.size() == 3) && !panels_.empty() && grid == (p.size() == 2)) {
      for (const json& e : p)
        if (!e.is_number_integer()) cloth_.fail("grid indices must be whole numbers", key);
      const int panel = p.size() == 3 ? whole(p[0]) : 0;
      const int i = whole(p[p.size() - 2]), j = whole(p[p.size() - 1]);
      if (panel < 0 || panel >= static_cast<int>(panels_.size())) {
        cloth_.fail("panel " + std::to_string(panel) + " is out of range", key);
      }
      const Panel& q = panels_[panel];
      if (i < 0 || i >= q.nx || j < 0 || j >= q.ny) {
        cloth_.fail("grid index [" + std::to_string(i) + ", " + std::to_string(j) + "] is out of range", key);
      }
      index = q.first + j * q.nx + i;
    } else {
      cloth_.fail(panels_.empty() ? "entries must be vertex indices"
                  : grid          ? "entries must be [i, j] grid indices or vertex indices"
                                  : "entries must be [panel, i, j] indices or vertex indices",
                  key);
    }
    if (index < 0 || index >= vertices_) {
      cloth_.fail("vertex " + std::to_string(index) + " is out of range (" + std::to_string(vertices_) + " vertices)", key);
    }
    return index;
  }
  /// A chain: an array of indices, or {"panel": p, "side": "left|right|bottom|top", "reverse": b}
  /// (left: i = 0, right: i = nx − 1, bottom: j = 0, top: j = ny − 1, in increasing j or i).
  std::vector<int> chain(const json& c, const char* key) const {
    std::vector<int> out;
    if (c.is_array()) {
      for (const json& p : c) out.push_back((*this)(p, key));
      return out;
    }
    if (!c.is_object() || panels_.empty() || panels_[0].nx == 0) {
      cloth_.fail("a chain is an array of indices, or {panel, side, reverse} on a grid or panels", key);
    }
    const Reader r(cloth_.file(), c, cloth_.name(key));
    r.allow({"panel", "side", "reverse"});
    const int panel = static_cast<int>(r.number("panel", 0, 0, static_cast<double>(panels_.size()) - 1));
    const Panel& q = panels_[panel];
    const std::string side = r.text("side", "");
    if (side == "left" || side == "right") {
      for (int j = 0; j < q.ny; ++j) out.push_back(q.first + j * q.nx + (side == "left" ? 0 : q.nx - 1));
    } else if (side == "bottom" || side == "top") {
      for (int i = 0; i < q.nx; ++i) out.push_back(q.first + (side == "bottom" ? 0 : q.ny - 1) * q.nx + i);
    } else {
      r.fail("must be left, right, bottom or top", "side");
    }
    if (r.boolean("reverse", false)) std::reverse(out.begin(), out.end());
    return out;
  }

 private:
  const Reader& cloth_;
  std::vector<Panel> panels_;
  int vertices_;
};

/// "seams": [{"pairs": [[A, B], ...]} | {"chains": [CHAIN_A, CHAIN_B]}, optional "stiffness" [N/m]
/// and "max_force" [N] or "max_acceleration" [m/s²]] (defaults: seams.h, 20 m/s²).
void read_seams(const Reader& cloth, const IndexReader& index, ClothModel& model) {
  const json& list = cloth.at("seams");
  if (!list.is_array()) cloth.fail("must be an array", "seams");
  const double stiffness = default_stitch_stiffness(model.springs);
  const int nv = static_cast<int>(model.rest_positions.rows());
  for (std::size_t n = 0; n < list.size(); ++n) {
    const std::string name = "seams[" + std::to_string(n) + "]";
    const Reader seam(cloth.file(), list[n], cloth.name(name));
    seam.allow({"pairs", "chains", "stiffness", "max_force", "max_acceleration"});
    if (seam.has("max_force") && seam.has("max_acceleration")) seam.fail("give max_force or max_acceleration, not both");
    const StitchLaw k{seam.number("stiffness", stiffness, 1e-9, 1e12), seam.number("max_force", 1.0, 1e-12, 1e9)};
    const int first = model.seams.size();
    try {
      if (seam.has("pairs") == seam.has("chains")) seam.fail("exactly one of pairs or chains is needed");
      if (seam.has("pairs")) {
        const json& pairs = seam.at("pairs");
        if (!pairs.is_array() || pairs.empty()) seam.fail("must be a non-empty array of [A, B] pairs", "pairs");
        std::vector<std::array<int, 2>> p;
        for (const json& pair : pairs) {
          if (!pair.is_array() || pair.size() != 2) seam.fail("each pair must be [A, B]", "pairs");
          p.push_back({index(pair[0], name.c_str()), index(pair[1], name.c_str())});
        }
        add_seam_pairs(model.seams, p, nv, k);
      } else {
        const json& chains = seam.at("chains");
        if (!chains.is_array() || chains.size() != 2) seam.fail("must be two chains", "chains");
        add_seam_chains(model.seams, model.rest_positions, index.chain(chains[0], name.c_str()),
                        index.chain(chains[1], name.c_str()), k);
      }
      if (!seam.has("max_force"))
        cap_stitches_by_acceleration(model.seams, first, model.mass, seam.number("max_acceleration", 20.0, 1e-9, 1e9));
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (what.rfind(cloth.file(), 0) == 0) throw;  // already names the file
      seam.fail(what);
    }
  }
}

/// "thickness": "heat" | {"t_skin", "t_env", "time", "threshold", "solidity", "composition"} (by heat
/// conduction through the fabric's fibres or the given ones, thickness/) | {"mm", "min_mm", "max_mm"}
/// (given, in millimetres whatever the units).
LayerThickness read_thickness(const Reader& cloth, const Fabric& fabric) {
  if (cloth.at("thickness").is_string()) {
    if (cloth.text("thickness", "") != "heat") cloth.fail("must be \"heat\" or an object", "thickness");
  } else {
    const Reader t = cloth.object("thickness");
    if (t.has("mm")) {
      t.allow({"mm", "min_mm", "max_mm"});
      LayerThickness given;
      given.thickness = t.number("mm", 0.0, 1e-6, 1e6) * 1e-3;
      given.min = t.number("min_mm", given.thickness * 1e3, 1e-6, 1e6) * 1e-3;
      given.max = t.number("max_mm", given.thickness * 1e3, 1e-6, 1e6) * 1e-3;
      if (!(given.min <= given.thickness && given.thickness <= given.max)) {
        t.fail("need min_mm ≤ mm ≤ max_mm");
      }
      return given;
    }
  }
  ThicknessOptions o;
  Composition composition = fabric.composition;
  if (cloth.at("thickness").is_object()) {
    const Reader t = cloth.object("thickness");
    t.allow({"t_skin", "t_env", "time", "threshold", "solidity", "composition"});
    o.t_skin = t.number("t_skin", o.t_skin, -273.15, 1e4);
    o.t_env = t.number("t_env", o.t_env, -273.15, 1e4);
    o.exposure = t.number("time", o.exposure, 1e-9, 1e9);
    if (t.has("threshold")) o.threshold = t.number("threshold", 0.0, -273.15, 1e4);
    o.solidity = t.number("solidity", o.solidity, 1e-9, 1.0);
    if (t.has("composition")) {
      const json& mix = t.at("composition");
      if (!mix.is_object()) t.fail("must be an object of fibre mass fractions", "composition");
      composition.clear();
      for (const auto& [fibre, fraction] : mix.items()) {
        if (!fraction.is_number()) t.fail("must be a number", "composition." + fibre);
        composition.emplace_back(fibre, fraction.get<double>());
      }
    }
  }
  try {
    const ThicknessResult r = compute_thickness(composition, o);
    return {r.thickness, r.thickness_min, r.thickness_max};
  } catch (const InputError& e) {
    cloth.fail(e.what(), "thickness");
  }
}

Garment read_garment(const Reader& cloth, const std::filesystem::path& folder, double scale) {
  cloth.allow({"grid", "panels", "mesh", "chain", "fabric", "fabric_file", "pins", "pin_motion", "total_mass",
               "warp", "bending_springs", "stiffness", "thickness", "seams"});
  Garment garment;
  ClothModel& model = garment.model;
  // Fabric: built-in by name, or by name from a user file.
  garment.info.fabric = cloth.text("fabric", "gray-interlock");
  Fabric fabric;
  if (cloth.has("fabric_file")) {
    garment.files.push_back((folder / cloth.text("fabric_file", "")).string());
    const auto fabrics = load_fabrics(garment.files.back());
    auto it = std::find_if(fabrics.begin(), fabrics.end(), [&](const Fabric& f) { return f.name == garment.info.fabric; });
    if (it == fabrics.end()) cloth.fail("'" + garment.info.fabric + "' is not in the fabric file", "fabric");
    fabric = *it;
  } else {
    fabric = fabric_by_name(garment.info.fabric);
  }
  ClothBuildOptions build;
  build.total_mass = cloth.number("total_mass", 0.0, 0.0, 1e6);
  build.warp_direction = cloth.vector<3>("warp", Eigen::Vector3d::UnitX());
  build.bending_springs = cloth.boolean("bending_springs", true);
  const int shapes = cloth.has("grid") + cloth.has("panels") + cloth.has("mesh") + cloth.has("chain");
  if (shapes != 1) cloth.fail("exactly one of grid, panels, mesh or chain is needed");
  std::vector<Panel> panels;
  if (cloth.has("grid")) {
    panels.emplace_back();
    model = build_cloth(read_grid(cloth.object("grid"), scale, panels[0]), fabric, build);
  } else if (cloth.has("panels")) {
    // Flat panels of one garment (a sewing pattern's pieces), one cloth: vertices panel after panel.
    const json& list = cloth.at("panels");
    if (!list.is_array() || list.empty()) cloth.fail("must be a non-empty array of grids", "panels");
    TriangleMesh all;
    for (std::size_t k = 0; k < list.size(); ++k) {
      Panel p;
      p.first = static_cast<int>(all.V.rows());
      const TriangleMesh m = read_grid(Reader(cloth.file(), list[k], cloth.name("panels[" + std::to_string(k) + "]")), scale, p);
      panels.push_back(p);
      TriangleMesh joined;
      joined.V.resize(all.V.rows() + m.V.rows(), 3);
      joined.V << all.V, m.V;
      joined.F.resize(all.F.rows() + m.F.rows(), 3);
      joined.F << all.F, (m.F.array() + p.first).matrix();
      joined.quads.resize(all.quads.rows() + m.quads.rows(), 4);
      joined.quads << all.quads, (m.quads.array() + p.first).matrix();
      all = std::move(joined);
    }
    model = build_cloth(all, fabric, build);
  } else if (cloth.has("mesh")) {
    LoadOptions load;
    load.units.metres_per_unit = scale;
    garment.files.push_back((folder / cloth.text("mesh", "")).string());
    const TriangleMesh mesh = load_mesh(garment.files.back(), load);
    model = build_cloth(mesh, fabric, build);
  } else {
    if (!(build.total_mass > 0)) cloth.fail("a chain needs a positive total_mass", "total_mass");
    model = make_chain(cloth.object("chain"), scale, build.total_mass);
    // Chain springs: linear at the fabric's warp stiffness per unit width × spacing / L0 (a strip
    // one spacing wide), or an explicit "stiffness" [N/m].
    const int n = static_cast<int>(model.rest_positions.rows());
    const double L0 = (model.rest_positions.row(1) - model.rest_positions.row(0)).norm();
    const double k_rest = cloth.number("stiffness", fabric.stiffness_at_rest(0.0), 1e-9, 1e12);
    const double k_knee = cloth.has("stiffness") ? k_rest : fabric.stiffness_at_knee(0.0);
    for (int k = 0; k + 1 < n; ++k) {
      SpringSet& s = model.springs;
      s.i.push_back(k);
      s.j.push_back(k + 1);
      s.rest_length.push_back(L0);
      s.k_rest.push_back(k_rest);
      s.k_knee.push_back(k_knee);
      s.type.push_back(SpringType::structural);
    }
  }
  if (cloth.has("stiffness") && !cloth.has("chain")) cloth.fail("only a chain takes an explicit stiffness", "stiffness");
  const int nv = static_cast<int>(model.rest_positions.rows());
  const IndexReader index(cloth, panels, nv);
  if (cloth.has("pins")) {
    const json& pins = cloth.at("pins");
    if (!pins.is_array()) cloth.fail("must be an array", "pins");
    for (const json& p : pins) garment.pins.push_back(index(p, "pins"));
  }
  if (cloth.has("pin_motion")) {
    const Reader m = cloth.object("pin_motion");
    m.allow({"pins", "axis", "center", "turns_per_second", "velocity", "until"});
    PinMotion& motion = garment.pin_motion;
    if (!m.has("pins")) m.fail("needs the pins it drives (indices, or {panel, side})", "pins");
    motion.particles = index.chain(m.at("pins"), "pin_motion");
    motion.axis = m.vector<3>("axis", motion.axis);
    if (motion.axis.norm() < 1e-12) m.fail("must not be zero", "axis");
    motion.centre = m.vector<3>("center", motion.centre) * scale;
    motion.turns_per_second = m.number("turns_per_second", 0.0, -1e3, 1e3);
    motion.velocity = m.vector<3>("velocity", motion.velocity) * scale;
    motion.until = m.number("until", motion.until, 0.0, 1e30);
  }
  if (cloth.has("seams")) read_seams(cloth, index, model);
  if (cloth.has("thickness")) {
    if (model.faces.rows() == 0) cloth.fail("a chain cannot have a thickness", "thickness");
    garment.info.double_layer = true;
    garment.info.thickness = read_thickness(cloth, fabric);
    model = make_double_layer(model, garment.info.thickness);
    const std::size_t n = garment.pins.size();
    for (std::size_t k = 0; k < n; ++k) garment.pins.push_back(garment.pins[k] + nv);
    const std::size_t driven = garment.pin_motion.particles.size();
    for (std::size_t k = 0; k < driven; ++k) garment.pin_motion.particles.push_back(garment.pin_motion.particles[k] + nv);
  }
  return garment;
}

/// A body mesh collider: the mesh in its own units (default: the scene's) and up axis, moved by
/// translate (scene units), with its signed distance grid (cell and band in the scene's units).
Collider read_mesh_collider(const Reader& c, const std::filesystem::path& folder, double scale) {
  LoadOptions load;
  load.units.metres_per_unit = scale;
  if (c.has("units")) {
    load.units.metres_per_unit = c.at("units").is_number() ? c.number("units", 1.0, 1e-12, 1e12)
                                                           : Units::parse(c.text("units", "m")).metres_per_unit;
  }
  if (c.has("up")) load.up = parse_up_axis(c.text("up", "+y"));
  if (!c.has("path")) c.fail("a mesh collider needs a path", "path");
  TriangleMesh body;
  try {
    body = load_mesh((folder / c.text("path", "")).string(), load);
  } catch (const InputError& e) {
    c.fail(e.what(), "path");
  }
  // A body read in the wrong units (millimetres as metres: 1,720 m tall; metres as millimetres:
  // 1.7 mm) is refused, with the units that would make it a person's size.
  const double extent = bounding_box(body).sizes().maxCoeff();
  if (!(extent >= 0.01 && extent <= 100.0)) {
    const std::string fits = units_for_body(extent / load.units.metres_per_unit);
    c.fail("the mesh is " + compact(extent) + " m across in these units" +
               (fits.empty() ? std::string(": check \"units\"") : "; with \"units\": \"" + fits + "\" it would be " +
                                                    compact(extent / load.units.metres_per_unit *
                                                            Units::parse(fits).metres_per_unit) + " m"),
           "units");
  }
  const Eigen::Vector3d shift = c.vector<3>("translate", Eigen::Vector3d::Zero()) * scale;
  body.V.rowwise() += shift.transpose();
  MeshDistanceOptions o;
  o.cell = c.number("cell", o.cell / scale, 1e-9, 1e9) * scale;
  o.band = c.number("band", o.band / scale, 1e-9, 1e9) * scale;
  return Collider::mesh(std::make_shared<const MeshDistance>(body, o));
}

}  // namespace

ClothScene load_cloth_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open scene file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  const Reader root(path, j, "");
  root.allow({"units", "cloth", "cloths", "colliders", "simulation"});
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  double scale = 1.0;
  if (root.has("units")) {
    scale = root.at("units").is_number() ? root.number("units", 1.0, 1e-12, 1e12)
                                         : Units::parse(root.text("units", "m")).metres_per_unit;
  }

  ClothScene scene;
  if (root.has("cloth") == root.has("cloths")) root.fail("exactly one of cloth or cloths is needed");
  std::vector<Garment> garments;
  if (root.has("cloth")) {
    garments.push_back(read_garment(root.object("cloth"), folder, scale));
  } else {
    const json& list = root.at("cloths");
    if (!list.is_array() || list.empty()) root.fail("must be a non-empty array", "cloths");
    for (std::size_t k = 0; k < list.size(); ++k) {
      const Reader cloth(path, list[k], "cloths[" + std::to_string(k) + "]");
      garments.push_back(read_garment(cloth, folder, scale));
      if (garments.back().model.faces.rows() == 0) cloth.fail("a chain cannot be one of several layers");
    }
  }
  double separation = 0.002 * scale;
  if (root.has("simulation")) separation = root.object("simulation").number("layer_separation", 0.002, 0.0, 1e3) * scale;
  std::vector<ClothModel> models;
  for (const Garment& g : garments) models.push_back(g.model);
  const std::vector<int> first = garment_offsets(models);
  scene.model = garments.size() == 1 ? std::move(models[0]) : stack_layers(models, separation);
  for (std::size_t k = 0; k < garments.size(); ++k) {
    for (int p : garments[k].pins) scene.pins.push_back(p + first[k]);
    if (!garments[k].pin_motion.particles.empty()) {
      if (!scene.pin_motion.particles.empty()) root.fail("only one cloth may have a pin_motion", "cloths");
      scene.pin_motion = garments[k].pin_motion;
      for (int& p : scene.pin_motion.particles) p += first[k];
    }
    GarmentInfo info = garments[k].info;
    info.first_vertex = first[k];
    info.vertices = first[k + 1] - first[k];
    scene.garments.push_back(info);
    scene.files.insert(scene.files.end(), garments[k].files.begin(), garments[k].files.end());
  }
  scene.fabric_name = scene.garments[0].fabric;
  scene.faces = scene.model.faces;
  // Cloth–cloth collisions are on for every cloth with faces unless the scene says otherwise.
  scene.simulation.self_collision = scene.faces.rows() > 0;

  if (root.has("colliders")) {
    if (!root.at("colliders").is_array()) root.fail("must be an array", "colliders");
    for (size_t k = 0; k < root.at("colliders").size(); ++k) {
      const Reader c(path, root.at("colliders")[k], "colliders[" + std::to_string(k) + "]");
      const std::string type = c.text("type", "");
      const double friction = c.number("friction", type == "mesh" ? 0.5 : 0.3, 0.0, 10.0);
      if (type == "sphere") {
        c.allow({"type", "center", "radius", "friction"});
        scene.simulation.colliders.push_back(Collider::sphere(
            c.vector<3>("center", Eigen::Vector3d::Zero()) * scale, c.number("radius", 0.0, 1e-9, 1e9) * scale, friction));
      } else if (type == "plane") {
        c.allow({"type", "point", "normal", "friction"});
        scene.simulation.colliders.push_back(Collider::plane(c.vector<3>("point", Eigen::Vector3d::Zero()) * scale,
                                                             c.vector<3>("normal", Eigen::Vector3d::UnitY()), friction));
      } else if (type == "box") {
        c.allow({"type", "center", "half_size", "friction"});
        scene.simulation.colliders.push_back(Collider::box(c.vector<3>("center", Eigen::Vector3d::Zero()) * scale,
                                                           c.vector<3>("half_size", Eigen::Vector3d::Zero()) * scale, friction));
      } else if (type == "cylinder") {
        c.allow({"type", "center", "axis", "radius", "half_length", "friction"});
        scene.simulation.colliders.push_back(Collider::cylinder(
            c.vector<3>("center", Eigen::Vector3d::Zero()) * scale, c.vector<3>("axis", Eigen::Vector3d::UnitY()),
            c.number("radius", 0.0, 1e-9, 1e9) * scale, c.number("half_length", 0.0, 1e-9, 1e9) * scale, friction));
      } else if (type == "mesh") {
        c.allow({"type", "path", "units", "up", "translate", "friction", "static_friction", "penalty", "cell", "band"});
        scene.simulation.colliders.push_back(read_mesh_collider(c, folder, scale));
        scene.files.push_back((folder / c.text("path", "")).string());
        scene.simulation.colliders.back().friction = friction;
      } else {
        c.fail("'" + type + "' is not sphere, plane, box, cylinder or mesh", "type");
      }
      if (c.has("static_friction"))
        scene.simulation.colliders.back().static_friction = c.number("static_friction", 0.0, 0.0, 10.0);
      if (c.has("penalty")) scene.simulation.colliders.back().penalty = c.number("penalty", 0.0, 0.0, 1e6);
    }
  }

  if (root.has("simulation")) {
    const Reader s = root.object("simulation");
    s.allow({"integrator", "linear_solver", "dt", "duration", "fps", "gravity", "strain_limit",
             "strain_limiting", "dynamic_stiffness", "air_damping", "spring_damping", "wind",
             "gust_amplitude", "gust_frequency", "collision_margin", "cg_tolerance", "adaptive", "dt_min",
             "max_strain_change", "newton_iterations", "newton_tolerance", "layer_separation", "layer_order_guard",
             "projective_iterations", "time_scheme", "projective_collisions", "self_collision", "cloth_thickness",
             "cloth_friction", "seam_tolerance", "weld_seams", "projective_lbfgs_history",
             "projective_adaptive_weights", "stop_at_rest", "rest_mean_speed", "rest_max_speed",
             "rest_time", "contact_travel", "rise_skips_held_springs"});
    SimulationOptions& o = scene.simulation;
    if (s.has("integrator")) o.integrator = parse_integrator(s.text("integrator", ""));
    const std::string solver = s.text("linear_solver", "cg");
    if (solver == "cg") o.linear.solver = LinearSolver::conjugate_gradient;
    else if (solver == "ldlt") o.linear.solver = LinearSolver::ldlt;
    else s.fail("'" + solver + "' is not cg or ldlt", "linear_solver");
    o.dt = s.number("dt", o.dt, 1e-7, 1.0);
    if (!(o.dt > 0)) s.fail("must be positive", "dt");
    scene.run.duration = s.number("duration", scene.run.duration, 0.0, 1e5);
    scene.run.fps = s.number("fps", scene.run.fps, 1e-3, 1e4);
    RestOptions& rest = scene.run.rest;
    rest.enabled = s.boolean("stop_at_rest", rest.enabled);
    rest.mean_speed = s.number("rest_mean_speed", rest.mean_speed, 0.0, 1e3);
    rest.max_speed = s.number("rest_max_speed", rest.max_speed, 0.0, 1e3);
    rest.time = s.number("rest_time", rest.time, 0.0, 1e5);
    o.gravity = s.vector<3>("gravity", o.gravity);
    o.strain_limit = s.number("strain_limit", o.strain_limit, 1e-6, 10.0);
    o.strain_limiting = s.boolean("strain_limiting", o.strain_limiting);
    o.dynamic_stiffness = s.boolean("dynamic_stiffness", false);
    o.air_damping = s.number("air_damping", o.air_damping, 0.0, 1e6);
    o.spring_damping = s.number("spring_damping", 0.0, 0.0, 1e3);
    o.wind = s.vector<3>("wind", o.wind);
    o.gust_amplitude = s.number("gust_amplitude", 0.0, 0.0, 100.0);
    o.gust_frequency = s.number("gust_frequency", 0.0, 0.0, 1e4);
    o.collision_margin = s.number("collision_margin", o.collision_margin, 0.0, 1.0) * scale;
    o.linear.cg_tolerance = s.number("cg_tolerance", o.linear.cg_tolerance, 1e-14, 0.1);
    o.adaptive = s.boolean("adaptive", o.adaptive);
    o.contact_travel = s.number("contact_travel", o.contact_travel, 0.0, 100.0);
    o.newton.iterations = static_cast<int>(s.number("newton_iterations", o.newton.iterations, 1, 1000));
    o.iteration_tolerance = s.number("newton_tolerance", o.iteration_tolerance, 1e-15, 1.0);
    o.dt_min = s.number("dt_min", std::min(o.dt_min, o.dt), 1e-12, 1.0);
    o.max_strain_change = s.number("max_strain_change", o.max_strain_change, 1e-9, 10.0);
    o.rise_skips_held_springs = s.boolean("rise_skips_held_springs", o.rise_skips_held_springs);
    o.layer_order_guard = s.boolean("layer_order_guard", o.layer_order_guard);
    o.projective.iterations = static_cast<int>(s.number("projective_iterations", o.projective.iterations, 1, 10000));
    o.self_collision = s.boolean("self_collision", o.self_collision);
    o.self_collision_options.thickness =
        s.number("cloth_thickness", o.self_collision_options.thickness / scale, 1e-9, 1.0) * scale;
    o.self_collision_options.friction = s.number("cloth_friction", o.self_collision_options.friction, 0.0, 10.0);
    o.seam_tolerance = s.number("seam_tolerance", o.seam_tolerance / scale, 1e-9, 1.0) * scale;
    scene.weld_seams = s.boolean("weld_seams", scene.weld_seams);
    const std::string scheme = s.text("time_scheme", to_string(o.projective.time_scheme));
    try {
      o.projective.time_scheme = parse_time_scheme(scheme);
    } catch (const InputError&) {
      s.fail("'" + scheme + "' is not backward_euler, bdf2, midpoint or tr_bdf2", "time_scheme");
    }
    o.projective.lbfgs_history =
        static_cast<int>(s.number("projective_lbfgs_history", o.projective.lbfgs_history, 0, 100));
    o.projective.collisions = s.boolean("projective_collisions", o.projective.collisions);
    o.projective.adaptive_weights = s.boolean("projective_adaptive_weights", o.projective.adaptive_weights);
  }
  check_options(scene.simulation);
  return scene;
}

}  // namespace dresskit::cloth
