#include "measures.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "dresskit/alignment/part_labels.h"
#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/io.h"

namespace dresskit::dressing::detail {

using namespace dresskit::mesh;

std::string number(double value, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

double height(const TriangleMesh& m) { return m.V.col(1).maxCoeff() - m.V.col(1).minCoeff(); }

SurfaceFit surface_fit(const Eigen::MatrixX3d& V, const InsideTest& body) {
  SurfaceFit fit;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double d = body.signed_distance(V.row(i).transpose());
    fit.mean_distance += std::abs(d);
    if (d < -0.002) ++fit.inside;
  }
  if (V.rows() > 0) fit.mean_distance /= static_cast<double>(V.rows());
  return fit;
}

bool on_body(const SurfaceFit& fit, Eigen::Index vertices, double body_height, const DressOptions& options) {
  return fit.inside <= options.fit_inside * static_cast<double>(vertices) &&
         fit.mean_distance <= options.fit_distance * body_height;
}

std::vector<double> structural_strains(const cloth::ClothModel& m, const Eigen::MatrixX3d& x) {
  const cloth::SpringSet& s = m.springs;
  std::vector<double> strain;
  for (int k = 0; k < s.size(); ++k)
    if (s.type[k] == cloth::SpringType::structural)
      strain.push_back((x.row(s.i[k]) - x.row(s.j[k])).norm() / s.rest_length[k] - 1.0);
  std::sort(strain.begin(), strain.end());
  return strain;
}

std::string units_hint(const std::string& option, const std::string& fits, const std::string& then) {
  return fits.empty() ? ": give its units (" + option + ")" : "; with " + option + " " + fits + " " + then;
}

void check_body_units(const TriangleMesh& body, const MeshFile& body_file, const std::vector<DressedGarment>& garments) {
  const double body_height = height(body);
  const double in_file = body_height / body_file.load.units.metres_per_unit;
  // A body lying along another of the file's axes than the up axis given (a Z-up file read as
  // Y-up), half as long again as it is tall (arms spread make it as wide as tall at most): that
  // axis is named, with the units that would then fit.
  const Eigen::MatrixX3d file = to_file_frame(body.V, body_file.load);
  const Eigen::Vector3d extent = file.colwise().maxCoeff() - file.colwise().minCoeff();
  Eigen::Index longest = 0;
  extent.maxCoeff(&longest);
  const UpAxis up = body_file.load.up;
  const int up_index = up == UpAxis::pos_x || up == UpAxis::neg_x ? 0 : up == UpAxis::pos_y || up == UpAxis::neg_y ? 1 : 2;
  const std::string said = body_file.path + ": the body is " + number(body_height) + " m tall in units " +
                           body_file.load.units.name;
  if (longest != up_index && extent[longest] > 1.5 * in_file) {
    const std::string name(1, "xyz"[longest]);
    const std::string along = units_for_body(extent[longest]);
    const bool same_units = along.empty() || Units::parse(along).metres_per_unit == body_file.load.units.metres_per_unit;
    const double metres = extent[longest] * (along.empty() ? body_file.load.units.metres_per_unit
                                                           : Units::parse(along).metres_per_unit);
    throw InputError(said + "; it is longest along the file's " + name + " axis: with --body-up " + name + " (or -" + name +
                     ")" + (same_units ? "" : " and --body-units " + along) + " it would be " + number(metres) +
                     " m tall");
  }
  if (body_height >= 0.5 && body_height <= 2.5) return;
  // One --units for all where every garment mesh is in the body's units and fits it as it is.
  bool as_body = !garments.empty();
  for (const DressedGarment& g : garments) {
    const double size = bounding_box(g.mesh).sizes().maxCoeff();
    as_body = as_body && !g.from_pattern && g.file.load.units.metres_per_unit == body_file.load.units.metres_per_unit &&
              size >= 0.1 * body_height && size <= 1.5 * body_height;
  }
  const std::string fits = units_for_body(in_file);
  throw InputError(said + units_hint(as_body && !fits.empty() ? "--units" : "--body-units", fits,
                                     "it would be " +
                                         number(fits.empty() ? 0.0 : in_file * Units::parse(fits).metres_per_unit) +
                                         " m"));
}

std::vector<DressPart> label(TriangleMesh& m, const MeshFile& f, const segmentation::SegmentationOptions& options,
                             bool& from_file) {
  std::vector<DressPart> parts;
  const bool with_mesh = f.labels.empty() && !m.label_names.empty() && m.labels.size() == m.num_vertices();
  from_file = !f.labels.empty() || with_mesh;
  if (from_file) {
    if (!with_mesh) alignment::apply_part_labels(m, f.labels, f.labels_key, f.path);
    parts.resize(m.label_names.size());
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k].name = m.label_names[k];
    for (Eigen::Index i = 0; i < m.labels.size(); ++i)
      if (m.labels(i) >= 0) ++parts[static_cast<std::size_t>(m.labels(i))].vertices;
    return parts;
  }
  const segmentation::SegmentationResult r = segmentation::segment_mesh(m, options);
  m.labels = r.vertex_labels;
  m.label_names = r.part_names();
  for (const segmentation::NamedPart& p : r.parts) parts.push_back({p.name, p.confidence, p.vertices});
  return parts;
}

}  // namespace dresskit::dressing::detail
