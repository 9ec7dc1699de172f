// Cloth scene files (docs/scenes.md); files a scene names are looked up beside it.
#include <cstdint>

#include "dresskit/cloth/scene.h"
#include "dresskit/mesh/errors.h"
#include "fuzz_input.h"

using namespace dresskit::cloth;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = dresskit::fuzz::write_input("scene.json", data, size);
  try {
    dresskit::cloth::load_cloth_scene(path);
  } catch (const dresskit::InputError&) {
  }
  return 0;
}
