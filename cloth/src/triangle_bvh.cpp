#include "dresskit/cloth/triangle_bvh.h"

#include <algorithm>
#include <numeric>

#include "dresskit/cloth/geometry.h"

namespace dresskit::cloth {

namespace {
Eigen::AlignedBox3d triangle_box(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, int t) {
  Eigen::AlignedBox3d b;
  for (int c = 0; c < 3; ++c) b.extend(V.row(F(t, c)).transpose());
  return b;
}
}  // namespace

TriangleBvh::TriangleBvh(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, double pad) : V_(V), F_(F) {
  const int n = static_cast<int>(F.rows());
  if (n == 0) return;
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  tri_box_.resize(n);
  std::vector<Eigen::Vector3d> centre(n);
  for (int t = 0; t < n; ++t) {
    tri_box_[t] = triangle_box(V, F, t);
    centre[t] = tri_box_[t].center();
  }
  nodes_.reserve(2 * static_cast<std::size_t>(n) / 2 + 1);
  build_node(0, n, centre);
  refit(V, nullptr, pad);
}

int TriangleBvh::build_node(int first, int count, std::vector<Eigen::Vector3d>& centre) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  Eigen::AlignedBox3d bounds;
  for (int k = first; k < first + count; ++k) bounds.extend(centre[order_[k]]);
  int axis = 0;
  bounds.sizes().maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
                   [&](int a, int b) { return centre[a](axis) < centre[b](axis); });
  const int left = build_node(first, mid - first, centre);
  const int right = build_node(mid, first + count - mid, centre);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void TriangleBvh::refit(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d* start, double pad) {
  if (nodes_.empty()) return;
  V_ = V;
  for (int t = 0; t < static_cast<int>(tri_box_.size()); ++t) {
    tri_box_[t] = triangle_box(V, F_, t);
    if (start) tri_box_[t].extend(triangle_box(*start, F_, t));
    tri_box_[t].min().array() -= pad;
    tri_box_[t].max().array() += pad;
  }
  // Children always come after their parent: one backward pass fits every box.
  for (int k = static_cast<int>(nodes_.size()) - 1; k >= 0; --k) {
    Node& n = nodes_[k];
    n.box.setEmpty();
    if (n.left < 0) {
      for (int m = n.first; m < n.first + n.count; ++m) n.box.extend(tri_box_[order_[m]]);
    } else {
      n.box = nodes_[n.left].box.merged(nodes_[n.right].box);
    }
  }
}

int TriangleBvh::closest(const Eigen::Vector3d& p, Eigen::Vector3d* q, double* d2, double max_d2) const {
  int best = -1;
  double best_d2 = max_d2;
  if (nodes_.empty()) return -1;
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.box.squaredExteriorDistance(p) >= best_d2) continue;
    if (n.left < 0) {
      for (int m = n.first; m < n.first + n.count; ++m) {
        const int t = order_[m];
        const Eigen::Vector3d c = closest_point_on_triangle(p, V_.row(F_(t, 0)).transpose(),
                                                            V_.row(F_(t, 1)).transpose(), V_.row(F_(t, 2)).transpose());
        const double d = (c - p).squaredNorm();
        if (d < best_d2) {
          best_d2 = d;
          best = t;
          *q = c;
        }
      }
      continue;
    }
    // Nearer child last, so that it is popped first.
    const double dl = nodes_[n.left].box.squaredExteriorDistance(p);
    const double dr = nodes_[n.right].box.squaredExteriorDistance(p);
    if (dl < dr) {
      stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  if (best >= 0) *d2 = best_d2;
  return best;
}

}  // namespace dresskit::cloth
