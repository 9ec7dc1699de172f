// Edge–triangle crossings of a cloth: counts for reports and tests, the crossing vertices, and the
// tangled particles the cloth–cloth pass leaves to separate on their own.
#include <vector>

#include "dresskit/cloth/self_collision.h"
#include "dresskit/cloth/geometry.h"
#include "dresskit/cloth/triangle_bvh.h"
#include "self_collision_internal.h"

namespace dresskit::cloth {

namespace {

Eigen::Vector3d row(const Eigen::MatrixX3d& m, int i) { return m.row(i).transpose(); }
/// Calls crossing(e, f) for every edge e (triangle_edges(F) numbering) that crosses a face f it
/// does not share a particle with (after joined).
template <typename Crossing>
void for_each_crossing(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F,
                       const std::vector<int>& rep, const EdgeList& edges, Crossing crossing) {
  const TriangleBvh bvh(x, F);
  auto owned_edges_against = [&](int ta, int tb) {
    for (int k = 0; k < 3; ++k) {
      const int e = edges.face_edges(ta, k);
      if (edges.owner[e] != ta) continue;
      const int a = rep[edges.i[e]], b = rep[edges.j[e]];
      bool shared = false;
      for (int m = 0; m < 3; ++m) shared = shared || rep[F(tb, m)] == a || rep[F(tb, m)] == b;
      if (!shared && segment_crosses_triangle(row(x, edges.i[e]), row(x, edges.j[e]), row(x, F(tb, 0)),
                                   row(x, F(tb, 1)), row(x, F(tb, 2))))
        crossing(e, tb);
    }
  };
  bvh.self_pairs([&](int ta, int tb) {
    owned_edges_against(ta, tb);
    owned_edges_against(tb, ta);
  });
}
}  // namespace

int count_intersections(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F,
                        const std::vector<int>& joined) {
  if (F.rows() == 0) return 0;
  int crossings = 0;
  for_each_crossing(x, F, detail::representatives(joined, static_cast<int>(x.rows())), triangle_edges(F),
                    [&](int, int) { ++crossings; });
  return crossings;
}

std::vector<int> crossing_vertices(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& F, const std::vector<int>& group) {
  std::vector<char> in(static_cast<std::size_t>(x.rows()), 0);
  if (F.rows() > 0) {
    const EdgeList edges = triangle_edges(F);
    for_each_crossing(x, F, detail::representatives({}, static_cast<int>(x.rows())), edges, [&](int e, int f) {
      if (!group.empty() && group[static_cast<std::size_t>(edges.i[e])] == group[static_cast<std::size_t>(F(f, 0))]) return;
      for (int p : {edges.i[e], edges.j[e], F(f, 0), F(f, 1), F(f, 2)}) in[static_cast<std::size_t>(p)] = 1;
    });
  }
  std::vector<int> out;
  for (std::size_t p = 0; p < in.size(); ++p)
    if (in[p]) out.push_back(static_cast<int>(p));
  return out;
}

void SelfCollision::find_tangles(const Eigen::MatrixX3d& x0) {
  tangled_.assign(static_cast<std::size_t>(x0.rows()), 0);
  tangled_count_ = 0;
  for_each_crossing(x0, faces_, rep_, edges_, [&](int e, int f) {
    for (int p : {edges_.i[e], edges_.j[e], faces_(f, 0), faces_(f, 1), faces_(f, 2)}) {
      tangled_count_ += !tangled_[p];
      tangled_[p] = 1;
    }
  });
}

}  // namespace dresskit::cloth
