#include "dresskit/alignment/part_matching.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <cmath>
#include <limits>
#include <set>

#include "dresskit/segmentation/metrics.h"

using namespace dresskit::mesh;
using namespace dresskit::segmentation;

namespace dresskit::alignment {

std::vector<PartDescriptor> describe_parts(const TriangleMesh& mesh) {
  std::vector<PartDescriptor> parts;
  if (!mesh.has_labels() || mesh.num_vertices() == 0) return parts;
  const Eigen::Vector3d whole = mesh.V.colwise().mean().transpose();
  const double diag =
      std::max(1e-12, (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm());
  const int n_labels = static_cast<int>(mesh.label_names.size());
  std::vector<std::set<int>> touching(n_labels);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.labels(mesh.F(f, k)), b = mesh.labels(mesh.F(f, (k + 1) % 3));
      if (a >= 0 && b >= 0 && a != b) {
        touching[a].insert(b);
        touching[b].insert(a);
      }
    }
  }
  for (int label = 0; label < n_labels; ++label) {
    std::vector<int> rows;
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.labels(v) == label) rows.push_back(v);
    if (rows.empty()) continue;
    PartDescriptor d;
    d.name = mesh.label_names[label];
    d.label = label;
    d.vertices = static_cast<int>(rows.size());
    Eigen::MatrixX3d X(rows.size(), 3);
    for (std::size_t k = 0; k < rows.size(); ++k) X.row(k) = mesh.V.row(rows[k]);
    d.centroid = X.colwise().mean().transpose();
    d.relative_position = (d.centroid - whole) / diag;
    const Eigen::MatrixX3d C = X.rowwise() - d.centroid.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C.transpose() * C /
                                                             static_cast<double>(rows.size()));
    for (int k = 0; k < 3; ++k)
      d.extents(k) = std::sqrt(std::max(0.0, eig.eigenvalues()(2 - k))) / diag;
    d.main_axis = eig.eigenvectors().col(2);
    if (d.main_axis.y() < 0) d.main_axis = -d.main_axis;
    for (int other : touching[label]) d.neighbours.push_back(mesh.label_names[other]);
    parts.push_back(d);
  }
  return parts;
}

namespace {
// The body part a garment part of another name follows: segmentation's garment parts (a garment's
// body, sleeves, a skirt and its halves, and further pieces of them named with a suffix, "body_2")
// follow the torso, the arms and the legs.
std::string body_name_for(std::string garment_part) {
  const std::size_t cut = garment_part.find_last_not_of("0123456789");
  if (cut != std::string::npos && cut + 1 < garment_part.size() && garment_part[cut] == '_')
    garment_part.resize(cut);
  static const std::map<std::string, std::string> follows = {
      {"body", "torso"},          {"sleeve_left", "arm_left"}, {"sleeve_right", "arm_right"},
      {"skirt", "torso"},         {"skirt_waist", "torso"},    {"skirt_left", "leg_left"},
      {"skirt_right", "leg_right"}};
  const auto it = follows.find(garment_part);
  return it == follows.end() ? garment_part : it->second;
}

double descriptor_cost(const PartDescriptor& g, const PartDescriptor& b) {
  return (g.relative_position - b.relative_position).norm() + (g.extents - b.extents).norm() +
         (1.0 - std::abs(g.main_axis.dot(b.main_axis)));
}
}  // namespace

std::vector<int> optimal_assignment(const Eigen::MatrixXd& cost) {
  return max_weight_matching(-cost);  // segmentation's Hungarian method (metrics.h)
}

MatchingResult match_parts(const std::vector<PartDescriptor>& garment,
                           const std::vector<PartDescriptor>& body,
                           const MatchingOptions& options) {
  MatchingResult out;
  std::vector<bool> body_used(body.size(), false);
  std::vector<int> left;  // garment parts without a namesake on the body
  for (std::size_t g = 0; g < garment.size(); ++g) {
    auto named = [&](const std::string& name) {
      return std::find_if(body.begin(), body.end(), [&](const PartDescriptor& b) { return b.name == name; });
    };
    // The same name first, then the part it follows (several garment parts may follow one).
    auto it = named(garment[g].name);
    if (it == body.end()) it = named(body_name_for(garment[g].name));
    if (it == body.end()) {
      left.push_back(static_cast<int>(g));
      continue;
    }
    body_used[it - body.begin()] = true;
    out.matches.push_back({garment[g].name, it->name, 1.0, "name"});
  }
  std::vector<int> free_body;
  for (std::size_t b = 0; b < body.size(); ++b)
    if (!body_used[b]) free_body.push_back(static_cast<int>(b));
  Eigen::MatrixXd cost(left.size(), free_body.size());
  for (std::size_t i = 0; i < left.size(); ++i)
    for (std::size_t j = 0; j < free_body.size(); ++j)
      cost(i, j) = descriptor_cost(garment[left[i]], body[free_body[j]]);
  const std::vector<int> assignment = optimal_assignment(cost);
  for (std::size_t i = 0; i < left.size(); ++i) {
    const int j = assignment[i];
    if (j >= 0 && cost(i, j) <= options.max_cost) {
      body_used[free_body[j]] = true;
      out.matches.push_back({garment[left[i]].name, body[free_body[j]].name,
                             std::exp(-cost(i, j) / options.max_cost), "descriptor"});
    } else {
      out.unmatched_garment_parts.push_back(garment[left[i]].name);
    }
  }
  for (std::size_t b = 0; b < body.size(); ++b)
    if (!body_used[b]) out.unmatched_body_parts.push_back(body[b].name);
  return out;
}

}  // namespace dresskit::alignment
