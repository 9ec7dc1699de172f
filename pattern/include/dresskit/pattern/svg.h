#pragma once
// The flat pattern as a picture (SVG): every panel's outline laid out side by side, its name, each
// edge's number, and stitched edges drawn in one colour per stitch (both sides of a stitch alike),
// with an arrow at each side's start so that how the two sides meet can be checked.
#include <string>

#include "dresskit/pattern/pattern.h"

namespace dresskit::pattern {

struct SvgOptions {
  double pixels_per_metre = 500.0;  ///< drawing scale [px/m]
  double gap = 0.06;                ///< space between panels and around the picture [m]
  double row_width = 2.4;           ///< panels are laid out left to right in rows this wide [m]
  double sample_step = 0.005;       ///< curves are drawn as polylines of this step [m]
};

/// The SVG text of the pattern's picture.
std::string pattern_svg(const Pattern& pattern, const SvgOptions& options = {});

/// Writes the picture to `path`. Throws OutputError naming the file when it cannot be written.
void write_pattern_svg(const std::string& path, const Pattern& pattern,
                       const SvgOptions& options = {});

/// The colour of stitch i in the picture ("#rrggbb"), distinct for neighbouring i.
std::string stitch_colour(int stitch);

}  // namespace dresskit::pattern
