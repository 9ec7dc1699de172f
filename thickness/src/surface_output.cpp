// The T(x, t) surface as CSV and as a PNG heat map (libpng, from Debian's libpng-dev).
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"
#include "dresskit/thickness/thickness.h"

using namespace dresskit::mesh;

namespace dresskit::thickness {
namespace {

/// Blue (cold) through light grey to red (warm), Moreland's "cool to warm" end and middle points.
void colour(double s, unsigned char* rgb) {
  static const double stops[3][3] = {{59, 76, 192}, {221, 221, 221}, {180, 4, 38}};
  s = std::clamp(s, 0.0, 1.0) * 2.0;
  const int k = s >= 1.0 ? 1 : 0;
  const double f = s - k;
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<unsigned char>(std::lround(stops[k][c] + f * (stops[k + 1][c] - stops[k][c])));
}

void append_bytes(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), size);
}

/// An RGB image encoded as PNG in memory; empty on failure.
std::string encode_png(const std::vector<unsigned char>& rgb, int width, int height) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return {};
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(png, &out, append_bytes, nullptr);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y)
    png_write_row(png, const_cast<png_bytep>(rgb.data() + static_cast<std::size_t>(y) * width * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

}  // namespace

void write_temperature_surface(const std::string& dir, const ThicknessResult& r,
                               const ThicknessOptions& o) {
  const HeatResult& h = r.nominal;
  if (h.surface.rows() == 0)
    throw OutputError("no temperature surface recorded (set heat.record_every)");

  std::ostringstream csv;
  csv.precision(10);
  csv << "time_s";
  for (Eigen::Index i = 0; i < h.x.size(); ++i) csv << ",T_at_" << h.x[i] * 1000.0 << "_mm";
  csv << "\n";
  for (Eigen::Index k = 0; k < h.surface.rows(); ++k) {
    csv << h.times[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < h.surface.cols(); ++i) csv << "," << h.surface(k, i);
    csv << "\n";
  }

  // Depth across (to the nominal thickness × 2.5, where nothing changes further), time downwards.
  const int width = 640, height = 480;
  const double x_max = std::min(h.x[h.x.size() - 1], 2.5 * std::max(r.thickness_max, r.thickness));
  const double t_end = h.times.back();
  const double lo = std::min(o.t_skin, o.t_env), span = std::abs(o.t_skin - o.t_env);
  std::vector<unsigned char> rgb(static_cast<std::size_t>(width) * height * 3);
  const double dx = h.x[1] - h.x[0];
  for (int py = 0; py < height; ++py) {
    const double t = t_end * py / (height - 1);
    // Recorded rows are at increasing times: interpolate between the two around t.
    const auto it = std::lower_bound(h.times.begin(), h.times.end(), t);
    const Eigen::Index k1 = std::min<Eigen::Index>(it - h.times.begin(), h.surface.rows() - 1);
    const Eigen::Index k0 = std::max<Eigen::Index>(k1 - 1, 0);
    const double t0 = h.times[static_cast<std::size_t>(k0)], t1 = h.times[static_cast<std::size_t>(k1)];
    const double ft = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    double previous = 0.0;
    for (int px = 0; px < width; ++px) {
      const double x = x_max * px / (width - 1);
      const Eigen::Index i0 = std::min<Eigen::Index>(static_cast<Eigen::Index>(x / dx), h.x.size() - 2);
      const double fx = std::clamp((x - h.x[i0]) / dx, 0.0, 1.0);
      auto at = [&](Eigen::Index k) { return (1 - fx) * h.surface(k, i0) + fx * h.surface(k, i0 + 1); };
      const double T = (1 - ft) * at(k0) + ft * at(k1);
      unsigned char* p = &rgb[(static_cast<std::size_t>(py) * width + px) * 3];
      colour((T - lo) / span, p);
      if (px > 0 && (previous - r.threshold) * (T - r.threshold) <= 0.0 && previous != T)
        p[0] = p[1] = p[2] = 0;  // the threshold isotherm in black
      previous = T;
    }
  }
  const std::string png = encode_png(rgb, width, height);
  if (png.empty()) throw OutputError(dir + "/temperature.png: PNG encoding failed");

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(dir + ": cannot create the folder (" + ec.message() + ")");
  const std::string csv_path = (std::filesystem::path(dir) / "temperature.csv").string();
  write_file_atomically(csv_path, csv.str());
  try {
    write_file_atomically((std::filesystem::path(dir) / "temperature.png").string(), png);
  } catch (...) {
    std::remove(csv_path.c_str());
    throw;
  }
}

}  // namespace dresskit::thickness
