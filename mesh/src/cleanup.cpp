// Mesh repair with CGAL Polygon Mesh Processing. The only translation unit of the mesh module that
// includes CGAL's PMP headers (they cost ~15 s of compile time each).
#include "dresskit/mesh/cleanup.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "dresskit/mesh/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>
#include <boost/iterator/counting_iterator.hpp>

#include <chrono>
#include <cstring>
#include <map>
#include <sstream>
#include <unordered_map>

#include "dresskit/mesh/topology.h"
#include "internal.h"

namespace dresskit::mesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Exact-position lookup: the input vertex with exactly these coordinates (the first, for duplicates).
// CGAL copies coordinates of the vertices it keeps, so this recovers where every kept vertex came from.
class ExactPositionMap {
 public:
  explicit ExactPositionMap(const Eigen::MatrixX3d& V) {
    map_.reserve(static_cast<size_t>(V.rows()));
    for (int i = 0; i < V.rows(); ++i) map_.emplace(key(V(i, 0), V(i, 1), V(i, 2)), i);
  }
  int find(double x, double y, double z) const {
    auto it = map_.find(key(x, y, z));
    return it == map_.end() ? -1 : it->second;
  }

 private:
  static std::array<std::uint64_t, 3> key(double x, double y, double z) {
    std::array<std::uint64_t, 3> k{};
    std::memcpy(&k[0], &x, 8);
    std::memcpy(&k[1], &y, 8);
    std::memcpy(&k[2], &z, 8);
    return k;
  }
  struct Hash {
    size_t operator()(const std::array<std::uint64_t, 3>& k) const {
      return static_cast<size_t>(k[0] * 0x9E3779B97F4A7C15ull ^ (k[1] + 0x632BE59BD9B4E019ull) * 31 ^
                                 k[2] * 0xC2B2AE3D27D4EB4Full);
    }
  };
  std::unordered_map<std::array<std::uint64_t, 3>, int, Hash> map_;
};

// Nearest input vertex, for attributes of vertices that cleanup created (hole filling, remeshing).
class NearestVertex {
  using Traits_base = CGAL::Search_traits_3<Kernel>;
  using PointMap = CGAL::Pointer_property_map<Point>::type;
  using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, Traits_base>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  using Tree = Search::Tree;
  using Distance = Search::Distance;

 public:
  explicit NearestVertex(const Eigen::MatrixX3d& V) : points_(static_cast<size_t>(V.rows())) {
    for (int i = 0; i < V.rows(); ++i) points_[i] = Point(V(i, 0), V(i, 1), V(i, 2));
    map_ = CGAL::make_property_map(points_);
    tree_ = std::make_unique<Tree>(boost::counting_iterator<std::size_t>(0),
                                   boost::counting_iterator<std::size_t>(points_.size()),
                                   Tree::Splitter(), Traits(map_));
  }
  int find(const Point& p) const {
    Search search(*tree_, p, 1, 0, true, Distance(map_));
    return static_cast<int>(search.begin()->first);
  }

 private:
  std::vector<Point> points_;
  PointMap map_;
  std::unique_ptr<Tree> tree_;
};

// Removes polygons with a repeated vertex index; returns how many.
int remove_repeated_index_polygons(std::vector<Polygon>& polygons) {
  const size_t before = polygons.size();
  polygons.erase(std::remove_if(polygons.begin(), polygons.end(),
                                [](const Polygon& p) {
                                  return p[0] == p[1] || p[1] == p[2] || p[0] == p[2];
                                }),
                 polygons.end());
  return static_cast<int>(before - polygons.size());
}

// Fills the boundary loops of at most max_edges edges, except a loop that is the border of an open
// surface rather than a hole in it: one whose spanned (vector) area is more than half its
// component's area (a panel's or a single triangle's outline). Filled, such a loop closes the
// surface onto itself, two sheets back to back, which remeshing then cannot handle.
void fill_small_holes(SurfaceMesh& sm, int max_edges, CleanupResult& r) {
  std::vector<SurfaceMesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  auto component = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:component", 0).first;
  PMP::connected_components(sm, component);
  std::vector<double> component_area;
  for (auto f : sm.faces()) {
    if (component[f] >= component_area.size()) component_area.resize(component[f] + 1, 0.0);
    component_area[component[f]] += PMP::face_area(f, sm);
  }
  for (auto h : cycles) {
    int edges = 0;
    Kernel::Vector_3 spanned(0, 0, 0);
    for (auto hc : CGAL::halfedges_around_face(h, sm)) {
      const Point& a = sm.point(sm.source(hc));
      const Point& b = sm.point(sm.target(hc));
      spanned = spanned + CGAL::cross_product(a - CGAL::ORIGIN, b - CGAL::ORIGIN);
      ++edges;
    }
    if (edges > max_edges) continue;
    const double area = 0.5 * std::sqrt(spanned.squared_length());
    if (area > 0.5 * component_area[component[sm.face(sm.opposite(h))]]) {
      ++r.borders_left_open;
      continue;
    }
    std::vector<SurfaceMesh::Face_index> faces;
    std::vector<SurfaceMesh::Vertex_index> vertices;
    PMP::triangulate_and_refine_hole(sm, h, std::back_inserter(faces), std::back_inserter(vertices));
    if (!faces.empty()) {
      ++r.holes_filled;
      r.hole_faces_added += static_cast<int>(faces.size());
    }
  }
}

// Copies the halfedge mesh back to arrays (vertex indices compacted in iteration order).
void to_arrays(const SurfaceMesh& sm, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F) {
  std::vector<int> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
  V.resize(sm.number_of_vertices(), 3);
  int n = 0;
  for (auto v : sm.vertices()) {
    const Point& p = sm.point(v);
    V.row(n) << p.x(), p.y(), p.z();
    index[v] = n++;
  }
  F.resize(sm.number_of_faces(), 3);
  int f = 0;
  for (auto face : sm.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(face), sm)) {
      if (k < 3) F(f, k) = index[v];
      ++k;
    }
    ++f;
  }
}

// Attributes of the output: where each vertex came from, labels, UVs, normals, quads, and how many
// faces changed orientation relative to the input.
void carry_attributes(const TriangleMesh& in, TriangleMesh& out, CleanupResult& r) {
  const int nv = out.num_vertices();
  const ExactPositionMap exact(in.V);
  std::vector<int> from(nv);
  std::unique_ptr<NearestVertex> nearest;
  for (int i = 0; i < nv; ++i) from[i] = exact.find(out.V(i, 0), out.V(i, 1), out.V(i, 2));
  std::vector<int> attribute_from(from);
  for (int i = 0; i < nv; ++i) {
    if (attribute_from[i] >= 0) continue;
    if (!nearest) nearest = std::make_unique<NearestVertex>(in.V);
    attribute_from[i] = nearest->find(Point(out.V(i, 0), out.V(i, 1), out.V(i, 2)));
  }
  out.label_names = in.label_names;
  if (in.has_labels()) {
    out.labels.resize(nv);
    for (int i = 0; i < nv; ++i) out.labels(i) = in.labels(attribute_from[i]);
  }
  if (in.UV.rows()) {
    out.UV.resize(nv, 2);
    for (int i = 0; i < nv; ++i) out.UV.row(i) = in.UV.row(attribute_from[i]);
  }
  if (in.N.rows()) out.N = vertex_normals(out.V, out.F);
  out.source_vertex.resize(nv);
  for (int i = 0; i < nv; ++i) {
    out.source_vertex(i) =
        from[i] < 0 ? -1 : (in.source_vertex.size() ? in.source_vertex(from[i]) : from[i]);
  }

  // Output faces by their corners' input indices, rotation-invariant and directed.
  std::map<std::array<int, 3>, int> out_face;
  for (int f = 0; f < out.num_faces(); ++f) {
    const int a = from[out.F(f, 0)], b = from[out.F(f, 1)], c = from[out.F(f, 2)];
    if (a >= 0 && b >= 0 && c >= 0) out_face.emplace(detail::directed_triangle_key(a, b, c), f);
  }
  for (int f = 0; f < in.num_faces(); ++f) {
    const int a = in.F(f, 0), b = in.F(f, 1), c = in.F(f, 2);
    if (!out_face.count(detail::directed_triangle_key(a, b, c)) &&
        out_face.count(detail::directed_triangle_key(a, c, b))) {
      ++r.faces_reoriented;
    }
  }
  // A quad survives when both of its triangles do, in either orientation.
  auto corner = [&](int f, int input_vertex) {
    for (int k = 0; k < 3; ++k)
      if (from[out.F(f, k)] == input_vertex) return out.F(f, k);
    return -1;
  };
  std::vector<Eigen::Vector4i> quads;
  for (int q = 0; q < in.quads.rows(); ++q) {
    const int a = in.quads(q, 0), b = in.quads(q, 1), c = in.quads(q, 2), d = in.quads(q, 3);
    auto t1 = out_face.find(detail::directed_triangle_key(a, b, c));
    auto t2 = out_face.find(detail::directed_triangle_key(a, c, d));
    if (t1 != out_face.end() && t2 != out_face.end()) {
      quads.emplace_back(corner(t1->second, a), corner(t1->second, b), corner(t1->second, c),
                         corner(t2->second, d));
      continue;
    }
    t1 = out_face.find(detail::directed_triangle_key(a, c, b));
    t2 = out_face.find(detail::directed_triangle_key(a, d, c));
    if (t1 != out_face.end() && t2 != out_face.end()) {
      quads.emplace_back(corner(t1->second, a), corner(t2->second, d), corner(t1->second, c),
                         corner(t1->second, b));
    }
  }
  out.quads.resize(static_cast<Eigen::Index>(quads.size()), 4);
  for (size_t q = 0; q < quads.size(); ++q) out.quads.row(static_cast<Eigen::Index>(q)) = quads[q].transpose();

  // Per face corner: texture coordinates and face groups of an output face whose corners are an
  // input face's (either orientation) come from that face; a face the repair made takes, at each
  // corner, a coordinate its vertex had in some input face, and no group.
  const bool corners = in.FTC.rows() == in.num_faces() && in.num_faces() > 0 && in.TC.rows() > 0;
  const bool groups = in.face_groups.size() == in.num_faces() && in.num_faces() > 0;
  if (!corners && !groups) return;
  std::map<std::array<int, 3>, int> in_face;
  for (int f = 0; f < in.num_faces(); ++f) {
    std::array<int, 3> key{in.F(f, 0), in.F(f, 1), in.F(f, 2)};
    std::sort(key.begin(), key.end());
    in_face.emplace(key, f);
  }
  std::vector<int> vertex_tc(static_cast<std::size_t>(in.num_vertices()), 0);
  if (corners)
    for (int f = in.num_faces() - 1; f >= 0; --f)
      for (int k = 0; k < 3; ++k) vertex_tc[static_cast<std::size_t>(in.F(f, k))] = in.FTC(f, k);
  if (corners) out.TC = in.TC, out.FTC.resize(out.num_faces(), 3);
  if (groups) out.group_names = in.group_names, out.face_groups = Eigen::VectorXi::Constant(out.num_faces(), -1);
  for (int f = 0; f < out.num_faces(); ++f) {
    std::array<int, 3> key{from[out.F(f, 0)], from[out.F(f, 1)], from[out.F(f, 2)]};
    std::sort(key.begin(), key.end());
    const auto match = key[0] >= 0 ? in_face.find(key) : in_face.end();
    if (groups && match != in_face.end()) out.face_groups(f) = in.face_groups(match->second);
    if (!corners) continue;
    for (int k = 0; k < 3; ++k) {
      const int v = out.F(f, k);
      int t = vertex_tc[static_cast<std::size_t>(attribute_from[v])];
      if (match != in_face.end())
        for (int m = 0; m < 3; ++m)
          if (in.F(match->second, m) == from[v]) t = in.FTC(match->second, m);
      out.FTC(f, k) = t;
    }
  }
}

}  // namespace

std::vector<std::string> CleanupResult::changes() const {
  std::vector<std::string> lines;
  auto add = [&](int n, const char* what) {
    if (n > 0) lines.push_back(std::to_string(n) + " " + what);
  };
  add(duplicate_vertices_merged, "duplicate vertices merged");
  add(degenerate_faces_removed, "degenerate faces removed");
  add(duplicate_faces_removed, "duplicate faces removed");
  add(isolated_vertices_removed, "isolated vertices removed");
  add(non_manifold_vertices_split, "vertices added to split non-manifold vertices");
  add(border_edges_stitched, "border edge pairs stitched");
  add(faces_reoriented, "faces reoriented");
  add(holes_filled, "holes filled");
  add(hole_faces_added, "faces added in holes");
  add(borders_left_open, "borders of open surfaces left open (not holes)");
  add(components_removed, "connected components removed");
  if (remeshed) lines.push_back("remeshed isotropically");
  return lines;
}

CleanupResult cleanup_mesh(const TriangleMesh& input, const CleanupOptions& options) {
  if (!(options.remesh_edge_length >= 0.0 && std::isfinite(options.remesh_edge_length)))
    throw InputError("remesh edge length: " + std::to_string(options.remesh_edge_length) + " m (must be 0 or more)");
  if (options.remesh_iterations < 1 || options.max_hole_edges < 1)
    throw InputError("remesh iterations and largest hole: must be at least 1");
  if (options.remesh_edge_length > 0.0) {
    // Equilateral triangles of edge L cover √3/4 L² each: too short an edge would fill the memory
    // (a body remeshed at 0.1 mm: 6.5 GB before running out).
    double area = 0.0;
    for (int f = 0; f < input.num_faces(); ++f)
      area += 0.5 * (input.V.row(input.F(f, 1)) - input.V.row(input.F(f, 0)))
                        .cross(input.V.row(input.F(f, 2)) - input.V.row(input.F(f, 0)))
                        .norm();
    const double L = options.remesh_edge_length, triangles = area / (std::sqrt(3.0) / 4.0 * L * L);
    if (triangles > kMaxRemeshTriangles) {
      const double shortest = std::sqrt(area / (std::sqrt(3.0) / 4.0 * kMaxRemeshTriangles));
      std::ostringstream why;
      why << "remesh edge length " << L << " m would make about " << std::llround(triangles)
          << " triangles of this mesh's " << area << " m² (at most " << std::llround(kMaxRemeshTriangles)
          << "): use at least " << shortest << " m";
      throw InputError(why.str());
    }
  }
  CleanupResult r;
  auto t0 = Clock::now();

  // Polygon soup phase: everything that does not need a valid halfedge structure.
  std::vector<Point> points(static_cast<size_t>(input.num_vertices()));
  for (int i = 0; i < input.num_vertices(); ++i) points[i] = Point(input.V(i, 0), input.V(i, 1), input.V(i, 2));
  std::vector<Polygon> polygons(static_cast<size_t>(input.num_faces()));
  for (int f = 0; f < input.num_faces(); ++f) {
    polygons[f] = {std::size_t(input.F(f, 0)), std::size_t(input.F(f, 1)), std::size_t(input.F(f, 2))};
  }
  r.degenerate_faces_removed += remove_repeated_index_polygons(polygons);
  r.duplicate_vertices_merged =
      static_cast<int>(PMP::merge_duplicate_points_in_polygon_soup(points, polygons));
  r.degenerate_faces_removed += remove_repeated_index_polygons(polygons);
  r.duplicate_faces_removed =
      static_cast<int>(PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons));
  r.isolated_vertices_removed =
      static_cast<int>(PMP::remove_isolated_points_in_polygon_soup(points, polygons));
  if (options.orient || options.repair_non_manifold) {
    // Orienting the soup also splits non-manifold vertices (a halfedge mesh cannot hold them).
    const size_t before = points.size();
    PMP::orient_polygon_soup(points, polygons);
    r.non_manifold_vertices_split = static_cast<int>(points.size() - before);
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  r.seconds_soup = seconds_since(t0);

  // Halfedge phase.
  t0 = Clock::now();
  if (options.stitch_borders) r.border_edges_stitched = static_cast<int>(PMP::stitch_borders(sm));
  {
    const auto before = sm.number_of_faces();
    PMP::remove_degenerate_faces(sm);
    sm.collect_garbage();
    r.degenerate_faces_removed += static_cast<int>(before - std::min(before, sm.number_of_faces()));
  }
  if (options.repair_non_manifold) {
    r.non_manifold_vertices_split += static_cast<int>(PMP::duplicate_non_manifold_vertices(sm));
  }
  if (options.fill_holes) fill_small_holes(sm, options.max_hole_edges, r);
  if (options.keep_largest_component) {
    r.components_removed = static_cast<int>(PMP::keep_largest_connected_components(sm, 1));
  }
  sm.collect_garbage();
  r.seconds_mesh = seconds_since(t0);

  t0 = Clock::now();
  if (options.remesh_edge_length > 0.0) {
    PMP::isotropic_remeshing(faces(sm), options.remesh_edge_length, sm,
                             PMP::parameters::number_of_iterations(options.remesh_iterations));
    sm.collect_garbage();
    r.remeshed = true;
  }
  r.seconds_remesh = seconds_since(t0);

  t0 = Clock::now();
  to_arrays(sm, r.mesh.V, r.mesh.F);
  if (options.orient) orient_closed_components_outward(r.mesh);
  carry_attributes(input, r.mesh, r);
  r.seconds_attributes = seconds_since(t0);
  return r;
}

}  // namespace dresskit::mesh
