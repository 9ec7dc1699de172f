#pragma once
// Procedural garments fitted to the procedural mannequin: the body's own primitives (a subset of them,
// plus a cone for the skirt) offset outwards by an ease, meshed, and cut open at the neckline, cuffs,
// waist and hems. Every vertex carries its true garment part by construction.
#include <string>
#include <vector>

#include "dresskit/mesh/triangle_mesh.h"
#include "dresskit/mannequin/mannequin.h"

namespace dresskit::mannequin {

enum class GarmentKind { tshirt, skirt, trousers };
const std::vector<GarmentKind>& all_garment_kinds();
std::string to_string(GarmentKind kind);
/// "tshirt" / "t-shirt", "skirt", "trousers"; throws InputError naming the value otherwise.
GarmentKind parse_garment_kind(const std::string& text);

/// Garment parts, shared by every garment so that labels compare across garments.
enum class GarmentPart : int { body = 0, sleeve_left, sleeve_right, leg_left, leg_right, skirt };
const std::vector<std::string>& garment_part_names();

struct GarmentOptions {
  double ease = 0.015;        ///< [m] gap between body and garment at rest, 0.003–0.1
  double edge_length = 0.02;  ///< [m] target edge length, 0.004–0.1
};

/// Throws InputError naming the field when an option is out of its documented range.
void check_options(const GarmentOptions& options);

/// An open, manifold, consistently oriented (normals away from the body) triangle mesh with per-vertex
/// part labels (label_names = garment_part_names()). Boundary loops: t-shirt 4 (neck, hem, two cuffs),
/// skirt 2 (waist, hem), trousers 3 (waist, two hems). Throws InputError naming the options when
/// they are out of range or give another surface (e.g. a large ease on a very thin body fuses the
/// trouser legs).
mesh::TriangleMesh make_garment(const BodyShape& body, GarmentKind kind, const GarmentOptions& options = {});

}  // namespace dresskit::mannequin
