#include "dresskit/alignment/placement.h"

#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <set>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

using namespace dresskit::mesh;

namespace dresskit::alignment {
namespace {

using Junction = std::pair<std::string, std::string>;  // part names, sorted

Junction junction(const std::string& a, const std::string& b) {
  return a < b ? Junction{a, b} : Junction{b, a};
}

// Centroid of the vertices on each boundary between two labelled parts. On a garment the boundary
// loop surrounds the limb or neck just like the body's does, so the two centroids are the same
// anatomical point (a shoulder, a hip, the neck) whatever the ease of the garment.
std::map<Junction, Eigen::Vector3d> junction_centroids(const TriangleMesh& mesh) {
  std::map<Junction, std::set<int>> members;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), v = mesh.F(f, (k + 1) % 3);
      const int a = mesh.labels(u), b = mesh.labels(v);
      if (a < 0 || b < 0 || a == b) continue;
      auto& set = members[junction(mesh.label_names[a], mesh.label_names[b])];
      set.insert(u);
      set.insert(v);
    }
  }
  std::map<Junction, Eigen::Vector3d> out;
  for (const auto& [key, set] : members) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int v : set) sum += mesh.V.row(v).transpose();
    out[key] = sum / static_cast<double>(set.size());
  }
  return out;
}

// Least-squares similarity (Umeyama) mapping the columns of X onto the columns of Y.
Eigen::Matrix4d umeyama_similarity(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& Y) {
  return Eigen::umeyama(X, Y, true);
}

std::vector<int> rows_with_label(const TriangleMesh& mesh, int label) {
  std::vector<int> rows;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.labels(v) == label) rows.push_back(v);
  return rows;
}

PointSet gather(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& N,
                const std::vector<int>& rows) {
  PointSet p;
  p.V.resize(rows.size(), 3);
  if (N.rows()) p.N.resize(rows.size(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    p.V.row(k) = V.row(rows[k]);
    if (N.rows()) p.N.row(k) = N.row(rows[k]);
  }
  return p;
}

int label_of(const TriangleMesh& mesh, const std::string& name) {
  const auto it = std::find(mesh.label_names.begin(), mesh.label_names.end(), name);
  return it == mesh.label_names.end() ? -1 : static_cast<int>(it - mesh.label_names.begin());
}

double rotation_angle_deg(const Eigen::Matrix4d& T) {
  const Eigen::Matrix3d A = T.block<3, 3>(0, 0);
  const Eigen::Matrix3d R = A / std::cbrt(A.determinant());
  return std::acos(std::clamp((R.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

PlacementResult place_garment(const TriangleMesh& garment, const TriangleMesh& body,
                              const PlacementOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Options a placement cannot use, named before any work (a negative clearance pulled the garment
  // into the body).
  auto require = [](bool ok, const char* what, double value) {
    if (!ok) throw InputError(std::string("placement: ") + what + " " + std::to_string(value) + " is out of range");
  };
  require(options.clearance >= 0.0 && std::isfinite(options.clearance), "clearance [m]", options.clearance);
  require(options.blend_radius >= 0.0 && std::isfinite(options.blend_radius), "blend radius [m]", options.blend_radius);
  require(options.max_edge_stretch > 0.0 && std::isfinite(options.max_edge_stretch), "largest edge stretch",
          options.max_edge_stretch);
  require(std::isfinite(options.layer_gap), "layer gap [m]", options.layer_gap);
  require(options.max_part_scale_change >= 1.0 && std::isfinite(options.max_part_scale_change),
          "largest part scale change", options.max_part_scale_change);
  require(options.max_part_rotation_deg >= 0.0 && options.max_part_rotation_deg <= 180.0,
          "largest part rotation [degrees]", options.max_part_rotation_deg);
  require(options.push_iterations >= 0 && options.stretch_sweeps >= 0 && options.min_part_vertices >= 1,
          "rounds, sweeps or smallest part", std::min({options.push_iterations, options.stretch_sweeps,
                                                       options.min_part_vertices}));
  if (!garment.has_labels()) throw InputError("garment: no part labels (give --garment-labels)");
  if (!body.has_labels()) throw InputError("body: no part labels (give --body-labels)");
  check_point_set(PointSet{garment.V, {}}, "garment");
  check_point_set(PointSet{body.V, {}}, "body");

  PlacementResult out;
  out.matching = match_parts(describe_parts(garment), describe_parts(body), options.matching);
  if (out.matching.matches.empty())
    throw InputError("garment: no garment part matches a body part");
  std::map<std::string, std::string> body_part_of;
  for (const auto& m : out.matching.matches) body_part_of[m.garment_part] = m.body_part;

  // Global similarity from the junctions that both sides have.
  const auto gj = junction_centroids(garment), bj = junction_centroids(body);
  std::vector<Eigen::Vector3d> from, to;
  for (const auto& [key, centre] : gj) {
    if (!body_part_of.count(key.first) || !body_part_of.count(key.second)) continue;
    const auto it = bj.find(junction(body_part_of[key.first], body_part_of[key.second]));
    if (it == bj.end()) continue;
    from.push_back(centre);
    to.push_back(it->second);
    out.junctions.push_back(key.first + "|" + key.second);
  }
  bool spread = false;
  if (from.size() >= 3) {
    Eigen::Matrix3Xd X(3, from.size());
    for (std::size_t k = 0; k < from.size(); ++k) X.col(k) = from[k];
    const Eigen::Matrix3Xd C = X.colwise() - X.rowwise().mean();
    const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(C);
    spread = svd.singularValues()(1) > 1e-3 * svd.singularValues()(0);  // not all on one line
  }
  const Eigen::MatrixX3d body_normals = vertex_normals(body.V, body.F);
  // Candidates: the similarity of the junctions (three or more spread landmarks; or two, both
  // meshes upright: a t-shirt's shoulders, trousers' hips) and the multi-start ICP of the whole
  // garment onto the whole body. Junction centroids of a garment's openings and of a body's cuts are
  // not the same points, and ICP alone may shrink a garment onto the wrong limb; the candidate whose
  // parts lie nearest their matched body parts (mean distance) is kept.
  std::vector<std::pair<Eigen::Matrix4d, std::string>> candidates;
  if (spread) {
    Eigen::Matrix3Xd X(3, from.size()), Y(3, to.size());
    for (std::size_t k = 0; k < from.size(); ++k) {
      X.col(k) = from[k];
      Y.col(k) = to[k];
    }
    candidates.emplace_back(umeyama_similarity(X, Y), "junctions (" + std::to_string(from.size()) + " landmarks)");
  } else if (from.size() == 2 && (from[1] - from[0]).norm() > 0.0 && (to[1] - to[0]).norm() > 0.0) {
    const Eigen::Vector3d a = from[1] - from[0], b = to[1] - to[0];
    const double yaw = std::atan2(b.x(), b.z()) - std::atan2(a.x(), a.z());
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const double s = b.norm() / a.norm();
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.block<3, 3>(0, 0) = s * R;
    T.block<3, 1>(0, 3) = 0.5 * (to[0] + to[1]) - s * R * 0.5 * (from[0] + from[1]);
    candidates.emplace_back(T, "junctions (2 landmarks, upright)");
  }
  if (!candidates.empty()) {
    // The junctions' fit refined by ICP (with scale) of the matched garment parts onto their body parts.
    std::vector<int> grows, brows;
    for (const auto& m : out.matching.matches) {
      for (int v : rows_with_label(garment, label_of(garment, m.garment_part))) grows.push_back(v);
      for (int v : rows_with_label(body, label_of(body, m.body_part))) brows.push_back(v);
    }
    std::sort(brows.begin(), brows.end());
    brows.erase(std::unique(brows.begin(), brows.end()), brows.end());
    if (grows.size() >= 3 && brows.size() >= 3) {
      IcpOptions o;
      o.with_scale = true;
      const IcpResult r = icp_align(gather(garment.V, {}, grows), gather(body.V, body_normals, brows), o,
                                    candidates.front().first);
      candidates.emplace_back(r.transform, candidates.front().second + " refined by ICP");
    }
  }
  {
    GlobalOptions g;
    g.with_scale = true;
    candidates.emplace_back(global_align(PointSet{garment.V, {}}, PointSet{body.V, body_normals}, g).result.transform,
                            "multi-start ICP");
  }
  double best = HUGE_VAL;
  for (const auto& [T, method] : candidates) {
    double sum = 0.0;
    int count = 0;
    for (const auto& m : out.matching.matches) {
      const std::vector<int> grows = rows_with_label(garment, label_of(garment, m.garment_part));
      const std::vector<int> brows = rows_with_label(body, label_of(body, m.body_part));
      if (grows.empty() || brows.empty()) continue;
      const PointLocator near(gather(body.V, {}, brows).V);
      const Eigen::MatrixX3d moved = transform_points(T, gather(garment.V, {}, grows).V);
      for (Eigen::Index i = 0; i < moved.rows(); ++i) {
        double d2 = 0.0;
        near.nearest(moved.row(i).transpose(), &d2);
        sum += std::sqrt(d2);
        ++count;
      }
    }
    const double score = count ? sum / count : HUGE_VAL;
    if (score < best) {
      best = score;
      out.global = T;
      out.global_method = method;
    }
  }
  if (out.global_method == "multi-start ICP") out.junctions.clear();
  out.global_scale = std::cbrt(out.global.block<3, 3>(0, 0).determinant());

  // Per-part refinement.
  const int n_labels = static_cast<int>(garment.label_names.size());
  std::vector<Eigen::Matrix4d> part_transform(n_labels, out.global);
  for (const auto& m : out.matching.matches) {
    PartPlacement p;
    p.garment_part = m.garment_part;
    p.body_part = m.body_part;
    const int gl = label_of(garment, m.garment_part), bl = label_of(body, m.body_part);
    const std::vector<int> grows = rows_with_label(garment, gl), brows = rows_with_label(body, bl);
    p.vertices = static_cast<int>(grows.size());
    p.icp.transform = out.global;
    p.icp.scale = out.global_scale;
    if (p.vertices < options.min_part_vertices ||
        static_cast<int>(brows.size()) < options.min_part_vertices) {
      p.note = "too few vertices for ICP: global transform kept";
    } else {
      IcpOptions o = options.part_icp;
      o.with_scale = options.part_scale;
      PointSet target = gather(body.V, body_normals, brows);
      if (options.keep_ease) {
        // The part's ease under the global placement: the median height of its points over the
        // body part along the nearest body vertex's normal; the part is registered to the body
        // part's surface raised by it, so that ICP does not pull it onto the skin.
        const PointLocator near(target.V);
        std::vector<double> heights;
        for (int v : grows) {
          const Eigen::Vector3d x =
              (out.global * Eigen::Vector4d(garment.V(v, 0), garment.V(v, 1), garment.V(v, 2), 1.0)).head<3>();
          const int b = near.nearest(x);
          heights.push_back((x - target.V.row(b).transpose()).dot(target.N.row(b).transpose()));
        }
        std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
        const double ease = std::max(0.0, heights[heights.size() / 2]);
        target.V += ease * target.N;
      }
      const IcpResult r = icp_align(gather(garment.V, {}, grows), target, o, out.global);
      const Eigen::Matrix4d relative = r.transform * out.global.inverse();
      const double scale_change = r.scale / out.global_scale;
      if (rotation_angle_deg(relative) > options.max_part_rotation_deg) {
        p.note = "ICP turned the part too far from the global placement: global transform kept";
      } else if (scale_change > options.max_part_scale_change ||
                 scale_change < 1.0 / options.max_part_scale_change) {
        p.note = "ICP changed the part's scale too much: global transform kept";
      } else {
        p.used_icp = true;
        part_transform[gl] = r.transform;
      }
      p.icp = r;
    }
    out.parts.push_back(p);
  }

  // Blending: a vertex of part p takes weight ½·f(d/R) of each other part q at distance d < R from
  // it (f falls smoothly from 1 to 0), the rest stays with p; at a boundary both sides get ½.
  std::vector<std::unique_ptr<PointLocator>> part_points(n_labels);
  for (int l = 0; l < n_labels; ++l) {
    const std::vector<int> rows = rows_with_label(garment, l);
    if (!rows.empty())
      part_points[l] = std::make_unique<PointLocator>(gather(garment.V, {}, rows).V);
  }
  const double R = options.blend_radius;
  out.V.resize(garment.num_vertices(), 3);
  for (int v = 0; v < garment.num_vertices(); ++v) {
    const Eigen::Vector4d x(garment.V(v, 0), garment.V(v, 1), garment.V(v, 2), 1.0);
    const int own = garment.labels(v);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double others = 0.0;
    for (int q = 0; q < n_labels; ++q) {
      if (q == own || !part_points[q] || R <= 0) continue;
      double d2 = 0.0;
      part_points[q]->nearest(x.head<3>(), &d2);
      const double t = std::sqrt(d2) / R;
      if (t >= 1.0) continue;
      const double w = 0.5 * (1.0 - t * t * (3.0 - 2.0 * t));
      sum += w * (part_transform[q] * x).head<3>();
      others += w;
    }
    const Eigen::Matrix4d& mine = own >= 0 ? part_transform[own] : out.global;
    const double w_own = std::max(0.0, 1.0 - others);
    sum += w_own * (mine * x).head<3>();
    out.V.row(v) = (sum / (w_own + others)).transpose();
  }

  push_out_of_body(garment, body, body_normals, options, 1.0, out.global_scale, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

/// The garment's edges (smaller index first) and their lengths [m].
void garment_edges(const TriangleMesh& garment, std::vector<std::pair<int, int>>& edges, std::vector<double>& rest) {
  std::set<std::pair<int, int>> edge_set;
  for (int f = 0; f < garment.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = garment.F(f, k), b = garment.F(f, (k + 1) % 3);
      edge_set.insert({std::min(a, b), std::max(a, b)});
    }
  edges.assign(edge_set.begin(), edge_set.end());
  rest.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    rest[e] = (garment.V.row(edges[e].first) - garment.V.row(edges[e].second)).norm();
}

/// Gauss–Seidel sweeps shortening edges longer than (1 + max_edge_stretch) × scale × rest, both
/// ends moved; the edges over the limit in the first sweep.
int limit_edge_stretch(const std::vector<std::pair<int, int>>& edges, const std::vector<double>& rest, double scale,
                       const PlacementOptions& options, Eigen::MatrixX3d& V) {
  int first = 0;
  for (int sweep = 0; sweep < options.stretch_sweeps; ++sweep) {
    int limited = 0;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [a, b] = edges[e];
      const Eigen::RowVector3d d = V.row(b) - V.row(a);
      const double length = d.norm(), limit = (1.0 + options.max_edge_stretch) * scale * rest[e];
      if (length <= limit) continue;
      const Eigen::RowVector3d shift = 0.5 * (length - limit) / length * d;
      V.row(a) += shift;
      V.row(b) -= shift;
      ++limited;
    }
    if (sweep == 0) first = limited;
  }
  return first;
}

}  // namespace

int limit_stretch(const TriangleMesh& garment, double scale, const PlacementOptions& options, Eigen::MatrixX3d& V) {
  std::vector<std::pair<int, int>> edges;
  std::vector<double> rest;
  garment_edges(garment, edges, rest);
  return limit_edge_stretch(edges, rest, scale, options, V);
}

void push_out_of_body(const TriangleMesh& garment, const TriangleMesh& body, const Eigen::MatrixX3d& body_normals,
                      const PlacementOptions& options, double limit_scale, double reach_scale, PlacementResult& out) {
  // Rounds of strain limiting (edges over the limit shortened, both ends moved) and push out of the
  // body (along the normal of the nearest body vertex, to `clearance` outside).
  std::vector<std::pair<int, int>> edges;
  std::vector<double> rest;
  garment_edges(garment, edges, rest);
  const PointLocator body_points(body.V);
  std::vector<bool> moved(garment.num_vertices(), false);
  std::vector<std::vector<int>> neighbours, body_neighbours;
  if (options.push_rings > 0) {
    neighbours = vertex_neighbours(garment.F, garment.num_vertices());
    body_neighbours = vertex_neighbours(body.F, body.num_vertices());
  }
  // Layers: the pieces ordered by the height of their tops, the lowest innermost; per outer vertex
  // the pieces inside it (their vertices' locators) and how far across the body's surface a
  // vertex of one may be from it and still lie under it (two of that piece's mean edges).
  int pieces = 0;
  const std::vector<int> face_piece = face_components(garment.F, garment.num_vertices(), &pieces);
  std::vector<int> piece_of(garment.num_vertices(), -1);
  for (int f = 0; f < garment.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) piece_of[garment.F(f, k)] = face_piece[f];
  std::vector<double> top(pieces, -HUGE_VAL), edge_sum(pieces, 0.0);
  std::vector<int> edge_count(pieces, 0), first_vertex(pieces, -1);
  std::vector<std::vector<int>> piece_rows(pieces);
  std::vector<int> loose;  // vertices of no face: pushed out of the body only
  for (int v = 0; v < garment.num_vertices(); ++v) {
    if (piece_of[v] < 0) {
      loose.push_back(v);
      continue;
    }
    top[piece_of[v]] = std::max(top[piece_of[v]], garment.V(v, 1));
    piece_rows[piece_of[v]].push_back(v);
    if (first_vertex[piece_of[v]] < 0) first_vertex[piece_of[v]] = v;
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const int c = piece_of[edges[e].first];
    edge_sum[c] += rest[e] * reach_scale;
    ++edge_count[c];
  }
  std::vector<double> reach(pieces);  // two mean edges of the piece, as placed
  for (int c = 0; c < pieces; ++c) reach[c] = 2.0 * edge_sum[c] / std::max(1, edge_count[c]);
  std::vector<int> order(pieces);
  std::iota(order.begin(), order.end(), 0);
  const bool given = options.vertex_layers.size() == garment.num_vertices();
  auto layer = [&](int c) { return given ? options.vertex_layers(first_vertex[c]) : 0; };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return layer(a) != layer(b) ? layer(a) < layer(b) : top[a] < top[b];
  });
  for (int c : order) out.layer_pieces.push_back(first_vertex[c]);
  const bool layered = options.layer_gap >= 0.0 && pieces > 1;
  std::vector<bool> layer_moved(garment.num_vertices(), false);
  const auto limit_stretch = [&] {
    out.stretch_limited_edges = limit_edge_stretch(edges, rest, limit_scale, options, out.V);
  };
  for (int it = 0; it < options.push_iterations; ++it) {
    limit_stretch();
    // The inner pieces where they are now (they move in the rounds too).
    std::vector<std::unique_ptr<PointLocator>> piece_points(pieces);
    if (layered)
      for (int c = 0; c < pieces; ++c)
        piece_points[c] = std::make_unique<PointLocator>(gather(out.V, {}, piece_rows[c]).V);
    // With push_rings, every sheet over one place of the body is pushed as far as the one that
    // lies deepest (a button as far as the cloth under it): the pushes needed are gathered per body
    // vertex, spread over push_rings rings of the body, each vertex pushed as far as its nearest
    // body vertex says, and the pushes then smoothed over as many rings of the garment, so that it
    // leaves the body as a bulge rather than a tent of stretched edges.
    Eigen::MatrixX3d push = Eigen::MatrixX3d::Zero(garment.num_vertices(), 3);
    if (options.push_rings > 0) {
      Eigen::VectorXd need = Eigen::VectorXd::Zero(body.num_vertices());
      std::vector<int> nearest(static_cast<std::size_t>(garment.num_vertices()));
      for (int v = 0; v < garment.num_vertices(); ++v) {
        const Eigen::Vector3d x = out.V.row(v).transpose();
        const int b = nearest[v] = body_points.nearest(x);
        const double s = (x - body.V.row(b).transpose()).dot(body_normals.row(b).transpose());
        need(b) = std::max(need(b), options.clearance - s);
      }
      for (int ring = 0; ring < options.push_rings; ++ring) {
        Eigen::VectorXd spread = need;
        for (int b = 0; b < body.num_vertices(); ++b)
          for (int c : body_neighbours[b]) spread(b) = std::max(spread(b), need(c));
        need.swap(spread);
      }
      for (int v = 0; v < garment.num_vertices(); ++v)
        push.row(v) = std::max(0.0, need(nearest[v])) * body_normals.row(nearest[v]);
      for (int ring = 0; ring < options.push_rings; ++ring) {
        Eigen::MatrixX3d smooth = push;
        for (int v = 0; v < garment.num_vertices(); ++v) {
          if (neighbours[v].empty()) continue;
          smooth.row(v) = 0.5 * push.row(v);
          for (int u : neighbours[v]) smooth.row(v) += 0.5 * push.row(u) / static_cast<double>(neighbours[v].size());
        }
        push.swap(smooth);
      }
    }
    for (int rank = 0; rank <= pieces; ++rank)
      for (int v : rank < pieces ? piece_rows[order[rank]] : loose) {
        Eigen::Vector3d x = out.V.row(v).transpose();
        const int b = body_points.nearest(x);
        const Eigen::Vector3d n = body_normals.row(b).transpose();
        const double s = (x - body.V.row(b).transpose()).dot(n);
        if (options.push_rings > 0) {
          x += push.row(v).transpose();
          moved[v] = moved[v] || push.row(v).squaredNorm() > 0.0;
        } else if (s < options.clearance) {
          x += (options.clearance - s) * n;
          moved[v] = true;
        }
        for (int inner = 0; layered && rank < pieces && inner < rank; ++inner) {
          const int c = order[inner];
          if (given && !options.pieces_of_a_layer_apart && layer(c) == layer(order[rank])) continue;
          const int u = piece_rows[c][piece_points[c]->nearest(x)];
          const Eigen::Vector3d d = x - out.V.row(u).transpose();
          const double above = d.dot(n);
          // Under it, not across the body from it: within reach along the normal too.
          if (above < options.layer_gap && above > -reach[c] && (d - above * n).norm() < reach[c]) {
            x += (options.layer_gap - above) * n;
            layer_moved[v] = true;
          }
        }
        out.V.row(v) = x.transpose();
      }
  }
  // With pushes spread, the rounds end by limiting the stretch once more: what that leaves inside
  // the body by a little, the settle pushes out; edges stretched far it could not take.
  if (options.push_rings > 0) limit_stretch();
  out.pushed_out = static_cast<int>(std::count(moved.begin(), moved.end(), true));
  out.layer_pushed = static_cast<int>(std::count(layer_moved.begin(), layer_moved.end(), true));
}

double inside_fraction(const Eigen::MatrixX3d& points, const TriangleMesh& m) {
  if (points.rows() == 0) return 0.0;
  int inside = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    double total = 0.0;  // sum of signed solid angles (Van Oosterom–Strackee)
    for (int f = 0; f < m.num_faces(); ++f) {
      const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose() - p,
                            b = m.V.row(m.F(f, 1)).transpose() - p,
                            c = m.V.row(m.F(f, 2)).transpose() - p;
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      total += 2.0 * std::atan2(a.dot(b.cross(c)),
                                la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
    }
    inside += total / (4.0 * M_PI) > 0.5;
  }
  return static_cast<double>(inside) / static_cast<double>(points.rows());
}

PlacementQuality placement_quality(const Eigen::MatrixX3d& posed, const TriangleMesh& garment_rest,
                                   const Eigen::MatrixX3d& reference, const TriangleMesh& body) {
  PlacementQuality q;
  q.body_height = body.V.col(1).maxCoeff() - body.V.col(1).minCoeff();
  std::vector<double> d(posed.rows());
  for (Eigen::Index i = 0; i < posed.rows(); ++i)
    d[i] = (posed.row(i) - reference.row(i)).norm() / q.body_height;
  q.mean_distance =
      d.empty() ? 0.0 : std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  std::sort(d.begin(), d.end());
  q.p95_distance = d.empty() ? 0.0 : d[static_cast<std::size_t>(0.95 * (d.size() - 1))];
  q.inside_fraction = inside_fraction(posed, body);
  for (int f = 0; f < garment_rest.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = garment_rest.F(f, k), b = garment_rest.F(f, (k + 1) % 3);
      const double rest = (garment_rest.V.row(a) - garment_rest.V.row(b)).norm();
      if (rest <= 0) continue;
      q.max_edge_stretch =
          std::max(q.max_edge_stretch, (posed.row(a) - posed.row(b)).norm() / rest - 1.0);
    }
  }
  return q;
}

}  // namespace dresskit::alignment
