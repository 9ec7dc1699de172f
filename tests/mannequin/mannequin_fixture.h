#pragma once
// The default mannequin and its garments, built once per test program (they take about a second).
#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"

namespace dresskit::test {

struct DefaultScene {
  BodyShape body;
  TriangleMesh mannequin;
  std::vector<TriangleMesh> garments;  // in all_garment_kinds() order
  GarmentOptions garment_options;

  static const DefaultScene& get() {
    static const DefaultScene scene;
    return scene;
  }

 private:
  DefaultScene() : body(MannequinOptions{}), mannequin(make_mannequin(body)) {
    for (GarmentKind kind : all_garment_kinds()) garments.push_back(make_garment(body, kind, garment_options));
  }
};

/// Generalised winding number of point p with respect to a closed triangle mesh: 1 inside, 0 outside
/// (sum of signed solid angles, Van Oosterom–Strackee). Independent of the implicit field.
inline double winding_number(const TriangleMesh& m, const Eigen::Vector3d& p) {
  double total = 0.0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose() - p, b = m.V.row(m.F(f, 1)).transpose() - p,
                          c = m.V.row(m.F(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * M_PI);
}

}  // namespace dresskit::test
