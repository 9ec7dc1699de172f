// Checks of PLY and OFF files before assimp reads them. assimp trusts their declared counts: a PLY
// header that declares 10⁹ vertices over three makes it reserve gigabytes and read for minutes, a
// PLY header without its `end_header` line makes it loop, and an OFF face naming a vertex past the
// table is accepted. Here the header is read, the counts are checked against what the file's size
// can hold, and OFF face indices against the vertex count, each with one line naming the file. Files
// in binary and JSON formats must start as their format says (check_signature).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dresskit/mesh/errors.h"
#include "internal.h"

namespace dresskit::mesh::detail {
namespace {

/// Bytes of one value of a PLY scalar type; 0 for an unknown type.
int ply_type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

/// A non-negative count as written in a header; throws naming the file and what it counts.
std::uint64_t parse_count(const std::string& text, const std::string& path, const std::string& what) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 18)
    throw InputError(path + ": " + what + " count '" + text + "' is not a whole number");
  return std::stoull(text);
}

void check_ply(const std::string& path, std::uint64_t file_size) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::uint64_t header_bytes = 0;
  bool binary = false, ended = false;
  struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t least_bytes = 0;  // per item: binary, its smallest size; ascii, 2 per value
  };
  std::vector<Element> elements;
  for (int n = 0; n < 10000 && std::getline(in, line); ++n) {
    header_bytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (n == 0) {
      if (key != "ply") throw InputError(path + ": not a PLY file (first line is not 'ply')");
      continue;
    }
    if (key == "end_header") {
      // assimp finds the header's end only as a line of its own (after "end_header" and another
      // whitespace character it searched on forever).
      if (line != "end_header")
        throw InputError(path + ": PLY header line " + std::to_string(n + 1) + " has more than 'end_header'");
      ended = true;
      break;
    }
    if (key == "format") {
      std::string format;
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        throw InputError(path + ": unknown PLY format '" + format + "'");
      binary = format != "ascii";
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      e.count = parse_count(count, path, "PLY element '" + e.name + "'");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw InputError(path + ": PLY property before any element");
      std::string type;
      words >> type;
      std::uint64_t least = 2;  // ascii: a digit and a separator
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        if (ply_type_size(count_type) == 0 || ply_type_size(item_type) == 0)
          throw InputError(path + ": unknown PLY list type '" + count_type + " " + item_type + "'");
        least = static_cast<std::uint64_t>(ply_type_size(count_type));  // an empty list
      } else if (ply_type_size(type) == 0) {
        throw InputError(path + ": unknown PLY property type '" + type + "'");
      } else if (binary) {
        least = static_cast<std::uint64_t>(ply_type_size(type));
      }
      elements.back().least_bytes += binary ? least : 2;
    } else if (!key.empty() && key != "comment" && key != "obj_info") {
      throw InputError(path + ": PLY header line " + std::to_string(n + 1) + " starts with an unknown word '" +
                       key.substr(0, 40) + "'");
    }
  }
  if (!ended) throw InputError(path + ": PLY header has no 'end_header' line");
  long double least = 0.0L;
  std::string declared;
  for (const Element& e : elements) {
    least += static_cast<long double>(e.count) * static_cast<long double>(e.least_bytes);
    declared += (declared.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
  }
  const std::uint64_t body = file_size > header_bytes ? file_size - header_bytes : 0;
  if (least > static_cast<long double>(body))
    throw InputError(path + ": the PLY header declares " + declared + ", more than the file's " +
                     std::to_string(body) + " bytes after it can hold");
}

void check_off(const std::string& path, std::uint64_t file_size) {
  std::ifstream in(path, std::ios::binary);
  // Words of the file with comments (# to the end of a line) left out.
  auto next = [&](std::string& word) {
    while (in >> word) {
      if (word[0] != '#') return true;
      std::string rest;
      std::getline(in, rest);
    }
    return false;
  };
  std::string word;
  if (!next(word)) throw InputError(path + ": empty OFF file");
  // The keyword may carry prefixes (ST, C, N, 4, n) and be followed by the counts on its line.
  if (word.size() < 3 || word.compare(word.size() - 3, 3, "OFF") != 0)
    throw InputError(path + ": not an OFF file (no OFF keyword)");
  if (word != "OFF") return;  // coloured, textured or higher-dimensional variants: assimp's checks
  std::string nv_text, nf_text, ne_text;
  if (!next(nv_text) || !next(nf_text) || !next(ne_text))
    throw InputError(path + ": OFF header lacks its vertex, face and edge counts");
  if (nv_text == "BINARY") return;
  const std::uint64_t nv = parse_count(nv_text, path, "OFF vertex"), nf = parse_count(nf_text, path, "OFF face");
  // Each vertex takes at least "0 0 0\n", each face "3 0 1 2\n".
  if (static_cast<long double>(nv) * 6.0L + static_cast<long double>(nf) * 8.0L > static_cast<long double>(file_size))
    throw InputError(path + ": the OFF header declares " + std::to_string(nv) + " vertices and " +
                     std::to_string(nf) + " faces, more than the file's " + std::to_string(file_size) +
                     " bytes can hold");
  for (std::uint64_t v = 0; v < 3 * nv; ++v)
    if (!next(word)) throw InputError(path + ": OFF file ends inside its vertex table");
  for (std::uint64_t f = 0; f < nf; ++f) {
    if (!next(word)) throw InputError(path + ": OFF file ends before face " + std::to_string(f));
    const std::uint64_t corners = parse_count(word, path, "OFF face " + std::to_string(f) + " corner");
    for (std::uint64_t k = 0; k < corners; ++k) {
      if (!next(word)) throw InputError(path + ": OFF file ends inside face " + std::to_string(f));
      const std::uint64_t index = parse_count(word, path, "OFF face " + std::to_string(f) + " vertex index");
      if (index >= nv)
        throw InputError(path + ": OFF face " + std::to_string(f) + " names vertex " + std::to_string(index) +
                         " of " + std::to_string(nv));
    }
    std::string rest;  // a face line may end with a colour
    std::getline(in, rest);
  }
}

// assimp reads a file that its extension's reader refuses with any reader that recognises the
// content (its PLY reader takes a file with the word "ply" anywhere in its first 200 bytes, and can
// search forever for a header's end there): a binary or JSON format must start as that format.
void check_signature(const std::string& path, const std::string& ext, std::uint64_t size) {
  std::string head(std::size_t{512}, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::size_t text = head.find_first_not_of(" \t\r\n");
  const std::string start = text == std::string::npos ? "" : head.substr(text);
  auto starts = [](const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; };
  bool ok = true;
  std::string expected;
  if (ext == "glb") {
    ok = starts(head, "glTF"), expected = "the binary glTF header 'glTF'";
  } else if (ext == "gltf") {
    ok = starts(start, "{"), expected = "a JSON object";
  } else if (ext == "stl") {
    std::uint32_t triangles = 0;
    if (head.size() >= 84) std::memcpy(&triangles, head.data() + 80, sizeof triangles);
    ok = starts(start, "solid") || (head.size() >= 84 && size == 84 + 50 * std::uint64_t{triangles});
    expected = "'solid' or a binary STL's size for its triangle count";
  } else if (ext == "fbx") {
    ok = starts(head, "Kaydara FBX Binary") || starts(start, ";") || head.find("FBXHeaderExtension") != std::string::npos;
    expected = "an FBX header";
  }
  if (!ok) throw InputError(path + ": not a ." + ext + " file (it does not start with " + expected + ")");
}

}  // namespace

void check_declared_counts(const std::string& path) {
  const std::string ext = lower_extension(path);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return;
  // By extension, and by content too: assimp reads a file its extension's reader refuses with any
  // reader that recognises the content (a PLY named .glb is read as PLY).
  char start[16] = {};
  std::ifstream(path, std::ios::binary).read(start, sizeof start - 1);
  std::string first(start);
  first = first.substr(0, first.find_first_of("\r\n"));
  const std::string word = first.substr(0, first.find(' '));
  const bool off_magic = word.size() >= 3 && word.size() <= 6 && word.compare(word.size() - 3, 3, "OFF") == 0;
  check_signature(path, ext, size);
  if (ext == "ply" || first == "ply") check_ply(path, size);
  else if (ext == "off" || off_magic) check_off(path, size);
}

}  // namespace dresskit::mesh::detail
