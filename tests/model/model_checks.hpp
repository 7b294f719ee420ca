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

// Number of intersecting triangle pairs between faces of set A and faces of set B (pairs
// sharing a vertex are skipped).
int intersecting_pairs(const Points& v, const Tris& faces, const std::vector<int>& a,
                       const std::vector<int>& b);

}  // namespace model_checks
