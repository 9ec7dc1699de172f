#pragma once
// A static 3-d k-d tree for the ICP correspondence searches (private to alignment/src).
//
// Why not PCL's KdTreeFLANN: FLANN opens an OpenMP parallel region and allocates result vectors
// for every single-point query, which on the 10k-point benchmark cost about a fifth of the ICP time
// (futex system calls and malloc/free in the profile), and PCL rebuilt the target tree at every
// stage of the schedule. This tree is built once per registration, answers nearest and k-nearest
// queries without allocating, and takes an upper bound on the distance so that a query beyond the
// correspondence distance stops early.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace dresskit::alignment::detail {

class KdTree3 {
 public:
  KdTree3() = default;
  /// Points (single precision: the caller centres them first).
  explicit KdTree3(std::vector<Eigen::Vector3f> points) { build(std::move(points)); }

  void build(std::vector<Eigen::Vector3f> points) {
    const int n = static_cast<int>(points.size());
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    nodes_.clear();
    nodes_.reserve(2 * static_cast<std::size_t>(n / kLeaf + 1));
    source_ = std::move(points);
    if (n) build_node(0, n);
    sorted_.resize(n);
    for (int i = 0; i < n; ++i) sorted_[i] = source_[order_[i]];
  }

  int size() const { return static_cast<int>(sorted_.size()); }
  const Eigen::Vector3f& point(int index) const { return source_[index]; }

  /// Index of the nearest point within sqrt(max_d2) of q, or -1; *d2 gets its squared distance.
  /// hint: a point index believed to be near q (ICP: the previous iteration's match), or -1; its
  /// distance only tightens the search bound, so the result is exact whatever the hint.
  int nearest(const Eigen::Vector3f& q, float max_d2, float* d2, int hint = -1) const {
    if (hint >= 0 && hint < size())
      max_d2 = std::min(max_d2, inflate((source_[hint] - q).squaredNorm()));
    if (nodes_.empty()) return -1;
    Nearest1 visit{max_d2, -1};
    float offsets[3] = {0.0f, 0.0f, 0.0f};
    search(0, q, 0.0f, offsets, visit);
    if (visit.best < 0) return -1;
    if (d2) *d2 = visit.best_d2;
    return order_[visit.best];
  }

  /// The (at most) k nearest points within sqrt(max_d2) of q, nearest first; returns how many.
  /// index and d2 must hold k entries. hints: k point indices believed to be near q (the previous
  /// iteration's neighbours) or nullptr; as for nearest(), they only tighten the bound.
  int nearest_k(const Eigen::Vector3f& q, int k, float max_d2, int* index, float* d2,
                const int* hints = nullptr) const {
    if (hints) {
      float bound = 0.0f;
      for (int m = 0; m < k && bound < max_d2; ++m)
        bound = hints[m] >= 0 && hints[m] < size()
                    ? std::max(bound, (source_[hints[m]] - q).squaredNorm())
                    : max_d2;
      max_d2 = std::min(max_d2, inflate(bound));
    }
    if (nodes_.empty() || k <= 0) return 0;
    NearestK visit{max_d2, k, 0, index, d2};
    float offsets[3] = {0.0f, 0.0f, 0.0f};
    search(0, q, 0.0f, offsets, visit);
    for (int i = 0; i < visit.count; ++i) index[i] = order_[index[i]];
    return visit.count;
  }

 private:
  static constexpr int kLeaf = 8;
  struct Nearest1 {
    float best_d2;
    int best;
    float worst() const { return best_d2; }
    void add(float d, int p) {
      if (d < best_d2) {
        best_d2 = d;
        best = p;
      }
    }
  };
  struct NearestK {
    float max_d2;
    int k, count;
    int* index;
    float* d2;
    float worst() const { return count < k ? max_d2 : d2[count - 1]; }
    void add(float d, int p) {
      if (d >= worst()) return;
      int slot = count < k ? count++ : k - 1;  // insertion sort into the k best
      while (slot > 0 && d2[slot - 1] > d) {
        d2[slot] = d2[slot - 1];
        index[slot] = index[slot - 1];
        --slot;
      }
      d2[slot] = d;
      index[slot] = p;
    }
  };

  // Depth first, near child first. `reach` is the squared distance from q to the node's cell as
  // the sum of the per-axis offsets beyond the splits crossed so far (offsets[dim]); a far child
  // is entered only when its cell can hold a point closer than the current worst.
  template <class Visit>
  void search(int id, const Eigen::Vector3f& q, float reach, float* offsets, Visit& visit) const {
    const Node& node = nodes_[id];
    if (node.dim < 0) {
      for (int p = node.begin; p < node.end; ++p) visit.add((sorted_[p] - q).squaredNorm(), p);
      return;
    }
    const float diff = q[node.dim] - node.split;
    search(diff <= 0 ? node.left : node.right, q, reach, offsets, visit);
    const float saved = offsets[node.dim];
    const float far_reach = reach - saved + diff * diff;
    if (far_reach <= visit.worst()) {
      offsets[node.dim] = diff * diff;
      search(diff <= 0 ? node.right : node.left, q, far_reach, offsets, visit);
      offsets[node.dim] = saved;
    }
  }
  // A hint's squared distance, made a little larger so that rounding never excludes the hint
  // itself or a point at the same distance.
  static float inflate(float d2) { return d2 * (1.0f + 1e-5f) + 1e-30f; }
  struct Node {
    int dim = -1;  // -1: leaf holding sorted_[begin, end)
    float split = 0.0f;
    int left = -1, right = -1, begin = 0, end = 0;
  };

  int build_node(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back(Node{});
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    if (end - begin <= kLeaf) return id;
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
    Eigen::Vector3f hi = -lo;
    for (int i = begin; i < end; ++i) {
      lo = lo.cwiseMin(source_[order_[i]]);
      hi = hi.cwiseMax(source_[order_[i]]);
    }
    int dim = 0;
    (hi - lo).maxCoeff(&dim);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return source_[a][dim] < source_[b][dim]; });
    const float split = source_[order_[mid]][dim];
    // Points equal to the split may lie on both sides: the search treats the split plane as
    // belonging to both halves (diff <= 0 goes left first, and the far side is pruned only by a
    // strictly positive distance), so results stay exact.
    const int left = build_node(begin, mid);
    const int right = build_node(mid, end);
    nodes_[id].dim = dim;
    nodes_[id].split = split;
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
  }

  std::vector<Eigen::Vector3f> source_;  // input order
  std::vector<Eigen::Vector3f> sorted_;  // leaf order
  std::vector<int> order_;               // leaf position -> input index
  std::vector<Node> nodes_;
};

}  // namespace dresskit::alignment::detail
