#pragma once
// Small meshes with known answers, built in code.
#include "dresskit/mesh/triangle_mesh.h"

namespace dresskit::fixtures {

/// Unit right tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), outward.
inline mesh::TriangleMesh tetrahedron() {
  mesh::TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

/// Axis-aligned cube of side s centred at the origin, as 6 quads (12 triangles), outward.
inline mesh::TriangleMesh cube(double s) {
  mesh::TriangleMesh m;
  m.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.V.row(i) << (i & 1 ? 0.5 : -0.5) * s, (i & 2 ? 0.5 : -0.5) * s, (i & 4 ? 0.5 : -0.5) * s;
  m.quads.resize(6, 4);
  m.quads << 0, 2, 3, 1,  4, 5, 7, 6,  0, 1, 5, 4,  2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5;
  m.F.resize(12, 3);
  for (int q = 0; q < 6; ++q) {
    m.F.row(2 * q) << m.quads(q, 0), m.quads(q, 1), m.quads(q, 2);
    m.F.row(2 * q + 1) << m.quads(q, 0), m.quads(q, 2), m.quads(q, 3);
  }
  return m;
}

/// An nx × ny grid of unit-square cells of size h in the XY plane, two triangles per cell.
inline mesh::TriangleMesh grid(int nx, int ny, double h) {
  mesh::TriangleMesh m;
  m.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.V.row(j * (nx + 1) + i) << i * h, j * h, 0.0;
  m.F.resize(2 * nx * ny, 3);
  int f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      m.F.row(f++) << a, b, c;
      m.F.row(f++) << a, c, d;
    }
  return m;
}

/// Two tetrahedra that share one vertex (index 0): a non-manifold vertex.
inline mesh::TriangleMesh bowtie_tetrahedra() {
  mesh::TriangleMesh m;
  m.V.resize(7, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3,  //
      0, 4, 5, 0, 6, 4, 0, 5, 6, 4, 6, 5;
  return m;
}

}  // namespace dresskit::fixtures
