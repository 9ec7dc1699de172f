#include "pattern_garment.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "dresskit/alignment/icp.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/pattern/sew.h"

using namespace dresskit::mesh;
using namespace dresskit::pattern;

namespace dresskit::dressing::detail {

namespace {

enum Part { kTorso, kHead, kArmLeft, kArmRight, kLegLeft, kLegRight, kOther, kParts };
const char* const kPartNames[kParts] = {"torso", "head", "arm_left", "arm_right", "leg_left", "leg_right", "other"};

// A part name of the segmentation or of a label file (../shared/data/labels: `arm_left`,
// `left_arm`, `head_neck`, `body` for torso and head) as one of the parts above.
Part part_of(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto has = [&](const char* word) { return name.find(word) != std::string::npos; };
  const bool left = has("left"), right = has("right");
  if (has("arm")) return left ? kArmLeft : right ? kArmRight : kOther;
  if (has("leg")) return left ? kLegLeft : right ? kLegRight : kOther;
  if (has("head") || has("neck")) return kHead;
  if (has("torso") || name == "body") return kTorso;
  return kOther;
}

// Where a labelled body's parts lie: each part's centroid, and where it meets the torso (the
// midpoints of the edges between the two, averaged).
struct Skeleton {
  std::vector<Part> part;  // per vertex
  std::array<Eigen::Vector3d, kParts> centroid, root;
  std::array<bool, kParts> has_root{};
};

Skeleton skeleton(const TriangleMesh& m) {
  Skeleton s;
  s.part.assign(static_cast<std::size_t>(m.V.rows()), kOther);
  std::array<int, kParts> count{}, joins{};
  s.centroid.fill(Eigen::Vector3d::Zero());
  s.root.fill(Eigen::Vector3d::Zero());
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const int l = v < m.labels.size() ? m.labels[v] : -1;
    const Part p = l >= 0 && std::size_t(l) < m.label_names.size() ? part_of(m.label_names[std::size_t(l)]) : kOther;
    s.part[std::size_t(v)] = p;
    s.centroid[p] += m.V.row(v).transpose();
    ++count[p];
  }
  for (int p = 0; p < kParts; ++p)
    if (count[p] > 0) s.centroid[p] /= count[p];
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = m.F(f, c), b = m.F(f, (c + 1) % 3);
      const Part pa = s.part[std::size_t(a)], pb = s.part[std::size_t(b)];
      if (pa == pb || (pa != kTorso && pb != kTorso)) continue;
      const Part other = pa == kTorso ? pb : pa;
      s.root[other] += 0.5 * (m.V.row(a) + m.V.row(b)).transpose();
      ++joins[other];
    }
  for (int p = 0; p < kParts; ++p)
    if (joins[p] > 0) {
      s.root[p] /= joins[p];
      s.has_root[p] = count[p] > 0;
    }
  return s;
}

// The move of a limb: turned about where it meets the torso, in the body's frontal plane (about
// +Z), so that its direction from there to its centroid, seen from the front, becomes the other
// body's; and moved with that point. Turned forward or back as well, a sleeve's inner end would
// sweep through the torso's panels beside it (the shirt on MakeHuman's man, whose arms reach
// forward: 81 crossings before sewing); seen from the front the panels stay clear of each other.
Eigen::Matrix4d limb_move(const Skeleton& from, const Skeleton& to, Part p) {
  Eigen::Vector3d a = from.centroid[p] - from.root[p], b = to.centroid[p] - to.root[p];
  a.z() = 0.0;
  b.z() = 0.0;
  const Eigen::Matrix3d R = a.norm() > 1e-9 && b.norm() > 1e-9
                                ? Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix()
                                : Eigen::Matrix3d::Identity();  // a limb straight along +Z: not turned
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = to.root[p] - R * from.root[p];
  return T;
}

}  // namespace

PanelMoves panel_moves(const Eigen::MatrixX3d& placed, const Eigen::VectorXi& panel_of_vertex, int panels,
                       const TriangleMesh& from, const TriangleMesh& to) {
  const Skeleton a = skeleton(from), b = skeleton(to);
  const auto both = [&](Part p) { return a.has_root[p] && b.has_root[p]; };
  // The torso's move by height: anchors at the hips, the shoulders and the neck (those both bodies
  // have), linear between them and constant beyond; without any, the torsos' centroids.
  std::vector<std::pair<double, Eigen::Vector3d>> anchors;
  const auto anchor = [&](Part p, Part q) {
    if (!both(p) || !both(q)) return;
    const Eigen::Vector3d at = 0.5 * (a.root[p] + a.root[q]);
    anchors.push_back({at.y(), 0.5 * (b.root[p] + b.root[q]) - at});
  };
  anchor(kLegLeft, kLegRight);
  anchor(kArmLeft, kArmRight);
  anchor(kHead, kHead);
  std::sort(anchors.begin(), anchors.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const auto torso_move = [&](double y) -> Eigen::Vector3d {
    if (anchors.empty()) return b.centroid[kTorso] - a.centroid[kTorso];
    if (y <= anchors.front().first) return anchors.front().second;
    for (std::size_t k = 1; k < anchors.size(); ++k)
      if (y <= anchors[k].first) {
        const double t = (y - anchors[k - 1].first) / std::max(anchors[k].first - anchors[k - 1].first, 1e-9);
        return (1.0 - t) * anchors[k - 1].second + t * anchors[k].second;
      }
    return anchors.back().second;
  };
  const alignment::PointLocator nearest(from.V), onto(to.V);
  PanelMoves r;
  for (int q = 0; q < panels; ++q) {
    std::vector<Eigen::Index> points;
    for (Eigen::Index v = 0; v < placed.rows(); ++v)
      if (panel_of_vertex[v] == q) points.push_back(v);
    std::array<int, kParts> votes{};
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    const std::size_t stride = std::max<std::size_t>(1, points.size() / 64);
    int sampled = 0;
    for (std::size_t k = 0; k < points.size(); k += stride, ++sampled) {
      const Eigen::Vector3d p = placed.row(points[k]).transpose();
      ++votes[a.part[std::size_t(nearest.nearest(p))]];
      centre += p;
    }
    if (sampled > 0) centre /= sampled;
    Part follows = kTorso;
    for (const Part limb : {kArmLeft, kArmRight})
      if (2 * votes[limb] > sampled && both(limb)) follows = limb;
    for (const Part limb : {kLegLeft, kLegRight})
      if (5 * votes[limb] > 4 * sampled && both(limb)) follows = limb;
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    if (follows == kTorso)
      T.topRightCorner<3, 1>() = torso_move(centre.y());
    else
      T = limb_move(a, b, follows);
    // Kept as far from the body as the pattern places it: a panel that its move brought nearer to
    // this body (its least distance to the body's vertices, over the points sampled) is moved out
    // along its normal by the difference.
    if (sampled >= 3) {
      const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
      const Eigen::Vector3d t = T.topRightCorner<3, 1>();
      double before = HUGE_VAL, after = HUGE_VAL;
      Eigen::Vector3d closest = Eigen::Vector3d::Zero();
      Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
      for (std::size_t k = 0; k < points.size(); k += stride) {
        const Eigen::Vector3d p = placed.row(points[k]).transpose();
        scatter += (p - centre) * (p - centre).transpose();
        double d2 = 0.0;
        const int j = nearest.nearest(p, &d2);
        if (std::sqrt(d2) < before) {
          before = std::sqrt(d2);
          closest = from.V.row(j).transpose();
        }
        onto.nearest(R * p + t, &d2);
        after = std::min(after, std::sqrt(d2));
      }
      Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
      if (normal.dot(centre - closest) < 0.0) normal = -normal;  // away from the body
      if (after < before) T.topRightCorner<3, 1>() += (before - after) * (R * normal);
    }
    r.moves.push_back(T);
    r.parts.push_back(kPartNames[follows]);
  }
  return r;
}

bool is_pattern_garment(const GarmentFile& g) {
  return !g.file.mesh && pattern::is_pattern_file(g.file.path);
}

void sew_pattern_garment(const GarmentFile& g, const TriangleMesh& body, const LoadOptions& body_units,
                         const std::shared_ptr<const cloth::MeshDistance>& body_distance,
                         const DressOptions& options, const PartBodies& parts, DressedGarment& d) {
  const pattern::Pattern p = pattern::read_pattern(g.file.path);
  pattern::CutOptions cut_options;
  cut_options.edge_length = options.pattern_edge_length;
  const pattern::CutPattern cut = pattern::cut_pattern(p, cut_options);
  pattern::SewOptions sew_options;
  sew_options.fabric = d.fabric;
  sew_options.tolerance = options.seam_tolerance;
  sew_options.weld_gap = options.pattern_edge_length;
  std::vector<std::string> panel_parts;
  if (parts.pattern_body && parts.body) {
    PanelMoves moves = panel_moves(cut.placed, cut.panel_of_vertex, static_cast<int>(p.panels.size()),
                                   *parts.pattern_body, *parts.body);
    sew_options.panel_moves = std::move(moves.moves);
    panel_parts = std::move(moves.parts);
  }
  if (options.on_sew) {
    const std::string name = d.name;
    const int pairs = static_cast<int>(cut.stitch_pairs.size());
    options.on_sew(name, pairs, 0.0, sew_options.max_seconds);
    sew_options.on_step = [&options, name, pairs](double done, double total) { options.on_sew(name, pairs, done, total); };
  }
  const pattern::SewResult sewn = [&] {
    try {
      return pattern::sew_pattern(p, cut, body, sew_options, body_distance);
    } catch (const InputError& e) {
      throw InputError(g.file.path + ": " + e.what());
    }
  }();
  SewnPattern& s = d.pattern;
  d.from_pattern = true;
  d.mesh = sewn.garment;
  d.mesh.labels.resize(0);  // panels are not body parts: the garment is segmented like a mesh
  d.mesh.label_names.clear();
  d.file.load = body_units;  // sewn around the body: its outputs are in the body's units and axes
  s.panels.clear();
  for (const pattern::Panel& panel : p.panels) s.panels.push_back(panel.name);
  s.panel_area.assign(cut.triangle_area.data(),
                      cut.triangle_area.data() + cut.triangle_area.size());
  s.panel_faces.resize(cut.faces.rows(), 3);
  for (Eigen::Index f = 0; f < cut.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) s.panel_faces(f, k) = sewn.welded_vertex[cut.faces(f, k)];
  s.panel_of_face = cut.panel_of_face;
  // Texture coordinates from the flat pattern: the welded garment's faces are the cut faces whose
  // welded corners stayed apart, in order; each corner keeps its panel's flat position.
  d.mesh.TC = pattern::texture_coordinates(p, cut);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < s.panel_faces.rows(); ++f) {
    const int a = s.panel_faces(f, 0), b = s.panel_faces(f, 1), c = s.panel_faces(f, 2);
    if (a != b && b != c && a != c) kept.push_back(f);
  }
  if (Eigen::Index(kept.size()) == d.mesh.num_faces()) {
    d.mesh.FTC = cut.faces(kept, Eigen::all);
    d.mesh.face_groups = cut.panel_of_face(kept);  // the panels, as OBJ groups
    d.mesh.group_names = s.panels;
  } else {
    d.mesh.TC.resize(0, 2);
  }
  // Flat lengths of the triangles' edges, keyed by their welded ends.
  std::map<std::array<int, 2>, std::pair<double, int>> flat;
  for (Eigen::Index f = 0; f < cut.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = cut.faces(f, c), b = cut.faces(f, (c + 1) % 3);
      const int u = sewn.welded_vertex[a], v = sewn.welded_vertex[b];
      if (u == v) continue;
      auto& [sum, count] = flat[{std::min(u, v), std::max(u, v)}];
      sum += (cut.flat.row(a) - cut.flat.row(b)).norm();
      ++count;
    }
  s.flat_edges.clear();
  s.flat_edge_length.clear();
  for (const auto& [edge, length] : flat) {
    s.flat_edges.push_back(edge);
    s.flat_edge_length.push_back(length.first / length.second);
  }
  s.stitches = static_cast<int>(p.stitches.size());
  s.stitch_pairs = sewn.stitch_pairs;
  s.sewn_pairs = sewn.closed_pairs;
  s.welded_open_pairs = sewn.welded_open;
  s.sew_method = sewn.method;
  s.sew_stopped = sewn.stopped;
  s.sew_steps = sewn.steps;
  s.sew_contacts = sewn.contacts;
  s.max_gap = sewn.max_gap;
  s.closed = sewn.closed;
  s.unwelded = sewn.unwelded;
  s.moved_by = sewn.moved_by;
  s.carried_by = !panel_parts.empty() ? "parts" : sewn.moved_by.isZero() ? "as placed" : "frames";
  s.panel_parts = std::move(panel_parts);
  s.panels_moved_out = sewn.panels_moved_out;
  s.triangles = static_cast<int>(sewn.garment.F.rows());
  s.cut_seconds = cut.seconds;
  s.sew_seconds = sewn.seconds;
  s.sew_simulated = sewn.simulated_seconds;
  s.warnings = p.warnings;
  if (!sewn.closed) {
    // The stitch furthest from closed, named: its pairs that were sewn, or came within the cut's
    // edge length, are welded, the rest stay open.
    const auto widest =
        std::max_element(sewn.stitch_gap.begin(), sewn.stitch_gap.end()) - sewn.stitch_gap.begin();
    const pattern::Stitch& st = p.stitches[static_cast<std::size_t>(widest)];
    const double gap = sewn.stitch_gap[static_cast<std::size_t>(widest)];
    if (gap > options.max_open_seam)
      throw InputError(g.file.path + ": stitch " + std::to_string(widest) + " (" +
                       p.edge_name(st.a.panel, st.a.edge) + " to " + p.edge_name(st.b.panel, st.b.edge) +
                       ") is still " + std::to_string(int(std::lround(1e3 * gap))) + " mm open after sewing (" +
                       sewn.stopped + "): the pattern does not sew on this body" +
                       (sewn.moved_by.isZero() ? std::string("; is it placed for another?")
                                               : std::string(" (carried from the body it is placed for)")));
    // How many pairs stay open is the dressed garment's warning (dressed_warnings).
    char open_mm[32], after[32];
    std::snprintf(open_mm, sizeof open_mm, "%.3g", 1e3 * sewn.stitch_gap[static_cast<std::size_t>(widest)]);
    std::snprintf(after, sizeof after, "%.3g", sewn.simulated_seconds);
    s.warnings.push_back(g.file.path + ": stitch " + std::to_string(widest) + " (" + p.edge_name(st.a.panel, st.a.edge) +
                         " to " + p.edge_name(st.b.panel, st.b.edge) + ") is still " + open_mm + " mm open after " +
                         after + " s of sewing" +
                         (sewn.closed_pairs + sewn.welded_open == sewn.stitch_pairs ? "; welded shut" : ""));
  }
}

void measure_dressed_panels(DressedGarment& d) {
  SewnPattern& s = d.pattern;
  s.panel_area_dressed.clear();
  if (!d.from_pattern || d.dressed.rows() != d.mesh.num_vertices() ||
      (s.panel_faces.size() > 0 && s.panel_faces.maxCoeff() >= d.dressed.rows()))
    return;
  s.panel_area_dressed.assign(s.panels.size(), 0.0);
  for (Eigen::Index f = 0; f < s.panel_faces.rows(); ++f) {
    const Eigen::Vector3d a = d.dressed.row(s.panel_faces(f, 0)),
                          b = d.dressed.row(s.panel_faces(f, 1)),
                          c = d.dressed.row(s.panel_faces(f, 2));
    s.panel_area_dressed[static_cast<std::size_t>(s.panel_of_face[f])] +=
        0.5 * (b - a).cross(c - a).norm();
  }
}

}  // namespace dresskit::dressing::detail
