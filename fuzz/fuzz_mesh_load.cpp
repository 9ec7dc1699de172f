// Mesh files of every loadable format: the first byte picks the format, the rest is the file.
#include <cstdint>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "fuzz_input.h"

using namespace dresskit::mesh;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* const kExtensions[] = {"obj", "ply", "off", "stl", "gltf", "glb", "fbx"};
  if (size < 1) return 0;
  const std::string ext = kExtensions[data[0] % (sizeof kExtensions / sizeof *kExtensions)];
  const std::string path = dresskit::fuzz::write_input("mesh." + ext, data + 1, size - 1);
  try {
    dresskit::mesh::load_mesh(path);
  } catch (const dresskit::InputError&) {
  }
  return 0;
}
