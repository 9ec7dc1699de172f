#pragma once
// Garment parts to body parts: by semantic name when both sides have names in common, otherwise by
// shape descriptors and an optimal (Hungarian) assignment. Parts come from per-vertex labels
// (TriangleMesh::labels / label_names), whether read from a file or computed by segmentation.
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::alignment {

/// Shape descriptor of one labelled part, in the frame of the whole mesh.
struct PartDescriptor {
  std::string name;
  int label = -1;
  int vertices = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Vector3d relative_position =
      Eigen::Vector3d::Zero();  ///< (centroid − whole's centroid) / whole's diagonal
  Eigen::Vector3d extents =
      Eigen::Vector3d::Zero();  ///< principal standard deviations / whole's diagonal, descending
  Eigen::Vector3d main_axis = Eigen::Vector3d::UnitY();  ///< principal axis (sign: towards +Y)
  std::vector<std::string> neighbours;  ///< parts that share a mesh edge with this one
};

/// One descriptor per label that has at least one vertex.
std::vector<PartDescriptor> describe_parts(const mesh::TriangleMesh& mesh);

struct PartMatch {
  std::string garment_part, body_part;
  double confidence =
      0.0;         ///< 1 for a name match with similar descriptors, → 0 for dissimilar parts
  std::string by;  ///< "name" or "descriptor"
};

struct MatchingOptions {
  /// Descriptor matches costing more than this are left unmatched (cost: distance of relative
  /// positions plus extents plus (1 − |cos|) of the main axes).
  double max_cost = 0.5;
};

struct MatchingResult {
  std::vector<PartMatch> matches;
  std::vector<std::string> unmatched_garment_parts, unmatched_body_parts;
};

/// By name: a garment part matches the body part of the same name, and a skirt's halves
/// (skirt_left, skirt_right) the legs (leg_left, leg_right); the rest by descriptors.
MatchingResult match_parts(const std::vector<PartDescriptor>& garment,
                           const std::vector<PartDescriptor>& body,
                           const MatchingOptions& options = {});

/// Optimal assignment (Hungarian method) for a rows×cols cost matrix: column of each row, -1 for
/// none.
std::vector<int> optimal_assignment(const Eigen::MatrixXd& cost);

}  // namespace dresskit::alignment
