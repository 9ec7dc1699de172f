#pragma once
// The signed distance to a body mesh, precomputed once per body: a grid of exact distances in a
// narrow band around the surface (trilinear lookup, ~30 ns a query: what the cloth's collision
// handling calls every step), the sign from ray parity along the three grid axes (majority vote), and
// exact closest-point queries through a bounding volume hierarchy where the band does not reach
// (deep inside, or outside the grid).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "dresskit/cloth/triangle_bvh.h"
#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::cloth {

struct MeshDistanceOptions {
  double cell = 0.005;     ///< grid spacing [m]
  double band = 0.012;     ///< exact distances stored within this distance of the surface [m]; at
                           ///< least 2√3 cells (raised to that)
  double padding = 0.05;   ///< the grid reaches this far beyond the mesh's bounding box [m]
};

struct MeshDistanceReport {
  /// Watertight: every edge has exactly two faces (no boundary, no edge of three or more faces), so
  /// every ray crosses the surface an even number of times and ray parity tells inside exactly.
  /// Pinched vertices and vertices used by no face do not matter here.
  bool closed = false;
  int boundary_edges = 0;
  int non_manifold_edges = 0;  ///< edges with more than two faces
  /// How inside was told from outside: "ray parity along x, y and z (watertight mesh)", or, for a
  /// mesh that is not watertight, the fallback "majority of the ray parities along x, y and z (not
  /// watertight)".
  std::string sign_method;
  int sign_disagreements = 0;  ///< grid points where the three parities did not all agree
  Eigen::Vector3i grid = Eigen::Vector3i::Zero();  ///< points per axis
  double cell = 0.0, band = 0.0;  ///< as used [m]
  double build_seconds = 0.0;
  std::size_t memory_bytes = 0;
};

class MeshDistance {
 public:
  /// Throws InputError when the mesh has no faces or a non-finite coordinate, or the options are out
  /// of range; the grid is capped at 2e8 points (InputError naming the cell size beyond that).
  explicit MeshDistance(const mesh::TriangleMesh& body, const MeshDistanceOptions& options = {});

  /// Signed distance from p to the surface [m], negative inside, and the outward unit direction
  /// (the normalised gradient of the distance). Exact to the grid's interpolation within the band
  /// and deep inside; farther outside it is a lower bound of at least the band (enough to tell that
  /// there is no contact).
  double distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward) const { return distance(p, outward, nullptr); }
  /// The grid cell a point was last looked up in, with its eight corner values: a particle that
  /// stays in its cell (5 mm) from one lookup to the next (a cloth resting on the body, looked up
  /// at every projective iteration) reads them from here rather than from the grid, whose tens of
  /// megabytes made the first corner's load a cache miss (a third of a lookup's time).
  struct Cell {
    int key = -1;  ///< the cell's first corner's place in the grid; −1: none yet
    float corner[8] = {};
  };
  /// The same as distance(p, outward), the same value to the bit, through `cell`'s corner values
  /// when p lies in that cell (and updating `cell` when it does not); cell may be null.
  double distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward, Cell* cell) const;
  /// The same from the exact closest point (BVH) with the grid's sign: slow, for checks and far points.
  double exact_distance(const Eigen::Vector3d& p, Eigen::Vector3d* outward) const;
  /// Inside by the grid's sign (the trilinear value's sign; false outside the grid).
  bool inside(const Eigen::Vector3d& p) const;

  const MeshDistanceReport& report() const { return report_; }
  const mesh::TriangleMesh& mesh() const { return mesh_; }

 private:
  /// Where grid point (i, j, k) is stored: in bricks of 8 × 8 × 8 points, so that a lookup's eight
  /// corners lie within one or two kilobytes instead of three rows and two planes of the grid apart
  /// (each a cache and page miss on the tens-of-megabytes grid of a body).
  int index(int i, int j, int k) const {
    return ((((k >> 3) * bricks_[1] + (j >> 3)) * bricks_[0] + (i >> 3)) << 9) | ((k & 7) << 6) |
           ((j & 7) << 3) | (i & 7);
  }

  mesh::TriangleMesh mesh_;
  TriangleBvh bvh_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i size_ = Eigen::Vector3i::Zero();
  Eigen::Vector3i bricks_ = Eigen::Vector3i::Zero();  ///< bricks of 8³ points per axis
  double h_ = 0.0, inv_h_ = 0.0, band_ = 0.0;
  std::vector<float> phi_;  ///< signed distance per grid point, clamped to ±band [m]
  MeshDistanceReport report_;
};

}  // namespace dresskit::cloth
