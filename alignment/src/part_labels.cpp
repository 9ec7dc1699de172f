#include "dresskit/alignment/part_labels.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "dresskit/mesh/errors.h"

using namespace dresskit::mesh;

namespace dresskit::alignment {

namespace {
/// A JSON value that must be a whole number within int (JSON numbers may be any size; converting
/// one beyond int is undefined behaviour).
int whole_number(const nlohmann::json& v, const std::string& path, const std::string& field) {
  if (v.is_number_integer()) {
    const auto wide = v.get<long long>();
    if (wide >= std::numeric_limits<int>::min() && wide <= std::numeric_limits<int>::max()) return static_cast<int>(wide);
  }
  throw InputError(path + ": " + field + ": " + v.dump() + " is not a whole number within range");
}
}  // namespace

void apply_part_labels(TriangleMesh& mesh, const std::string& labels_path, const std::string& key,
                       const std::string& mesh_path) {
  using json = nlohmann::json;
  std::ifstream in(labels_path);
  if (!in) throw InputError(labels_path + ": cannot open labels file");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(labels_path + ": not valid JSON: " + e.what());
  }
  int source_count = 0;
  for (Eigen::Index i = 0; i < mesh.source_vertex.size(); ++i)
    source_count = std::max(source_count, mesh.source_vertex(i) + 1);
  if (mesh.source_vertex.size() == 0) source_count = mesh.num_vertices();

  std::vector<std::string> per_source(source_count);  // part name per source vertex
  try {
    const json* list = nullptr;
    const bool from_segment = j.contains("vertex_labels") && j.contains("part_names");
    if (from_segment) {  // segment's labels.json: part ids per vertex and their names
      const json& ids = j["vertex_labels"];
      const json& names = j["part_names"];
      if (static_cast<int>(ids.size()) != source_count)
        throw InputError(labels_path + ": " + std::to_string(ids.size()) + " vertex_labels for a mesh of " +
                         std::to_string(source_count) + " vertices");
      for (int i = 0; i < source_count; ++i) {
        const int id = whole_number(ids[static_cast<std::size_t>(i)], labels_path, "vertex_labels");
        if (id >= static_cast<int>(names.size()))
          throw InputError(labels_path + ": vertex " + std::to_string(i) + " has part " + std::to_string(id) +
                           " of " + std::to_string(names.size()) + " part_names");
        if (id >= 0) per_source[static_cast<std::size_t>(i)] = names[static_cast<std::size_t>(id)].get<std::string>();
      }
    } else if (j.contains("labels") && j["labels"].is_array()) {
      list = &j["labels"];
    } else if (j.contains("labels") && j["labels"].is_object()) {
      std::vector<std::string> keys;
      if (!key.empty()) keys.push_back(key);
      if (key.empty() && !mesh_path.empty()) {
        const std::string stem = std::filesystem::path(mesh_path).stem().string();
        keys.push_back(stem);
        if (stem.rfind("mh_", 0) == 0) keys.push_back(stem.substr(3));
      }
      for (const auto& k : keys)
        if (!list && j["labels"].contains(k)) list = &j["labels"][k];
      if (!list) {
        std::string known;
        for (const auto& [k, v] : j["labels"].items()) known += (known.empty() ? "" : ", ") + k;
        throw InputError(labels_path + ": no labels for '" + (keys.empty() ? std::string("?") : keys.front()) +
                         "' (the file has: " + known + ")");
      }
    }
    if (list) {
      if (static_cast<int>(list->size()) != source_count)
        throw InputError(labels_path + ": " + std::to_string(list->size()) +
                         " labels for a mesh of " + std::to_string(source_count) + " vertices");
      for (int i = 0; i < source_count; ++i) per_source[i] = (*list)[i].get<std::string>();
    } else if (!from_segment) {  // {"part": [indices]}
      for (const auto& [part, indices] : j.items()) {
        if (!indices.is_array()) continue;
        for (const auto& index : indices) {
          const int i = whole_number(index, labels_path, "part " + part);
          if (i < 0 || i >= source_count)
            throw InputError(labels_path + ": part " + part + " names vertex " + std::to_string(i) +
                             " of a mesh with " + std::to_string(source_count) + " vertices");
          per_source[i] = part;
        }
      }
    }
  } catch (const json::exception& e) {
    throw InputError(labels_path + ": malformed labels: " + e.what());
  }

  std::map<std::string, int> ids;
  mesh.label_names.clear();
  for (const auto& name : per_source) {
    if (!name.empty() && !ids.count(name)) {
      ids[name] = static_cast<int>(mesh.label_names.size());
      mesh.label_names.push_back(name);
    }
  }
  mesh.labels = Eigen::VectorXi::Constant(mesh.num_vertices(), -1);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const int s = mesh.source_vertex.size() ? mesh.source_vertex(v) : v;
    if (s >= 0 && s < source_count && !per_source[s].empty()) mesh.labels(v) = ids[per_source[s]];
  }
}

}  // namespace dresskit::alignment
