#pragma once
// The default mannequin and its garments, built once per test program (they take about a second).
#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"
#include "dresskit/testing/winding_number.h"

namespace dresskit::test {

struct DefaultScene {
  mannequin::BodyShape body;
  mesh::TriangleMesh mannequin;
  std::vector<mesh::TriangleMesh> garments;  // in mannequin::all_garment_kinds() order
  mannequin::GarmentOptions garment_options;

  static const DefaultScene& get() {
    static const DefaultScene scene;
    return scene;
  }

 private:
  DefaultScene() : body(mannequin::MannequinOptions{}), mannequin(make_mannequin(body)) {
    for (mannequin::GarmentKind kind : mannequin::all_garment_kinds()) garments.push_back(make_garment(body, kind, garment_options));
  }
};

}  // namespace dresskit::test
