#include "dresskit/mesh/names.h"
#include "dresskit/dressing/dress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "dresskit/alignment/part_labels.h"
#include "dresskit/cloth/fabric.h"
#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/layers.h"
#include "dresskit/cloth/mesh_distance.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/cleanup.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/mesh/topology.h"
#include "dresskit/thickness/thickness.h"
#include "garments.h"
#include "padding.h"
#include "pattern_garment.h"

using namespace dresskit::alignment;
using namespace dresskit::cloth;
using namespace dresskit::mesh;
using namespace dresskit::segmentation;
using namespace dresskit::thickness;

namespace dresskit::dressing {
using namespace detail;

MeshFile MeshFile::file(std::string path, LoadOptions load, std::string labels) {
  MeshFile f;
  f.path = std::move(path);
  f.load = std::move(load);
  f.labels = std::move(labels);
  return f;
}

MeshFile MeshFile::given(std::string name, TriangleMesh mesh) {
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

std::string number(double value, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

/// The same vertices and faces (a mesh that cleaning left as it was).
bool same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  return a.V.rows() == b.V.rows() && a.F.rows() == b.F.rows() && a.V == b.V && a.F == b.F;
}

double height(const TriangleMesh& m) { return m.V.col(1).maxCoeff() - m.V.col(1).minCoeff(); }

/// Times a stage and records it (and tells the caller) when it ends.
class Stage {
 public:
  Stage(DressResult& result, const DressOptions& options, std::string name)
      : result_(result), options_(options), start_(Clock::now()) {
    stage_.name = std::move(name);
  }
  void done(bool ran, std::string reason) {
    stage_.ran = ran;
    stage_.reason = std::move(reason);
    stage_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    result_.stages.push_back(stage_);
    if (options_.on_stage) options_.on_stage(stage_);
  }

 private:
  DressResult& result_;
  const DressOptions& options_;
  DressStage stage_;
  Clock::time_point start_;
};

/// What makes a mesh unfit for the later stages, or "" when nothing does: degenerate faces, edges
/// with more than two faces, faces turned against their neighbours. (A pinched vertex or a vertex
/// used by no face is harmless.)
std::string defects(const TriangleMesh& m) {
  const TopologyReport t = analyse_topology(m);
  std::string why;
  auto add = [&](int count, const char* what) {
    if (count > 0) why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + what;
  };
  add(t.num_degenerate_faces, "degenerate faces");
  add(t.num_non_manifold_edges, "edges with more than two faces");
  add(t.num_inconsistent_edges, "edges between faces turned against each other");
  return why;
}

/// Parts from a label file or given with the mesh, or by spectral segmentation.
std::vector<DressPart> label(TriangleMesh& m, const MeshFile& f, const SegmentationOptions& options,
                             bool& from_file) {
  std::vector<DressPart> parts;
  const bool with_mesh = f.labels.empty() && !m.label_names.empty() && m.labels.size() == m.num_vertices();
  from_file = !f.labels.empty() || with_mesh;
  if (from_file) {
    if (!with_mesh) apply_part_labels(m, f.labels, f.labels_key, f.path);
    parts.resize(m.label_names.size());
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k].name = m.label_names[k];
    for (Eigen::Index i = 0; i < m.labels.size(); ++i)
      if (m.labels(i) >= 0) ++parts[static_cast<std::size_t>(m.labels(i))].vertices;
    return parts;
  }
  const SegmentationResult r = segment_mesh(m, options);
  m.labels = r.vertex_labels;
  m.label_names = r.part_names();
  for (const NamedPart& p : r.parts) parts.push_back({p.name, p.confidence, p.vertices});
  return parts;
}

std::string part_list(const std::vector<DressPart>& parts) {
  std::string s;
  for (const DressPart& p : parts) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

/// How a garment's vertices lie against the body: mean distance to its surface [m] and the
/// vertices deeper than 2 mm inside.
struct SurfaceFit {
  double mean_distance = 0.0;
  int inside = 0;
};
SurfaceFit surface_fit(const Eigen::MatrixX3d& V, const InsideTest& body) {
  SurfaceFit fit;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double d = body.signed_distance(V.row(i).transpose());
    fit.mean_distance += std::abs(d);
    if (d < -0.002) ++fit.inside;
  }
  if (V.rows() > 0) fit.mean_distance /= static_cast<double>(V.rows());
  return fit;
}

/// A garment's height over the body: its vertices' mean distance to the body in each cell of
/// `cell` [m] that their nearest body points fall in.
std::unordered_map<std::int64_t, double> height_over_body(const Eigen::MatrixX3d& V, const MeshDistance& body,
                                                          double cell) {
  std::unordered_map<std::int64_t, std::pair<double, int>> sum;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    Eigen::Vector3d outward;
    const Eigen::Vector3d p = V.row(i).transpose();
    const double d = body.distance(p, &outward);
    auto& s = sum[grid_cell_key(p - d * outward, cell)];
    s.first += d;
    ++s.second;
  }
  std::unordered_map<std::int64_t, double> height;
  for (const auto& [key, s] : sum) height[key] = s.first / s.second;
  return height;
}

/// Which of two garments lies outside the other where both cover the body: +1 when `a` lies
/// farther from it in more of the cells both cover, −1 when `b` does, 0 when they share no cell
/// or tie.
int lies_outside(const std::unordered_map<std::int64_t, double>& a, const std::unordered_map<std::int64_t, double>& b) {
  int votes = 0;
  for (const auto& [key, h] : a) {
    const auto it = b.find(key);
    if (it != b.end() && h != it->second) votes += h > it->second ? 1 : -1;
  }
  return (votes > 0) - (votes < 0);
}

/// A garment that already lies on the body: few vertices inside it, near its surface on average.
bool on_body(const SurfaceFit& fit, Eigen::Index vertices, double body_height, const DressOptions& options) {
  return fit.inside <= options.fit_inside * static_cast<double>(vertices) &&
         fit.mean_distance <= options.fit_distance * body_height;
}

/// The body cells [m] in which layers inferred for garments on the body compare their heights.
constexpr double kLayerCell = 0.02;

/// A body of a person's height (0.5–2.5 m) standing along its file's up axis; otherwise an
/// InputError naming the axis, or the units, that would make it one (one --units for all where the
/// garment meshes so far are in the body's units and fit it as they are).
void check_body_units(const TriangleMesh& body, const MeshFile& body_file, const std::vector<DressedGarment>& garments) {
  const double body_height = height(body);
  const double in_file = body_height / body_file.load.units.metres_per_unit;
  const std::string fits = units_for_body(in_file);
  // A body lying along another of the file's axes than the up axis given (a Z-up file read as
  // Y-up), half as long again as it is tall (arms spread make it as wide as tall at most): that
  // axis is named, with the units that would then fit.
  const Eigen::MatrixX3d file = to_file_frame(body.V, body_file.load);
  const Eigen::Vector3d extent = file.colwise().maxCoeff() - file.colwise().minCoeff();
  Eigen::Index longest = 0;
  extent.maxCoeff(&longest);
  const UpAxis up = body_file.load.up;
  const int up_index = up == UpAxis::pos_x || up == UpAxis::neg_x ? 0 : up == UpAxis::pos_y || up == UpAxis::neg_y ? 1 : 2;
  std::string axis_hint;
  if (longest != up_index && extent[longest] > 1.5 * in_file) {
    const std::string name(1, "xyz"[longest]);
    const std::string along = units_for_body(extent[longest]);
    axis_hint = "; it is longest along the file's " + name + " axis: with --up " + name + " (or -" + name + ")" +
                (along.empty() || Units::parse(along).metres_per_unit == body_file.load.units.metres_per_unit
                     ? ""
                     : " and --body-units " + along) +
                " it would be " +
                number(extent[longest] * (along.empty() ? body_file.load.units.metres_per_unit
                                                        : Units::parse(along).metres_per_unit)) +
                " m tall";
  }
  bool as_body = !garments.empty();
  for (const DressedGarment& g : garments) {
    const double size = bounding_box(g.mesh).sizes().maxCoeff();
    as_body = as_body && !g.from_pattern && g.file.load.units.metres_per_unit == body_file.load.units.metres_per_unit &&
              size >= 0.1 * body_height && size <= 1.5 * body_height;
  }
  if (!axis_hint.empty() || !(body_height >= 0.5 && body_height <= 2.5))
    throw InputError(body_file.path + ": the body is " + number(body_height) + " m tall in units " +
                     body_file.load.units.name +
                     (!axis_hint.empty() ? axis_hint
                      : fits.empty()     ? ": give its units (--body-units)"
                                         : "; with " + std::string(as_body ? "--units " : "--body-units ") + fits +
                                           " it would be " + number(in_file * Units::parse(fits).metres_per_unit) + " m"));
}

/// The simulator's options for a quality; the run's duration.
SimulationOptions simulation_options(DressQuality q, double& duration) {
  SimulationOptions o;
  o.self_collision = true;
  switch (q) {
    // Fast keeps the simulator's steps and iterations and settles for less time: a stiff fabric
    // held against the body (denim on a larger body) needs the default projective iterations, or
    // its adaptive step falls to the minimum.
    case DressQuality::fast: duration = 0.5; break;
    case DressQuality::balanced: duration = 1.0; break;
    case DressQuality::accurate:
      o.dt = 1.0 / 240.0;
      o.projective.iterations = 20;
      duration = 2.0;
      break;
  }
  return o;
}

/// Structural strains of a cloth model at positions x (quad diagonals are shear springs), sorted.
std::vector<double> structural_strains(const ClothModel& m, const Eigen::MatrixX3d& x) {
  const SpringSet& s = m.springs;
  std::vector<double> strain;
  for (int k = 0; k < s.size(); ++k)
    if (s.type[k] == SpringType::structural)
      strain.push_back((x.row(s.i[k]) - x.row(s.j[k])).norm() / s.rest_length[k] - 1.0);
  std::sort(strain.begin(), strain.end());
  return strain;
}

/// Where two layers overlap (the outer one's vertices within `overlap` of the inner one), the 5th
/// and 50th percentiles of the distance from those vertices to the inner one's triangles [m], and
/// their count.
struct Gap {
  double p5 = 0.0, median = 0.0;
  int vertices = 0;
};
Gap layer_gap(const Eigen::MatrixX3d& outer, const Eigen::MatrixX3d& inner, const Eigen::MatrixX3i& inner_faces,
              double overlap) {
  const TriangleBvh tree(inner, inner_faces);
  std::vector<double> d;
  for (Eigen::Index i = 0; i < outer.rows(); ++i) {
    Eigen::Vector3d q;
    double d2 = 0.0;
    tree.closest(outer.row(i).transpose(), &q, &d2);
    if (d2 < overlap * overlap) d.push_back(std::sqrt(d2));
  }
  if (d.empty()) return {};
  std::sort(d.begin(), d.end());
  return {d[d.size() / 20], d[d.size() / 2], static_cast<int>(d.size())};
}

/// Parts of the same name from several garments keep apart as name_2, name_3, ... (each garment's
/// body is placed on its own), as segmentation names the pieces of one garment.
void distinct_label_names(TriangleMesh& m) {
  for (std::size_t l = 1; l < m.label_names.size(); ++l) {
    const std::string name = m.label_names[l];
    for (int n = 2; std::count(m.label_names.begin(), m.label_names.begin() + static_cast<long>(l), m.label_names[l]); ++n)
      m.label_names[l] = name + "_" + std::to_string(n);
  }
}

}  // namespace

DressResult dress(const MeshFile& body_file, const std::vector<GarmentFile>& garment_files,
                  const DressOptions& options) {
  const auto start = Clock::now();
  DressResult result;
  result.body_file = body_file;
  result.body_file.mesh.reset();
  result.quality = options.quality;
  if (garment_files.empty()) throw InputError("dress: no garment given");
  if (!(options.settle_seconds >= 0.0 && options.settle_seconds < 1e6))
    throw InputError("settle seconds: " + number(options.settle_seconds) + " is not between 0 and 1e6");
  std::vector<Fabric> fabrics;
  for (const GarmentFile& g : garment_files) fabrics.push_back(fabric_by_name(g.fabric.empty() ? "gray-interlock" : g.fabric));

  std::shared_ptr<const MeshDistance> body_distance;  // the body's, for sewing, untangling and settling
  // Patterns carried part by part: their bodies with part labels, each read once, and this body's
  // parts, found once at load and kept for the segmentation stage (unless cleaning changes it).
  std::map<std::string, TriangleMesh> pattern_bodies;
  std::optional<TriangleMesh> labelled_body;
  std::vector<DressPart> labelled_body_parts;
  bool labelled_body_from_file = false;

  // Load.
  {
    Stage stage(result, options, "load");
    auto load = [](const MeshFile& f) {
      if (!f.mesh) return load_mesh(f.path, f.load);
      validate_mesh(*f.mesh, f.path);
      const Eigen::Index names = static_cast<Eigen::Index>(f.mesh->label_names.size());
      if (f.mesh->labels.size() > 0 &&
          (f.mesh->labels.size() != f.mesh->num_vertices() || f.mesh->labels.minCoeff() < -1 ||
           f.mesh->labels.maxCoeff() >= names))
        throw InputError(f.path + ": labels must be one per vertex, each -1 or the index of one of its " +
                         std::to_string(names) + " part names");
      return *f.mesh;
    };
    result.body = load(body_file);
    for (const GarmentFile& g : garment_files) {
      DressedGarment d;
      d.in_memory = g.file.mesh.has_value();
      d.name = d.in_memory ? g.file.path : stem(g.file.path);  // a mesh in memory keeps the name given
      d.file = g.file;  // with a mesh given in memory: kept, the output's vertex order is its
      for (const DressedGarment& other : result.garments)
        if (other.name == d.name)
          throw InputError(g.file.path + ": another garment is called " + d.name + "; outputs are named by it");
      d.fabric = g.fabric.empty() ? "gray-interlock" : g.fabric;
      d.padded = g.padded;
      if (is_pattern_garment(g)) {  // a sewing pattern: cut, sewn, welded
        // Sewn around the body: a body in the wrong units or lying down is said before, not as a
        // seam that would not close minutes later.
        check_body_units(result.body, body_file, result.garments);
        if (!body_distance) body_distance = std::make_shared<const MeshDistance>(result.body);
        PartBodies parts;
        if (!g.pattern_body.path.empty() || g.pattern_body.mesh) {
          auto it = pattern_bodies.find(g.pattern_body.path);
          if (it == pattern_bodies.end()) {
            TriangleMesh from = load(g.pattern_body);
            const double tall = height(from);
            if (!(tall >= 0.5 && tall <= 2.5)) {
              const double in_file = tall / g.pattern_body.load.units.metres_per_unit;
              const std::string fits = units_for_body(in_file);
              throw InputError(g.pattern_body.path + ": the pattern's body is " + number(tall) + " m tall in units " +
                               g.pattern_body.load.units.name +
                               (fits.empty() ? ": give its units (--pattern-body-units)"
                                             : "; with --pattern-body-units " + fits + " it would be " +
                                                   number(in_file * Units::parse(fits).metres_per_unit) + " m"));
            }
            bool from_file = false;
            label(from, g.pattern_body, options.segmentation, from_file);
            it = pattern_bodies.emplace(g.pattern_body.path, std::move(from)).first;
          }
          if (!labelled_body) {
            labelled_body = result.body;
            labelled_body_parts = label(*labelled_body, body_file, options.segmentation, labelled_body_from_file);
          }
          parts = {&it->second, &*labelled_body};
        }
        sew_pattern_garment(g, result.body, body_file.load, body_distance, options, parts, d);
      } else
        d.mesh = load(g.file);
      result.garments.push_back(std::move(d));
    }
    const int files = !body_file.mesh + static_cast<int>(std::count_if(garment_files.begin(), garment_files.end(),
                                                                         [](const GarmentFile& g) { return !g.file.mesh; }));
    const int meshes = 1 + static_cast<int>(garment_files.size());
    stage.done(files > 0, files == meshes ? counted(meshes, "mesh", "meshes")
                          : files == 0    ? "every mesh given in memory"
                                          : std::to_string(files) + " of " + counted(meshes, "mesh", "meshes") + " from files");
  }

  // Clean: only the meshes with defects the later stages cannot take.
  {
    Stage stage(result, options, "clean");
    std::string done;
    auto clean = [&](TriangleMesh& m, const std::string& name) {
      const std::string why = defects(m);
      if (why.empty()) return;
      CleanupOptions o;
      o.stitch_borders = false;  // a garment's openings stay open
      m = cleanup_mesh(m, o).mesh;
      done += (done.empty() ? "" : "; ") + name + ": " + why;
    };
    clean(result.body, stem(body_file.path));
    for (DressedGarment& g : result.garments) clean(g.mesh, g.name);
    stage.done(!done.empty(), done.empty() ? "no mesh has degenerate faces, non-manifold or inconsistent edges" : done);
  }

  // Units: a person is 0.5–2.5 m tall; a garment is between a tenth and one and a half of its body.
  const double body_height = height(result.body);
  {
    Stage stage(result, options, "units");
    check_body_units(result.body, body_file, result.garments);
    // A body is closed or nearly so (a scan may lack its soles or the top of its head); a garment's
    // openings (neck, cuffs, hem, waist) add up to more than its wearer's height.
    const double open = analyse_topology(result.body).boundary_length;
    if (open > body_height) {
      throw InputError(body_file.path + ": does not look like a body: " + number(open) +
                       " m of open edges on a mesh " + number(body_height) +
                       " m tall (a body is closed or nearly so; is it a garment?)");
    }
    for (DressedGarment& g : result.garments) {
      const double size = bounding_box(g.mesh).sizes().maxCoeff();
      if (size >= 0.1 * body_height && size <= 1.5 * body_height) continue;
      const double in_file = size / g.file.load.units.metres_per_unit;
      std::string fits;
      for (const char* name : {"m", "dm", "cm", "mm"}) {
        const double s = in_file * Units::parse(name).metres_per_unit;
        if (s >= 0.1 * body_height && s <= 1.5 * body_height) {
          fits = name;
          break;
        }
      }
      throw InputError(g.file.path + ": the garment is " + number(size) + " m across in units " +
                       g.file.load.units.name + " on a body " + number(body_height) + " m tall" +
                       (fits.empty() ? ": give its units (--garment-units)" : "; with --garment-units " + fits + " it fits"));
    }
    stage.done(true, "body " + number(body_height) + " m tall; garments " + std::to_string(result.garments.size()) +
                         " within its size");
  }

  // Segmentation: label files where given, spectral segmentation otherwise.
  {
    Stage stage(result, options, "segmentation");
    int segmented = 0;
    if (labelled_body && same_mesh(*labelled_body, result.body)) {
      result.body.labels = labelled_body->labels;
      result.body.label_names = labelled_body->label_names;
      result.body_parts = labelled_body_parts;
      result.body_labels_from_file = labelled_body_from_file;
    } else {
      result.body_parts = label(result.body, body_file, options.segmentation, result.body_labels_from_file);
    }
    segmented += !result.body_labels_from_file;
    bool limbs = false;
    for (const DressPart& p : result.body_parts) {
      const std::string& n = p.name;
      limbs = limbs || n.find("arm") != std::string::npos || n.find("leg") != std::string::npos;
    }
    if (!limbs) {
      throw InputError(body_file.path + ": does not look like a body: no arms or legs among its parts (" +
                       part_list(result.body_parts) + ")");
    }
    for (DressedGarment& g : result.garments) {
      g.parts = label(g.mesh, g.file, options.segmentation, g.labels_from_file);
      segmented += !g.labels_from_file;
    }
    const int meshes = 1 + static_cast<int>(result.garments.size());
    stage.done(segmented > 0, segmented == 0        ? "every mesh has part labels"
                              : segmented == meshes ? "every mesh cut into parts"
                                                    : std::to_string(segmented) + " of " + std::to_string(meshes) +
                                                          " meshes cut into parts (the others have part labels)");
  }

  const InsideTest inside(result.body);
  // The body's distance, built once (sewing patterns built it at load unless the body changed since).
  if (!body_distance || !same_mesh(body_distance->mesh(), result.body))
    body_distance = std::make_shared<const MeshDistance>(result.body);

  // Layers, inside to outside: as given, or inferred from the garments' kinds (bottoms under tops;
  // of one kind, the one lying farther out where both already lie on the body, else the larger
  // outside). Before placement, which pushes outer pieces out of inner ones.
  {
    Stage stage(result, options, "layers");
    if (options.infer_layers && result.garments.size() > 1) {
      const std::size_t n = result.garments.size();
      std::vector<int> kind(n), legs(n);
      std::vector<double> area(n);
      std::vector<std::unordered_map<std::int64_t, double>> height(n);  // empty: not on the body
      for (std::size_t k = 0; k < n; ++k) {
        const DressedGarment& g = result.garments[k];
        kind[k] = is_top(g) ? 1 : 0;
        legs[k] = covers_legs(g) ? 1 : 0;
        area[k] = analyse_topology(g.mesh).area;
        if (on_body(surface_fit(g.mesh.V, inside), g.mesh.num_vertices(), body_height, options))
          height[k] = height_over_body(g.mesh.V, *body_distance, kLayerCell);
      }
      const auto outside = [&](std::size_t a, std::size_t b) {
        if (kind[a] != kind[b]) return kind[a] > kind[b];
        const int over = lies_outside(height[a], height[b]);
        if (over != 0) return over > 0;
        if (legs[a] != legs[b]) return legs[a] < legs[b];  // a suit or a dress under a top
        return area[a] > area[b];
      };
      // Insertion: a garment goes after every garment it lies outside (the relation need not be
      // transitive for three garments on the body, so no sort that assumes it).
      std::vector<std::size_t> order;
      for (std::size_t k = 0; k < n; ++k) {
        auto at = order.end();
        while (at != order.begin() && outside(*std::prev(at), k)) --at;
        order.insert(at, k);
      }
      std::vector<DressedGarment> garments;
      std::vector<Fabric> ordered_fabrics;
      for (std::size_t k : order) {
        garments.push_back(std::move(result.garments[k]));
        ordered_fabrics.push_back(fabrics[k]);
      }
      result.garments = std::move(garments);
      fabrics = std::move(ordered_fabrics);
    }
    for (std::size_t k = 0; k < result.garments.size(); ++k) result.garments[k].layer = static_cast<int>(k);
    std::string order;
    for (const DressedGarment& g : result.garments)
      order += (order.empty() ? "" : " < ") + g.name + (options.infer_layers ? (is_top(g) ? " (top)" : " (bottom)") : "");
    stage.done(result.garments.size() > 1,
               result.garments.size() < 2 ? "one garment: no layers to order"
               : options.infer_layers     ? "inside to outside, inferred from the garments' kinds (of one kind: the one lying farther out "
                                                            "where both lie on the body, else one without legs or a skirt "
                                                            "over one with, else the larger): " + order
                                          : "inside to outside as given: " + order);
  }

  // Placement, unless the garment already sits on this body. Garments to place are placed together,
  // as one outfit whose pieces are worn in the order given, so that their parts share one global
  // fit and outer pieces are pushed out of inner ones.
  {
    Stage stage(result, options, "placement");
    std::string report, names;
    TriangleMesh outfit;
    std::vector<std::size_t> to_place;
    std::vector<Eigen::Index> first;
    std::vector<int> layer_of;
    for (std::size_t k = 0; k < result.garments.size(); ++k) {
      DressedGarment& g = result.garments[k];
      g.crossings_authored = count_intersections(g.mesh.V, g.mesh.F);
      const SurfaceFit before = surface_fit(g.mesh.V, inside);
      const std::string as_given = " (mean distance " + number(100.0 * before.mean_distance / body_height, 2) +
                                   " % of its height, " + counted(before.inside, "vertex", "vertices") + " inside)";
      if (on_body(before, g.mesh.num_vertices(), body_height, options)) {
        g.placed = g.mesh.V;
        report += (report.empty() ? "" : "; ") + g.name + " already on the body" + as_given;
        continue;
      }
      // A sewn pattern that did not end on this body is not a garment placement can rescue: its
      // panels' places are for another body.
      if (g.from_pattern)
        throw InputError(g.file.path + ": sewn around this body, the garment is not on it" + as_given +
                         ": the pattern is placed for another body");
      report += (report.empty() ? "" : "; ") + g.name + " not on the body as given" + as_given;
      to_place.push_back(k);
      first.push_back(outfit.V.rows());
      append_mesh(outfit, g.mesh, "");
      layer_of.insert(layer_of.end(), static_cast<std::size_t>(g.mesh.num_vertices()), static_cast<int>(k));
      names += (names.empty() ? "" : ", ") + g.file.path;
    }
    if (!to_place.empty()) {
      first.push_back(outfit.V.rows());
      distinct_label_names(outfit);
      PlacementOptions o = options.placement;
      o.vertex_layers = Eigen::Map<const Eigen::VectorXi>(layer_of.data(), static_cast<Eigen::Index>(layer_of.size()));
      const PlacementResult p = place_garment(outfit, result.body, o);
      // The quality gate: a placement that shrank or blew the garments up, or left them off the body,
      // is refused rather than passed on.
      const double scale = p.global_scale;
      const SurfaceFit after = surface_fit(p.V, inside);
      if (!(scale >= 0.4 && scale <= 2.5) || after.mean_distance > 0.1 * body_height) {
        throw InputError(names + ": the placement does not fit the garment on the body (scale " + number(scale) +
                         ", mean distance to the body " + number(after.mean_distance) +
                         " m): check its units and that it is a garment for a person");
      }
      for (std::size_t i = 0; i < to_place.size(); ++i) {
        DressedGarment& g = result.garments[to_place[i]];
        g.placement = p;
        g.placed_by_placement = true;
        g.placed = p.V.middleRows(first[i], first[i + 1] - first[i]);
      }
      report += (report.empty() ? "" : "; ") + std::string(to_place.size() > 1 ? "placed together" : "placed") +
                " (scale " + number(scale) + ", " + std::to_string(p.matching.matches.size()) + " parts matched, " +
                p.global_method + ")";
    }
    for (std::size_t k = 0; k < result.garments.size(); ++k) {
      DressedGarment& g = result.garments[k];
      g.crossings_placed = g.crossings_fitted = count_intersections(g.placed, g.mesh.F);
      if (g.placed_by_placement && g.crossings_placed > g.crossings_authored) {
        untangle(result.garments, k, *body_distance, options.placement.clearance);
        untangle_along_path(result.garments, k);
        report += "; " + g.name + ": crossing itself " + counted(g.crossings_fitted, "time", "times") + " as fitted, " +
                  std::to_string(g.crossings_placed) + " after untangling (" +
                  std::to_string(g.crossings_authored) + " as authored)";
      }
      g.inside_placed = surface_fit(g.placed, inside).inside;
      // A garment placed with springs stretched beyond the simulator's blow-up strain cannot be
      // settled (its first length-limit pass pulls particles through the body): refused.
      if (!g.placed_by_placement) continue;
      const std::vector<double> strain = structural_strains(garment_cloth(g, fabrics[k]), g.placed);
      const double blow_up = SimulationOptions().blow_up_strain;
      if (!strain.empty() && strain.back() > blow_up)
        throw InputError(g.file.path + ": the placement stretches it by up to " + number(100.0 * strain.back(), 3) +
                         " % (more than " + number(100.0 * blow_up, 3) + " %): the garment does not fit this body as placed");
    }
    stage.done(!to_place.empty(), report);
  }

  // Thickness: each cloth's own thickness from its fabric keeps the layers apart.
  double separation = 0.0;
  {
    Stage stage(result, options, "thickness");
    std::string report;
    for (std::size_t k = 0; k < result.garments.size(); ++k) {
      DressedGarment& g = result.garments[k];
      const Fabric& f = fabrics[k];
      g.thickness = sheet_thickness(f.composition, f.areal_density);
      separation = std::max(separation, g.thickness);
      report += (report.empty() ? "" : ", ") + g.name + " " + number(1e3 * g.thickness, 2) + " mm";
    }
    report += " (mass per area over fibre density × solidity 0.25)";
    for (std::size_t k = 0; k < result.garments.size(); ++k) {
      DressedGarment& g = result.garments[k];
      if (!g.padded) continue;
      const ThicknessResult t = compute_thickness(fabrics[k].composition, options.padding);
      g.padding.thickness = t.thickness, g.padding.min = t.thickness_min, g.padding.max = t.thickness_max;
      report += "; " + g.name + " padded " + number(1e3 * t.thickness) + " mm (limits " + number(1e3 * t.thickness_min) +
                "–" + number(1e3 * t.thickness_max) + " mm) by heat conduction";
    }
    stage.done(true, report);
  }

  // Layers apart: each garment worn over another moved out over it by the separation, so that the
  // settle starts with the layers in order (its cloth–cloth collisions keep them so, but cannot
  // undo a crossing they start with).
  {
    Stage stage(result, options, "grading");
    if (result.garments.size() < 2) {
      stage.done(false, "one garment: no layers to grade");
    } else {
      const int before = crossings_between(result.garments, &DressedGarment::placed);
      const std::vector<Grading> graded = grade_layers(result.garments, body_distance, separation);
      std::string report;
      for (std::size_t k = 0; k < graded.size(); ++k) {
        if (graded[k].vertices == 0) continue;
        DressedGarment& g = result.garments[k];
        g.crossings_placed = count_intersections(g.placed, g.mesh.F);
        report += (report.empty() ? "" : "; ") + g.name + " moved out over " + result.garments[k - 1].name + ": " +
                  counted(graded[k].vertices, "vertex", "vertices") + ", by up to " + number(1e3 * graded[k].largest, 3) + " mm";
        // Moved out at an armpit or the crotch, where the body's normals of two parts face each
        // other, a placed garment's sleeve and side (or two legs) cross: it is moved onto its graded
        // positions from an uncrossed shape, its parts held apart on the way (as after placement).
        // A garment worn as authored settles its few new crossings out better from where grading
        // left it (the elegantsuit over the casualsuit: 7–11 crossings settled against 22–39, in
        // half the time).
        if (g.placed_by_placement && g.crossings_placed > g.crossings_authored) {
          const int graded_crossings = g.crossings_placed;
          untangle_along_path(result.garments, k);
          report += ", crossing itself " + counted(graded_crossings, "time", "times") + ", " + std::to_string(g.crossings_placed) +
                    " after untangling (" + std::to_string(g.crossings_authored) + " as authored)";
        }
        g.inside_placed = surface_fit(g.placed, inside).inside;
      }
      if (report.empty()) {
        stage.done(false, "every garment already lies over the one beneath it");
      } else {
        const int after = crossings_between(result.garments, &DressedGarment::placed);
        stage.done(true, report + "; the garments cross each other " + counted(after, "time", "times") + " (" +
                             std::to_string(before) + " before)");
      }
    }
  }

  // Settle.
  for (DressedGarment& g : result.garments) g.dressed = g.placed;
  double duration = 1.0;
  SimulationOptions o = simulation_options(options.quality, duration);
  if (options.settle_seconds > 0.0) duration = options.settle_seconds;
  o.colliders.push_back(Collider::mesh(body_distance));
  // A garment sewn from a pattern holds springs at their length limit for good where its seams join
  // edges of unequal length: the adaptive step leaves them out of the strain rise it judges.
  const bool sewn = std::any_of(result.garments.begin(), result.garments.end(),
                                [](const DressedGarment& g) { return g.from_pattern; });
  o.rise_skips_held_springs = sewn;
  std::vector<std::vector<int>> bands;  // trousers and skirts stay up by their waistband, held as by a belt
  {
    Stage stage(result, options, "settle");
    if (!options.settle) {
      stage.done(false, "not asked for");
    } else {
      std::vector<ClothModel> models;
      for (std::size_t k = 0; k < result.garments.size(); ++k)
        models.push_back(garment_cloth(result.garments[k], fabrics[k]));
      // A garment reaching above three quarters of the body's height hangs from its shoulders.
      const double shoulders = result.body.V.col(1).minCoeff() + 0.75 * body_height;
      const std::vector<int> first = garment_offsets(models);
      const ClothModel model = models.size() == 1 ? models[0] : stack_layers(models, separation);
      for (DressedGarment& g : result.garments) {
        bands.push_back(waistband(g, rest_shape(g).V, options.waistband, o.strain_limit, inside, shoulders));
        g.waistband_vertices = static_cast<int>(bands.back().size());
      }
      RunOptions run_options;
      run_options.duration = duration;
      std::optional<ClothSimulator> sim;
      // Particles held where placed besides the waistbands (garment vertex indices per garment).
      std::vector<std::vector<int>> hold(result.garments.size());
      auto settle = [&] {
        sim.emplace(model, o);
        Eigen::MatrixX3d x(model.rest_positions.rows(), 3);
        std::vector<int> belt;
        for (std::size_t k = 0; k < result.garments.size(); ++k) {
          x.middleRows(first[k], first[k + 1] - first[k]) = result.garments[k].placed;
          for (int v : bands[k]) belt.push_back(first[k] + v);
          for (int v : hold[k]) belt.push_back(first[k] + v);
        }
        sim->set_state(x, Eigen::MatrixX3d::Zero(x.rows(), 3));
        if (!belt.empty()) sim->set_pinned(belt);
        result.settle_time.clear(), result.settle_energy.clear(), result.settle_strain.clear();
        // Sampled at most kSettleSamples times (the elastic energy costs about a millisecond for 7k
        // particles, 5 % of a step) and after the last step.
        auto sample = [&](double strain) {
          result.settle_time.push_back(sim->time());
          result.settle_energy.push_back(sim->elastic_energy());
          result.settle_strain.push_back(strain);
        };
        double next_sample = 0.0;
        result.settle = run(*sim, run_options, {}, [&](const StepResult& step) {
          if (step.ok && sim->time() >= next_sample) {
            sample(step.strain);
            next_sample = sim->time() + duration / kSettleSamples;
          }
          if (options.on_settle) options.on_settle(sim->time(), duration);
        });
        if (result.settle_time.empty() || result.settle_time.back() < sim->time()) sample(sim->max_strain());
      };
      // A garment untangled by holding its parts apart may be pressed between them and the body
      // tighter than its length limits allow: the contacts then raise its strain at every step by
      // more than the adaptive step allows, however short, and the settle stalls. It settles again
      // from the same placement allowing twice the rise a step, and four times where that stalls
      // too. The least that gets past the jam is used: the larger steps it allows crumple cloth
      // pressed between body and cloth (a pattern's hoody carried to the 11-year-old girl: 27
      // crossings and a panel 19 % larger at four times, 7 crossings and panels within 3 % at twice).
      std::string held;
      const double allowed = o.max_strain_change;
      const auto settle_through_jams = [&] {
        std::vector<std::string> retries;
        o.max_strain_change = allowed;
        settle();
        for (const double factor : {2.0, 4.0}) {
          if (!result.settle.stalled) break;
          retries.push_back("settling " + result.settle.stopped_reason + ", settled again allowing a rise in strain of " +
                            number(factor * allowed) + " a step");
          held += "; " + retries.back();
          o.max_strain_change = factor * allowed;
          settle();
        }
        result.settle.warnings.insert(result.settle.warnings.begin(), retries.begin(), retries.end());
      };
      settle_through_jams();
      const auto own_crossings = [&](std::size_t k) {
        return count_intersections(sim->positions().middleRows(first[k], first[k + 1] - first[k]),
                                   result.garments[k].mesh.F);
      };
      // Settles again by `run`; the new run is kept where it ends with fewer crossings of the
      // garments' own than `before`, otherwise the earlier run is put back and `undo` called. `held`
      // says which (and what the kept run said of itself).
      const auto settle_again = [&](const std::string& how, int before, const std::function<void()>& run,
                                    const std::function<void()>& undo) {
        std::optional<ClothSimulator> earlier = std::move(sim);
        const RunResult earlier_run = result.settle;
        const std::vector<double> t = result.settle_time, e = result.settle_energy, st = result.settle_strain;
        const std::string said = held;
        run();
        const std::string its_own = held.substr(said.size());
        held = said + "; settled again " + how;
        int after = 0;
        for (std::size_t k = 0; k < result.garments.size(); ++k) after += own_crossings(k);
        if (result.settle.ok && after < before) {
          held += " (" + std::to_string(before) + " → " + counted(after, "crossing", "crossings") + ")" + its_own;
          return;
        }
        held += ", not kept (" + (result.settle.ok ? counted(after, "crossing", "crossings") + " against " + std::to_string(before)
                                                   : result.settle.stopped_reason) + ")";
        sim = std::move(earlier);
        result.settle = earlier_run;
        result.settle_time = t, result.settle_energy = e, result.settle_strain = st;
        undo();
      };
      // With a garment sewn from a pattern the adaptive step leaves the springs held at their length
      // limit out of the rise it judges. The longer steps that allows can let cloth pressed between
      // body and cloth pass through itself (the shirt carried by parts to MakeHuman's woman: 6
      // crossings in one trial of three, none when they are judged): a settle that leaves a garment
      // crossing itself more often than sewn runs again judging them.
      std::vector<int> own(result.garments.size());
      const auto count_own = [&] {
        for (std::size_t k = 0; k < result.garments.size(); ++k) own[k] = own_crossings(k);
      };
      count_own();
      bool more = false;  // a pattern's garment crossing itself more often than sewn
      for (std::size_t k = 0; k < result.garments.size(); ++k)
        more = more || (result.garments[k].from_pattern && own[k] > result.garments[k].crossings_authored);
      if (result.settle.ok && o.rise_skips_held_springs && more) {
        const double change = o.max_strain_change;
        o.rise_skips_held_springs = false;
        settle_again("judging the springs held at their length limit", std::accumulate(own.begin(), own.end(), 0),
                     settle_through_jams, [&] {
                       o.rise_skips_held_springs = true;
                       o.max_strain_change = change;
                     });
        count_own();
      }
      // Cloth–cloth collisions leave out pairs whose sides both lie in a crossing at a step's
      // start, so that a garment can drape out of the crossings placement left; but where a garment
      // crosses itself as authored (layered details: folded hems, lapels through a jacket), its
      // tangled parts may pass further through each other instead. A settle that leaves a garment
      // crossing itself more often than as authored is run again with the particles of the
      // crossings it has both as authored and as placed held where they were placed; the run with
      // fewer crossings is kept.
      int tangled = 0;
      for (std::size_t k = 0; k < result.garments.size(); ++k) {
        const DressedGarment& g = result.garments[k];
        if (own[k] <= g.crossings_authored) continue;
        const std::vector<int> authored = crossing_vertices(g.mesh.V, g.mesh.F), placed = crossing_vertices(g.placed, g.mesh.F);
        std::set_intersection(authored.begin(), authored.end(), placed.begin(), placed.end(), std::back_inserter(hold[k]));
        tangled += static_cast<int>(hold[k].size());
      }
      if (result.settle.ok && tangled > 0)
        settle_again("holding " + std::to_string(tangled) + " particles of the garments' own crossings as authored",
                     std::accumulate(own.begin(), own.end(), 0), settle, [&] {
                       for (auto& h : hold) h.clear();
                     });
      result.settled = true;
      std::string belts;
      for (std::size_t k = 0; k < result.garments.size(); ++k) {
        DressedGarment& g = result.garments[k];
        g.dressed = sim->positions().middleRows(first[k], first[k + 1] - first[k]);
        g.tangle_held_vertices = static_cast<int>(hold[k].size());
        if (g.waistband_vertices > 0)
          belts += "; waistband of " + g.name + " held (" + counted(g.waistband_vertices, "vertex", "vertices") + ")";
      }
      held = belts + held;
      stage.done(true, counted(result.settle.totals.steps, "step", "steps") + ", " + number(sim->time()) +
                           " s simulated, " + result.settle.stopped_reason + held);
    }
  }

  // Padding: padded garments become double layers over the settled outfit.
  {
    Stage stage(result, options, "padding");
    const bool any = std::any_of(result.garments.begin(), result.garments.end(), [](const DressedGarment& g) { return g.padded; });
    if (!any) {
      stage.done(false, "no padded garment");
    } else if (!result.settled || !result.settle.ok) {
      stage.done(false, "padding grows over the settled garments: not settled");
    } else {
      o.rise_skips_held_springs = sewn;  // as the settle began, whichever settle was kept
      const PaddingRun p = pad_garments(result.garments, fabrics, *body_distance, o, separation, duration, bands, options.on_settle);
      result.padding_ran = true;
      result.padding_settle = p.run;
      std::string report;
      for (const DressedGarment& g : result.garments)
        if (g.padded)
          report += (report.empty() ? "" : "; ") + g.name + " " + number(1e3 * g.padding.thickness) + " mm asked, shells " +
                    number(1e3 * g.padding.gap_min) + "–" + number(1e3 * g.padding.gap_max) + " mm apart (median " +
                    number(1e3 * g.padding.gap_median) + "), " + std::to_string(g.padding.start_at_full) + " of " +
                    counted(g.dressed.rows(), "vertex", "vertices") + " started at the full thickness";
      stage.done(true, report + "; " + counted(p.run.totals.steps, "step", "steps") + ", " + number(p.simulated) +
                           " s simulated, " + p.run.stopped_reason);
    }
  }

  result.layer_crossings = crossings_between(result.garments, &DressedGarment::dressed);
  if (result.layer_crossings > 0)
    result.warnings.push_back("the garments cross each other " + counted(result.layer_crossings, "time", "times"));
  for (std::size_t k = 0; k < result.garments.size(); ++k) {
    DressedGarment& g = result.garments[k];
    g.crossings_dressed = count_intersections(g.dressed, g.mesh.F);
    g.inside_dressed = surface_fit(g.dressed, inside).inside;
    const std::vector<double> strain = structural_strains(garment_cloth(g, fabrics[k]), g.dressed);
    if (!strain.empty()) {
      g.max_strain_dressed = std::max(0.0, strain.back());
      g.strain_p99_dressed = std::max(0.0, strain[strain.size() * 99 / 100]);
      g.springs_over_limit = static_cast<int>(strain.end() - std::upper_bound(strain.begin(), strain.end(), kOverLimit));
    }
    if (g.from_pattern && result.settled) measure_dressed_panels(g);
    g.warnings = dressed_warnings(g, result.padding_ran && result.padding_settle.stalled ? result.padding_settle.stopped_reason : "");
    if (k == 0) continue;
    const DressedGarment& inner = result.garments[k - 1];
    const Gap gap = layer_gap(g.dressed, inner.padded && inner.dressed_outer.rows() > 0 ? inner.dressed_outer : inner.dressed,
                              inner.mesh.F, 0.02);
    result.layer_gap_p5.push_back(gap.p5);
    result.layer_gap_median.push_back(gap.median);
    result.layer_gap_vertices.push_back(gap.vertices);
    result.layer_gap_asked.push_back(separation);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace dresskit::dressing
