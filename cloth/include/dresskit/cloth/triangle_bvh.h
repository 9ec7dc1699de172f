#pragma once
// A bounding volume hierarchy (axis-aligned boxes, median split on the longest axis, up to 4
// triangles a leaf) over the triangles of a mesh: built once, refitted bottom-up when the vertices
// move (the cloth every step), queried for boxes that overlap a box, for overlapping pairs within one
// tree, and for the exact closest point.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <vector>

namespace dresskit::cloth {

class TriangleBvh {
 public:
  TriangleBvh() = default;
  /// Builds the tree over the triangles F of V; every box is inflated by pad [m].
  TriangleBvh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, double pad = 0.0);

  /// New boxes for new positions, the tree's shape kept. With start, each triangle's box also holds
  /// its corners at start (a swept box: what moved through space during a step). Inflated by pad.
  void refit(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d* start = nullptr, double pad = 0.0);

  /// Calls visit(triangle) for every triangle whose box overlaps box.
  template <typename Visit>
  void query(const Eigen::AlignedBox3d& box, Visit&& visit) const;
  /// Calls visit(t1, t2) once for every pair of distinct triangles whose boxes overlap.
  template <typename Visit>
  void self_pairs(Visit&& visit) const;

  /// The closest point q of the mesh to p, its triangle (returned) and squared distance d2; -1 when
  /// nothing lies closer than sqrt(max_d2).
  int closest(const Eigen::Vector3d& p, Eigen::Vector3d* q, double* d2,
              double max_d2 = std::numeric_limits<double>::infinity()) const;

  int num_triangles() const { return static_cast<int>(order_.size()); }
  const Eigen::AlignedBox3d& box(int triangle) const { return tri_box_[triangle]; }
  bool empty() const { return nodes_.empty(); }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  ///< children; -1 for a leaf
    int first = 0, count = 0;   ///< leaf: its triangles are order_[first .. first + count)
  };
  int build_node(int first, int count, std::vector<Eigen::Vector3d>& centre);
  template <typename Visit>
  void pairs(int a, int b, Visit& visit) const;

  Eigen::MatrixX3d V_;  ///< positions at the last build or refit (closest-point queries)
  Eigen::MatrixX3i F_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<Eigen::AlignedBox3d> tri_box_;
};

template <typename Visit>
void TriangleBvh::query(const Eigen::AlignedBox3d& box, Visit&& visit) const {
  if (nodes_.empty()) return;
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!n.box.intersects(box)) continue;
    if (n.left < 0) {
      for (int k = n.first; k < n.first + n.count; ++k)
        if (tri_box_[order_[k]].intersects(box)) visit(order_[k]);
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
}

template <typename Visit>
void TriangleBvh::pairs(int a, int b, Visit& visit) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (a != b && !na.box.intersects(nb.box)) return;
  if (na.left < 0 && nb.left < 0) {
    for (int i = na.first; i < na.first + na.count; ++i) {
      const int ti = order_[i];
      for (int j = (a == b ? i + 1 : nb.first); j < nb.first + nb.count; ++j) {
        const int tj = order_[j];
        if (tri_box_[ti].intersects(tri_box_[tj])) visit(ti, tj);
      }
    }
    return;
  }
  if (a == b) {
    pairs(na.left, na.left, visit);
    pairs(na.right, na.right, visit);
    pairs(na.left, na.right, visit);
  } else if (nb.left < 0 || (na.left >= 0 && na.box.volume() > nb.box.volume())) {
    pairs(na.left, b, visit);
    pairs(na.right, b, visit);
  } else {
    pairs(a, nb.left, visit);
    pairs(a, nb.right, visit);
  }
}

template <typename Visit>
void TriangleBvh::self_pairs(Visit&& visit) const {
  if (!nodes_.empty()) pairs(0, 0, visit);
}

}  // namespace dresskit::cloth
