// Part label files (docs/formats.md) applied to a small mesh: a tetrahedron.
#include <cstdint>

#include "dresskit/alignment/part_labels.h"
#include "dresskit/mesh/errors.h"
#include "fuzz_input.h"

using namespace dresskit::alignment;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = dresskit::fuzz::write_input("labels.json", data, size);
  dresskit::mesh::TriangleMesh mesh;
  mesh.V.resize(4, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.F.resize(4, 3);
  mesh.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  mesh.source_vertex.resize(4);
  mesh.source_vertex << 0, 1, 2, 3;
  try {
    dresskit::alignment::apply_part_labels(mesh, path, "mesh", "mesh.obj");
  } catch (const dresskit::InputError&) {
  }
  return 0;
}
