// The one translation unit with CGAL: each panel's resampled outline as the constraints of a 2D
// constrained Delaunay triangulation, refined inside without splitting the outline (so stitched
// edges keep their matching points).
#include "dresskit/pattern/cut.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/curves.h"

using namespace dresskit::mesh;

namespace dresskit::pattern {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb =
    CGAL::Triangulation_vertex_base_with_info_2<int, K, CGAL::Delaunay_mesh_vertex_base_2<K>>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Mesher = CGAL::Delaunay_mesher_no_edge_refinement_2<CDT, Criteria>;

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// One panel meshed: its outline polygon (given) and the interior points CGAL added, with triangles
/// over both (indices: outline points first, then the added ones).
struct PanelTriangles {
  std::vector<Eigen::Vector2d> added;
  std::vector<std::array<int, 3>> triangles;
};

PanelTriangles mesh_panel(const std::vector<Eigen::Vector2d>& outline, const CutOptions& options,
                          const std::string& where) {
  CDT cdt;
  std::vector<CDT::Vertex_handle> handles;
  handles.reserve(outline.size());
  for (std::size_t i = 0; i < outline.size(); ++i) {
    handles.push_back(cdt.insert(K::Point_2(outline[i].x(), outline[i].y())));
    handles.back()->info() = int(i);
  }
  for (std::size_t i = 0; i < outline.size(); ++i)
    cdt.insert_constraint(handles[i], handles[(i + 1) % outline.size()]);
  if (cdt.number_of_vertices() != outline.size())
    throw InputError(where +
                     ": two points of the resampled outline coincide; try a smaller edge length");
  // Faces not reachable from outside without crossing the outline are the panel (CGAL marks the
  // infinite face's component as outside when no seeds are given).
  Mesher mesher(cdt, Criteria(options.shape_bound, options.edge_length));
  // This mesher leaves its seed mark uninitialised (the sanitizer build reports reading it);
  // clear_seeds() sets it to false, Delaunay_mesher_2's default: no seeds, mesh the bounded domain.
  mesher.clear_seeds();
  mesher.refine_mesh();
  PanelTriangles out;
  int next = int(outline.size());
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info() >= 0 && v->info() < int(outline.size()) &&
        handles[v->info()] == CDT::Vertex_handle(v))
      continue;
    v->info() = next++;
    out.added.emplace_back(v->point().x(), v->point().y());
  }
  for (std::size_t i = 0; i < outline.size(); ++i)
    if (!cdt.is_edge(handles[i], handles[(i + 1) % outline.size()]))
      throw InputError(
          where + ": the outline was split while meshing (it crosses itself at this edge length)");
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    out.triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  if (out.triangles.empty()) throw InputError(where + ": no triangles inside the outline");
  return out;
}

}  // namespace

std::vector<std::vector<int>> edge_piece_counts(const Pattern& pattern, double step) {
  std::vector<int> first(pattern.panels.size() + 1, 0);
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    first[p + 1] = first[p] + int(pattern.panels[p].edges.size());
  std::vector<int> parent(first.back());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Stitch& s : pattern.stitches) {
    const int a = find(parent, first[s.a.panel] + s.a.edge),
              b = find(parent, first[s.b.panel] + s.b.edge);
    parent[a] = b;
  }
  std::vector<int> count(first.back(), 1);
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    for (std::size_t e = 0; e < pattern.panels[p].edges.size(); ++e)
      count[first[p] + e] =
          std::max(1, int(std::ceil(edge_length(pattern.panels[p], int(e)) / step - 1e-9)));
  std::vector<int> group(first.back(), 1);
  for (int i = 0; i < first.back(); ++i)
    group[find(parent, i)] = std::max(group[find(parent, i)], count[i]);
  std::vector<std::vector<int>> out(pattern.panels.size());
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    for (std::size_t e = 0; e < pattern.panels[p].edges.size(); ++e)
      out[p].push_back(group[find(parent, first[p] + e)]);
  return out;
}

CutPattern cut_pattern(const Pattern& pattern, const CutOptions& options) {
  if (!(options.edge_length > 0.0)) throw InputError("cut: edge length must be positive");
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<std::vector<int>> pieces = edge_piece_counts(pattern, options.edge_length);
  std::vector<Eigen::Vector2d> flat;
  std::vector<int> vertex_panel, face_panel;
  std::vector<std::array<int, 3>> faces;
  CutPattern cut;
  const int np = int(pattern.panels.size());
  cut.edge_vertices.resize(np);
  cut.outline_area.resize(np);
  cut.triangle_area.resize(np);
  for (int p = 0; p < np; ++p) {
    const Panel& panel = pattern.panels[p];
    const int base = int(flat.size());
    // The outline: each edge's points but its last (the next edge's first).
    std::vector<Eigen::Vector2d> outline;
    std::vector<int> edge_start;
    for (std::size_t e = 0; e < panel.edges.size(); ++e) {
      edge_start.push_back(int(outline.size()));
      const Eigen::MatrixX2d s = sample_edge(panel, int(e), pieces[p][e]);
      for (Eigen::Index i = 0; i + 1 < s.rows(); ++i) outline.push_back(s.row(i).transpose());
    }
    const int m = int(outline.size());
    cut.edge_vertices[p].resize(panel.edges.size());
    for (std::size_t e = 0; e < panel.edges.size(); ++e)
      for (int i = 0; i <= pieces[p][e]; ++i)
        cut.edge_vertices[p][e].push_back(base + (edge_start[e] + i) % m);
    Eigen::MatrixX2d polygon(m, 2);
    for (int i = 0; i < m; ++i) polygon.row(i) = outline[i].transpose();
    const double turning = polygon_area(polygon);
    const PanelTriangles t =
        mesh_panel(outline, options, pattern.file + ": panel '" + panel.name + "'");
    flat.insert(flat.end(), outline.begin(), outline.end());
    flat.insert(flat.end(), t.added.begin(), t.added.end());
    vertex_panel.insert(vertex_panel.end(), outline.size() + t.added.size(), p);
    double area = 0.0;
    for (const auto& tri : t.triangles) {
      // CGAL's faces turn counter-clockwise; a panel whose outline turns clockwise gets them
      // reversed.
      std::array<int, 3> f{base + tri[0], base + tri[1], base + tri[2]};
      if (turning < 0) std::swap(f[1], f[2]);
      const Eigen::Vector2d a = flat[f[0]], b = flat[f[1]], c = flat[f[2]];
      area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      faces.push_back(f);
      face_panel.push_back(p);
    }
    cut.triangle_area[p] = area;
    cut.outline_area[p] = std::abs(polygon_area(sample_outline(panel, 1e-4)));
  }
  const int nv = int(flat.size());
  cut.flat.resize(nv, 2);
  cut.placed.resize(nv, 3);
  cut.panel_of_vertex = Eigen::Map<Eigen::VectorXi>(vertex_panel.data(), nv);
  for (int v = 0; v < nv; ++v) {
    cut.flat.row(v) = flat[v].transpose();
    cut.placed.row(v) = pattern.panels[vertex_panel[v]].place(flat[v]).transpose();
  }
  cut.faces.resize(faces.size(), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    cut.faces.row(f) << faces[f][0], faces[f][1], faces[f][2];
  cut.panel_of_face = Eigen::Map<Eigen::VectorXi>(face_panel.data(), face_panel.size());
  // Stitch pairs: the start of one edge meets the end of the other (or starts meet,
  // same_direction).
  for (std::size_t s = 0; s < pattern.stitches.size(); ++s) {
    const Stitch& st = pattern.stitches[s];
    const std::vector<int>& a = cut.edge_vertices[st.a.panel][st.a.edge];
    const std::vector<int>& b = cut.edge_vertices[st.b.panel][st.b.edge];
    if (a.size() != b.size())
      throw std::logic_error("cut: stitched edges with different point counts");
    const int n = int(a.size());
    for (int i = 0; i < n; ++i) {
      const int j = st.same_direction ? i : n - 1 - i;
      if (a[i] == b[j]) continue;  // a dart's tip
      cut.stitch_pairs.push_back({a[i], b[j]});
      cut.stitch_of_pair.push_back(int(s));
    }
  }
  cut.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return cut;
}

TriangleMesh placed_mesh(const Pattern& pattern, const CutPattern& cut) {
  TriangleMesh m;
  m.V = cut.placed;
  m.F = cut.faces;
  m.labels = cut.panel_of_vertex;
  for (const Panel& p : pattern.panels) m.label_names.push_back(p.name);
  m.face_groups = cut.panel_of_face;
  m.group_names = m.label_names;
  return m;
}

Eigen::MatrixX2d texture_coordinates(const Pattern& pattern, const CutPattern& cut, double gap) {
  const int panels = int(pattern.panels.size());
  Eigen::VectorXd turn = Eigen::VectorXd::Zero(panels);  // twice each panel's signed area
  for (Eigen::Index f = 0; f < cut.faces.rows(); ++f) {
    const Eigen::RowVector2d a = cut.flat.row(cut.faces(f, 0));
    const Eigen::RowVector2d ab = cut.flat.row(cut.faces(f, 1)) - a, ac = cut.flat.row(cut.faces(f, 2)) - a;
    turn[cut.panel_of_face[f]] += ab.x() * ac.y() - ab.y() * ac.x();
  }
  Eigen::MatrixX2d uv(cut.flat.rows(), 2);
  double u = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double sign = turn[p] < 0.0 ? -1.0 : 1.0;
    double lo = 1e30, hi = -1e30;
    for (Eigen::Index v = 0; v < cut.flat.rows(); ++v)
      if (cut.panel_of_vertex[v] == p) lo = std::min(lo, sign * cut.flat(v, 0)), hi = std::max(hi, sign * cut.flat(v, 0));
    for (Eigen::Index v = 0; v < cut.flat.rows(); ++v)
      if (cut.panel_of_vertex[v] == p) uv.row(v) << sign * cut.flat(v, 0) - lo + u, cut.flat(v, 1);
    if (hi >= lo) u += hi - lo + gap;
  }
  return uv;
}

TriangleMesh flat_mesh(const Pattern& pattern, const CutPattern& cut, double gap) {
  TriangleMesh m = placed_mesh(pattern, cut);
  m.V.leftCols<2>() = texture_coordinates(pattern, cut, gap);
  m.V.col(2).setZero();
  return m;
}

}  // namespace dresskit::pattern
