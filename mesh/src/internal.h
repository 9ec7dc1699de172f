#pragma once
// Helpers shared by the mesh module's translation units; not part of the public API.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <string>

namespace dresskit::mesh::detail {

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// For PLY and OFF files, before assimp reads them (io_headers.cpp): the header ends, its counts fit
/// in the file's size, and OFF face indices name existing vertices. Throws InputError naming the
/// file and what is wrong; other formats pass.
void check_declared_counts(const std::string& path);

/// A directed triangle up to rotation: (a,b,c), (b,c,a) and (c,a,b) give the same key, (a,c,b) not.
inline std::array<int, 3> directed_triangle_key(int a, int b, int c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

}  // namespace dresskit::mesh::detail
