// Closed manifold triangle meshes from an implicit function: marching tetrahedra on a regular
// grid (Kuhn subdivision, vertices welded by grid edge), then remeshing towards a target edge
// length by edge collapse (with the link condition), valence-improving edge flips and
// tangential relaxation, every moved vertex projected back onto the surface.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace default_model {

struct TriMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;  // counter-clockwise seen from outside
};

using ScalarField = std::function<double(const Eigen::Vector3d&)>;

// Negative inside. `threads` evaluates the grid in parallel (results do not depend on it).
TriMesh marching_tetrahedra(const ScalarField& field, const Eigen::AlignedBox3d& box,
                            double spacing, int threads = 2);

struct RemeshOptions {
  std::function<double(const Eigen::Vector3d&)> target_edge;       // metres
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> project;  // onto the surface
  int relax_iterations = 6;
};

void remesh(TriMesh& mesh, const RemeshOptions& options);

// Keeps the connected component with the most faces and drops unused vertices.
void keep_largest_component(TriMesh& mesh);

// Signed volume (positive when the faces wind counter-clockwise seen from outside).
double signed_volume(const TriMesh& mesh);

// Each vertex's neighbours in the order the faces list them (each face gives its corners the
// next corner round it): on a closed manifold every edge appears once in each direction, so
// both ends list each other once.
std::vector<std::vector<int>> neighbours_by_face(std::size_t vertex_count,
                                                 const std::vector<std::array<int, 3>>& faces);

// Area-weighted vertex normals.
std::vector<Eigen::Vector3d> vertex_normals(const TriMesh& mesh);

}  // namespace default_model
