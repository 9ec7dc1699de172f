#pragma once
// Ground-truth part labels of the shared data (../shared/data/labels, index = OBJ `v` order),
// mapped to the names segment_mesh gives. Used by the tests and by bench_segmentation.
#include <Eigen/Core>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dresskit::test {

struct GroundTruth {
  Eigen::VectorXi labels;  ///< #V index into names, −1 = not compared
  std::vector<std::string> names;
};

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// Per-vertex names → labels through a name map (names missing from the map → −1).
inline GroundTruth truth_from_names(const std::vector<std::string>& per_vertex,
                                    const std::map<std::string, std::string>& rename,
                                    const std::vector<std::string>& names) {
  GroundTruth t;
  t.names = names;
  t.labels = Eigen::VectorXi::Constant(static_cast<int>(per_vertex.size()), -1);
  for (size_t i = 0; i < per_vertex.size(); ++i) {
    const auto it = rename.find(per_vertex[i]);
    const std::string name = it == rename.end() ? per_vertex[i] : it->second;
    const auto pos = std::find(names.begin(), names.end(), name);
    if (pos != names.end()) t.labels(static_cast<int>(i)) = static_cast<int>(pos - names.begin());
  }
  return t;
}

/// MakeHuman bodies: six parts; head_neck is our head.
inline GroundTruth mh_body_truth(const std::string& data_dir) {
  const auto j = read_json(data_dir + "/labels/mh_body_part_labels.json");
  return truth_from_names(j["labels"].get<std::vector<std::string>>(), {{"head_neck", "head"}},
                          {"head", "torso", "arm_left", "arm_right", "leg_left", "leg_right"});
}

/// GarmentCode bodies: `body` is head + torso (compare after merging our head into the torso);
/// face_internal and unlisted vertices are not compared.
inline GroundTruth gc_body_truth(const std::string& data_dir, int num_vertices) {
  const auto j = read_json(data_dir + "/labels/gc_body_segmentation.json");
  GroundTruth t;
  t.names = {"torso", "arm_left", "arm_right", "leg_left", "leg_right"};
  const std::vector<std::string> keys = {"body", "left_arm", "right_arm", "left_leg", "right_leg"};
  t.labels = Eigen::VectorXi::Constant(num_vertices, -1);
  for (size_t k = 0; k < keys.size(); ++k)
    for (int v : j[keys[k]].get<std::vector<int>>()) t.labels(v) = static_cast<int>(k);
  return t;
}

/// MakeHuman outfits (key e.g. "female_casualsuit01"): arm_* on a top is a sleeve; head_neck (the
/// collar) counts as torso.
inline GroundTruth mh_outfit_truth(const std::string& data_dir, const std::string& key) {
  const auto j = read_json(data_dir + "/labels/mh_clothes_part_labels.json");
  return truth_from_names(j["labels"][key].get<std::vector<std::string>>(),
                          {{"head_neck", "torso"}},
                          {"torso", "arm_left", "arm_right", "leg_left", "leg_right"});
}

}  // namespace dresskit::test
