// GarmentCode pattern JSON (docs/pattern.md): read and checked, drawn, and cut into triangles at a
// coarse edge length (the patterns the reader accepts must cut or be refused with an InputError).
#include <cstdint>
#include <string>

#include "dresskit/mesh/errors.h"
#include "dresskit/pattern/cut.h"
#include "dresskit/pattern/pattern.h"
#include "dresskit/pattern/svg.h"

using namespace dresskit::pattern;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Pattern pattern = parse_pattern(text, "pattern.json");
    (void)pattern_svg(pattern);
    (void)cut_pattern(pattern, {0.1});
  } catch (const dresskit::InputError&) {
  }
  return 0;
}
