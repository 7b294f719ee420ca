// Geometric checks of the default body model shared by the tests: mesh topology, inverted
// triangles, stature, and self-intersection between body regions.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace model_checks {

using Points = std::vector<Eigen::Vector3d>;
using Tris = std::vector<std::array<int, 3>>;

struct Topology {
  int vertices = 0, edges = 0, faces = 0;
  int non_manifold_edges = 0;     // undirected edges not in exactly 2 faces
  int inconsistent_edges = 0;     // directed edges used more than once (winding conflicts)
  int non_manifold_vertices = 0;  // faces around the vertex do not form one closed fan
  int unused_vertices = 0;
  int euler() const { return vertices - edges + faces; }
};

Topology topology(int vertex_count, const Tris& faces);
double signed_volume(const Points& v, const Tris& faces);

// Triangles whose normal turned by 90 degrees or more from the template's (n . n0 <= 0), and
// degenerate ones (area below 1e-12 m^2).
int inverted_triangles(const Points& base, const Points& deformed, const Tris& faces);

double stature(const Points& v);

// How far the chest stands forward of the fold below it, in metres. Along the nipple line
// (3.5-7.5% of the stature from the body's midline, on the front) the forward profile z(y)
// in bins of 0.5% of the stature; at each level of the chest band (70-78% of the stature from
// the soles; the nipples are at about 72%), the profile there minus its least value within
// `window` (a fraction of the stature) below: the inframammary fold under a breast, the lower
// border of a pectoral. A slim waist farther down, or a belly that rises higher than the
// chest, does not count.
double breast_projection(const Points& v, double window);

// Number of intersecting triangle pairs between faces of set A and faces of set B (pairs
// sharing a vertex are skipped).
int intersecting_pairs(const Points& v, const Tris& faces, const std::vector<int>& a,
                       const std::vector<int>& b);

}  // namespace model_checks
