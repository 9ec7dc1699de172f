// Units: a person is 0.5–2.5 m tall and a body is closed or nearly so; a garment is between a
// tenth and one and a half of its body.
#include "../measures.h"
#include "../outfit.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"

namespace dresskit::dressing::detail::stages {

using namespace dresskit::mesh;

StageReport units(Outfit& outfit, const DressOptions&) {
  const DressResult& result = outfit.result;
  const double body_height = height(result.body);
  outfit.body_height = body_height;
  check_body_units(result.body, outfit.body_file, result.garments);
  // A body is closed or nearly so (a scan may lack its soles or the top of its head); a garment's
  // openings (neck, cuffs, hem, waist) add up to more than its wearer's height.
  const double open = analyse_topology(result.body).boundary_length;
  if (open > body_height)
    throw InputError(outfit.body_file.path + ": does not look like a body: " + number(open) + " m of open edges on a mesh " +
                     number(body_height) + " m tall (a body is closed or nearly so; is it a garment?)");
  const auto fits_body = [&](double size) { return size >= 0.1 * body_height && size <= 1.5 * body_height; };
  for (const DressedGarment& g : result.garments) {
    const double size = bounding_box(g.mesh).sizes().maxCoeff();
    if (fits_body(size)) continue;
    const double in_file = size / g.file.load.units.metres_per_unit;
    std::string fits;
    for (const char* name : {"m", "dm", "cm", "mm"})
      if (fits.empty() && fits_body(in_file * Units::parse(name).metres_per_unit)) fits = name;
    throw InputError(g.file.path + ": the garment is " + number(size) + " m across in units " + g.file.load.units.name +
                     " on a body " + number(body_height) + " m tall" + units_hint("--garment-units", fits, "it fits"));
  }
  return ran("body " + number(body_height) + " m tall; garments " + std::to_string(result.garments.size()) +
             " within its size");
}

}  // namespace dresskit::dressing::detail::stages
