#include "body/mesh_normals.hpp"

#include <cmath>

namespace body {

void compute_vertex_normals(const Vertices& vertices, const Faces& faces, Vertices& normals) {
  const Eigen::Index V = vertices.rows();
  normals.setZero(V, 3);
  const float* p = vertices.data();
  float* n = normals.data();
  const std::uint32_t* f = faces.data();
  const Eigen::Index F = faces.rows();
  for (Eigen::Index i = 0; i < F; ++i) {
    const std::uint32_t a = f[3 * i], b = f[3 * i + 1], c = f[3 * i + 2];
    const float* pa = p + 3 * a;
    const float* pb = p + 3 * b;
    const float* pc = p + 3 * c;
    const float e1x = pb[0] - pa[0], e1y = pb[1] - pa[1], e1z = pb[2] - pa[2];
    const float e2x = pc[0] - pa[0], e2y = pc[1] - pa[1], e2z = pc[2] - pa[2];
    const float nx = e1y * e2z - e1z * e2y;
    const float ny = e1z * e2x - e1x * e2z;
    const float nz = e1x * e2y - e1y * e2x;
    float* na = n + 3 * a;
    float* nb = n + 3 * b;
    float* nc = n + 3 * c;
    na[0] += nx, na[1] += ny, na[2] += nz;
    nb[0] += nx, nb[1] += ny, nb[2] += nz;
    nc[0] += nx, nc[1] += ny, nc[2] += nz;
  }
  for (Eigen::Index v = 0; v < V; ++v) {
    float* nv = n + 3 * v;
    const float len2 = nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2];
    if (len2 > 1e-30f && std::isfinite(len2)) {
      const float inv = 1.0f / std::sqrt(len2);
      nv[0] *= inv, nv[1] *= inv, nv[2] *= inv;
    } else {
      nv[0] = 0.0f, nv[1] = 1.0f, nv[2] = 0.0f;
    }
  }
}

}  // namespace body
