// Area-weighted vertex normals of a triangle mesh.
#pragma once

#include "body/body_model.hpp"

namespace body {

// Sum of the (unnormalised, so area-weighted) face normals around each vertex, normalised.
// Vertices without faces (or with a zero sum) get (0, 1, 0) so every normal is unit length.
// `normals` is resized to V x 3.
void compute_vertex_normals(const Vertices& vertices, const Faces& faces, Vertices& normals);

}  // namespace body
