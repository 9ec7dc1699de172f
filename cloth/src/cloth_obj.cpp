// A cloth's positions as OBJ text (simulate's result.obj and frames).
#include <charconv>
#include <string>

#include "dresskit/cloth/scene.h"

namespace dresskit::cloth {

std::string cloth_obj_text(const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces, const SpringSet& springs) {
  std::string out = "# dresskit cloth: metres, +Y up\n";
  char buf[32];
  for (int i = 0; i < x.rows(); ++i) {
    out += 'v';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      out.append(buf, std::to_chars(buf, buf + sizeof buf, x(i, k)).ptr);
    }
    out += '\n';
  }
  for (int f = 0; f < faces.rows(); ++f) {
    out += "f " + std::to_string(faces(f, 0) + 1) + " " + std::to_string(faces(f, 1) + 1) + " " +
           std::to_string(faces(f, 2) + 1) + "\n";
  }
  if (faces.rows() == 0) {
    for (int k = 0; k < springs.size(); ++k) {
      out += "l " + std::to_string(springs.i[k] + 1) + " " + std::to_string(springs.j[k] + 1) + "\n";
    }
  }
  return out;
}

}  // namespace dresskit::cloth
