// Robustness sweep of the embedded default scene: mannequins and garments over poses, girths, heights
// and edge lengths. Prints every configuration that does not give the expected surface and a summary.
// Usage: bench_scene_sweep [--quick]   (full: 150 bodies × 3 garments, about 16 minutes on one core;
// quick: edge lengths 2–5 cm only)
#include <cstdio>
#include <cstring>
#include <vector>

#include "dresskit/mesh/topology.h"
#include "dresskit/mannequin/garments.h"
#include "dresskit/mannequin/mannequin.h"

using namespace dresskit;
using namespace dresskit::mannequin;
using namespace dresskit::mesh;

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::vector<double> edges = {0.01, 0.0173, 0.02, 0.031, 0.05};
  if (quick) edges = {0.02, 0.031, 0.05};
  int bodies = 0, bad_bodies = 0, garments = 0, refused = 0;
  for (Pose pose : {Pose::a_pose, Pose::t_pose})
    for (double girth : {0.6, 0.8, 1.0, 1.3, 1.8})
      for (double height : {1.0, 1.75, 2.5})
        for (double edge : edges) {
          MannequinOptions o;
          o.pose = pose;
          o.girth = girth;
          o.height = height;
          o.edge_length = edge;
          const char* pose_name = pose == Pose::a_pose ? "a-pose" : "t-pose";
          ++bodies;
          const BodyShape body(o);
          try {
            make_mannequin(body);  // throws unless closed, outward and genus 0
          } catch (const std::exception& e) {
            ++bad_bodies;
            std::printf("mannequin %s girth %.1f height %.2f edge %.4f: %s\n", pose_name, girth,
                        height, edge, e.what());
          }
          GarmentOptions g;
          g.edge_length = edge;
          for (GarmentKind kind : all_garment_kinds()) {
            ++garments;
            try {
              make_garment(body, kind, g);  // throws unless one piece with its openings, no handle
            } catch (const std::exception& e) {
              ++refused;
              std::printf("%s %s girth %.1f height %.2f edge %.4f: %s\n", to_string(kind).c_str(),
                          pose_name, girth, height, edge, e.what());
            }
          }
        }
  std::printf("mannequins: %d of %d closed genus-0; garments: %d of %d as expected, %d refused\n",
              bodies - bad_bodies, bodies, garments - refused, garments, refused);
  return bad_bodies == 0 ? 0 : 1;
}
