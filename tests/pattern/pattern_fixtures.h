#pragma once
// Small pattern files written in the tests, and the shared GarmentCode patterns by path.
#include <string>
#include <vector>

#include "test_data.h"

namespace dresskit::test {

/// The shared GarmentCode patterns (made for the gc_mean_all body, cm).
inline std::vector<std::string> shared_patterns() {
  return {"gc_shirt_mean_specification.json", "gc_hoody_mean_specification.json",
          "gc_dress_pencil_specification.json"};
}
inline std::string shared_pattern(const std::string& name) {
  return data_dir() + "/patterns/" + name;
}

/// Two 40 × 60 cm rectangles (cm), front at z = +15 and back at z = −15, sewn along both long
/// sides; `edits` is spliced into the front panel's edge 1 (e.g. a curvature).
inline std::string two_panel_pattern(
    const std::string& front_edge1 = "{\"endpoints\": [1, 2]}",
    const std::string& stitches =
        "[[{\"panel\": \"front\", \"edge\": 1}, {\"panel\": \"back\", \"edge\": 3}],"
        " [{\"panel\": \"front\", \"edge\": 3}, {\"panel\": \"back\", \"edge\": 1}]]",
    const std::string& properties =
        "{\"curvature_coords\": \"relative\", \"units_in_meter\": 100}") {
  return R"({"pattern": {"panels": {
    "front": {"translation": [-20, 80, 15], "rotation": [0, 0, 0],
              "vertices": [[0, 0], [40, 0], [40, 60], [0, 60]],
              "edges": [{"endpoints": [0, 1]}, )" +
         front_edge1 + R"(, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]},
    "back": {"translation": [20, 80, -15], "rotation": [0, 180, 0],
             "vertices": [[0, 0], [40, 0], [40, 60], [0, 60]],
             "edges": [{"endpoints": [0, 1]}, {"endpoints": [1, 2]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]}},
  "stitches": )" +
         stitches + R"(},
  "properties": )" +
         properties + "}";
}

}  // namespace dresskit::test
