// Every bad input of the loaders gives an InputError whose message is one line naming the file.
#include <gtest/gtest.h>

#include <fstream>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "test_data.h"

using namespace dresskit;
using namespace dresskit::mesh;

namespace {
struct BadFile {
  const char* name;      // file name, its extension chooses the reader
  std::string contents;  // file contents
  const char* expected;  // a fragment of the message
};

std::string garbage(size_t n) {
  std::string s(n, '\0');
  unsigned x = 12345;
  for (auto& c : s) c = static_cast<char>((x = x * 1103515245u + 12345u) >> 16);
  return s;
}

const BadFile kBadFiles[] = {
    {"empty.obj", "", "empty file"},
    {"empty.ply", "", "empty file"},
    {"no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
    {"truncated_vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1", ":3: "},
    {"truncated_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2", ":4: face line with 2 corners"},
    {"truncated_point.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1", ":5: face line with 1 corner"},
    {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite"},
    {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "non-finite"},
    {"out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out_of_range.obj"},
    {"garbage.obj", garbage(4096), "garbage.obj"},
    {"garbage.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n" + garbage(7),
     "garbage.ply"},
    {"random.ply", garbage(2048), "random.ply"},
    {"nan.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n",
     "non-finite"},
    {"out_of_range.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
     "out_of_range.ply"},
    // Declared counts the file cannot hold: refused at once, not read for minutes into gigabytes.
    {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
     "declares 1000000000 vertex"},
    {"huge_binary.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n" + garbage(36),
     "more than the file's 36 bytes"},
    // A header whose end is misspelt or missing (assimp looped on both).
    {"misspelt_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nend_hedaer\n0 0 0\n1 0 0\n0 1 0\n",
     "line 7 starts with an unknown word 'end_hedaer'"},
    {"no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\n",
     "no 'end_header' line"},
    // Found by fuzzing: assimp searched forever for a header's end followed by another whitespace
    // character, and an unknown header line is refused rather than guessed at.
    {"end_tab.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\v0 0 0\n1 0 0\n0 1 0\n",
     "line 7 has more than 'end_header'"},
    {"unknown_word.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n-property float y\n"
                         "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
     "line 5 starts with an unknown word '-property'"},
    {"huge.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "declares 1000000000 vertices"},
    {"out_of_range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "face 0 names vertex 7 of 3"},
    {"negative.off", "OFF\n3 -1 0\n0 0 0\n1 0 0\n0 1 0\n", "is not a whole number"},
    {"mesh.xyz", "1 2 3\n", "unsupported extension"},
    {"garbage.stl", garbage(300), "garbage.stl"},
    // Read by content whatever the extension: a PLY without its end_header named .glb (found by
    // fuzzing: assimp's PLY reader looped on it), an OFF declaring 10⁹ vertices named .obj.
    {"ply_inside.glb", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nenf\xac\xac" "ement face 2\np",
     "not a .glb file (it does not start with the binary glTF header 'glTF')"},
    // Found by fuzzing: assimp's PLY reader took a .glb with the word "ply" in its first bytes and
    // searched forever for its header's end; a binary or JSON format must start as that format.
    {"ply_word.glb", "ply\x01\xb4p\x01ply\nformat ascii 0.0\nele\n\x10ment vertex 3\nproperty list uchar ",
     "not a .glb file"},
    {"ply_word.gltf", "ply\nformat ascii 1.0\nelement vertex 3\n", "not a .gltf file (it does not start with a JSON object)"},
    {"ply_word.fbx", "ply\nformat ascii 1.0\nelement vertex 3\n", "not a .fbx file"},
    {"off_inside.obj", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "declares 1000000000 vertices"},
};
}  // namespace

class BadInput : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadInput, OneLineNamingTheFile) {
  test::TempDir dir;
  const BadFile& bad = GetParam();
  const std::string path = dir.file(bad.name);
  std::ofstream(path, std::ios::binary) << bad.contents;
  try {
    load_mesh(path);
    FAIL() << "no error for " << bad.name;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadInput, ::testing::ValuesIn(kBadFiles),
                         [](const auto& info) {
                           std::string n = info.param.name;
                           for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

TEST(BadInput, MissingFileAndFolder) {
  test::TempDir dir;
  EXPECT_THROW(load_mesh(dir.file("nope.obj")), InputError);
  try {
    load_mesh(dir.path().string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos);
  }
}
