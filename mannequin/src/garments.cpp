#include "dresskit/mesh/names.h"
#include "dresskit/mannequin/garments.h"

#include <cmath>
#include <limits>

#include "dresskit/mesh/errors.h"
#include "dresskit/mesh/topology.h"
#include "mesh_field.h"

using namespace dresskit::mesh;

namespace dresskit::mannequin {

const std::vector<GarmentKind>& all_garment_kinds() {
  static const std::vector<GarmentKind> kinds = {GarmentKind::tshirt, GarmentKind::skirt,
                                                 GarmentKind::trousers};
  return kinds;
}

const NameTable<GarmentKind> kGarmentKinds = {{"tshirt", GarmentKind::tshirt}, {"t-shirt", GarmentKind::tshirt},
    {"skirt", GarmentKind::skirt}, {"trousers", GarmentKind::trousers}};
std::string to_string(GarmentKind kind) { return name_of(kind, kGarmentKinds); }

GarmentKind parse_garment_kind(const std::string& text) { return parse_name(text, kGarmentKinds, "garment"); }

const std::vector<std::string>& garment_part_names() {
  static const std::vector<std::string> names = {"body",     "sleeve_left", "sleeve_right",
                                                 "leg_left", "leg_right",   "skirt"};
  return names;
}

namespace {

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// The garment's solid: the named body primitives, each relabelled with its garment part.
ImplicitUnion garment_solid(const BodyShape& body, GarmentKind kind, double ease) {
  ImplicitUnion solid;
  solid.blend = body.field().blend;
  solid.offset = ease;
  for (Primitive p : body.field().primitives) {
    const bool left = p.name.size() > 5 && p.name.compare(p.name.size() - 5, 5, "_left") == 0;
    const bool trunk = p.name == "chest" || p.name == "abdomen" || p.name == "pelvis";
    bool take = false;
    switch (kind) {
      case GarmentKind::tshirt:
        // Thighs too: their tops reach out of the pelvis near the hem.
        take = trunk || starts_with(p.name, "upper_arm") || starts_with(p.name, "thigh");
        p.part = int(starts_with(p.name, "upper_arm")
                         ? (left ? GarmentPart::sleeve_left : GarmentPart::sleeve_right)
                         : GarmentPart::body);
        break;
      case GarmentKind::trousers:
        take = p.name == "abdomen" || p.name == "pelvis" || starts_with(p.name, "thigh") ||
               starts_with(p.name, "shin");
        p.part = int(trunk ? GarmentPart::body : left ? GarmentPart::leg_left : GarmentPart::leg_right);
        break;
      case GarmentKind::skirt:
        take = p.name == "abdomen" || p.name == "pelvis" || starts_with(p.name, "thigh");
        p.part = int(GarmentPart::skirt);
        break;
    }
    if (take) solid.primitives.push_back(p);
  }
  if (kind == GarmentKind::skirt) {
    // A flared cone from the waist to below the knees that encloses both legs.
    const Skeleton& s = body.skeleton();
    const double H = body.options().height, g = body.options().girth;
    solid.primitives.push_back(Primitive::round_cone(
        Eigen::Vector3d(0, s.waist_y - 0.01 * H, 0), Eigen::Vector3d(0, s.knee[0].y() + 0.02 * H, 0),
        0.08 * H * g, 0.15 * H * g, int(GarmentPart::skirt), "skirt_cone"));
  }
  return solid;
}

// Distance along a limb axis from its root joint [m].
double along(const Eigen::Vector3d& p, const Eigen::Vector3d& root, const Eigen::Vector3d& end) {
  return (p - root).dot((end - root).normalized());
}

}  // namespace

void check_options(const GarmentOptions& options) {
  if (!(options.ease >= 0.003 && options.ease <= 0.1)) {
    throw InputError("ease: " + std::to_string(options.ease) + " m is outside 0.003–0.1 m");
  }
  if (!(options.edge_length >= 0.004 && options.edge_length <= 0.1)) {
    throw InputError("edge length: " + std::to_string(options.edge_length) +
                     " m is outside 0.004–0.1 m");
  }
}

TriangleMesh make_garment(const BodyShape& body, GarmentKind kind, const GarmentOptions& options) {
  check_options(options);
  const ImplicitUnion solid = garment_solid(body, kind, options.ease);
  const Skeleton& s = body.skeleton();
  const double H = body.options().height;

  // Where to cut the closed solid open: keep where cut(p) < 0.
  std::function<double(const Eigen::Vector3d&)> cut;
  switch (kind) {
    case GarmentKind::tshirt: {
      const double hem_y = s.hip[0].y() + 0.02 * H;
      const double neck_radius = body.field().primitives[1].ra + options.ease + 0.025 * H;
      cut = [=, &solid](const Eigen::Vector3d& p) {
        double c = hem_y - p.y();
        // Neckline: a vertical cylinder around the neck, above the chest's widest part.
        const double neck = neck_radius - std::hypot(p.x() - s.neck_base.x(), p.z() - s.neck_base.z());
        if (p.y() > s.neck_base.y() - 0.06 * H) c = std::max(c, neck);
        const int part = solid.primitives[solid.nearest(p)].part;
        for (int side = 0; side < 2; ++side) {
          if (part != int(side == 0 ? GarmentPart::sleeve_left : GarmentPart::sleeve_right)) continue;
          const double length = (s.elbow[side] - s.shoulder[side]).norm();
          c = std::max(c, along(p, s.shoulder[side], s.elbow[side]) - 0.6 * length);
        }
        return c;
      };
      break;
    }
    case GarmentKind::trousers: {
      cut = [=, &solid](const Eigen::Vector3d& p) {
        double c = p.y() - (s.waist_y - 0.02 * H);
        const int part = solid.primitives[solid.nearest(p)].part;
        for (int side = 0; side < 2; ++side) {
          if (part != int(side == 0 ? GarmentPart::leg_left : GarmentPart::leg_right)) continue;
          const double length = (s.ankle[side] - s.hip[side]).norm();
          c = std::max(c, along(p, s.hip[side], s.ankle[side]) - (length - 0.03 * H));
        }
        return c;
      };
      break;
    }
    case GarmentKind::skirt: {
      const double waist = s.waist_y - 0.02 * H, hem = s.knee[0].y() + 0.06 * H;
      cut = [=](const Eigen::Vector3d& p) { return std::max(p.y() - waist, hem - p.y()); };
      break;
    }
  }

  TriangleMesh mesh = mesh_implicit(solid, options.edge_length, feature_spacing(H), cut);
  // The garment must be one piece with exactly its openings and no handle. On very thin or very
  // large bodies a big ease can fuse the legs or cut a sliver off at the neckline: say so rather
  // than return a surface that is not the garment.
  const int loops = kind == GarmentKind::tshirt ? 4 : kind == GarmentKind::skirt ? 2 : 3;
  const TopologyReport t = analyse_topology(mesh);
  if (!t.manifold || t.num_components != 1 || t.num_boundary_loops != loops ||
      t.euler_characteristic != 2 - loops) {
    const int handles = (2 * t.num_components - t.euler_characteristic - t.num_boundary_loops) / 2;
    throw InputError("garment " + to_string(kind) + ": ease " + std::to_string(options.ease) +
                     " m on a body of height " + std::to_string(H) + " m and girth " +
                     std::to_string(body.options().girth) + " gives " +
                     std::to_string(t.num_components) + " piece(s), " +
                     std::to_string(t.num_boundary_loops) + " openings and " +
                     std::to_string(std::max(handles, 0)) + " handle(s) instead of one piece with " +
                     std::to_string(loops) + " openings and no handle (try a smaller ease)");
  }
  mesh.label_names = garment_part_names();
  mesh.labels.resize(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    mesh.labels(i) = solid.primitives[solid.nearest(mesh.V.row(i).transpose())].part;
  }
  return mesh;
}

}  // namespace dresskit::mannequin
