// How well a skinned mesh keeps its shape in a pose: the volume change and the sharpest fold of
// the limb region around a posed joint, and the triangle pairs the pose makes intersect. Works
// on plain arrays (rest mesh, posed mesh, joints, weights), so it judges any skinning. No GL.
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

// A joint and the radius (metres) of the region measured around it.
struct JointRegion {
  int joint = -1;
  double radius = 0.0;
};

// Per face, the joint (bone) with the largest weight summed over its three vertices.
std::vector<int> dominant_bones(const Faces& faces, const Eigen::MatrixXf& weights);

// The region around `joint`, chosen in the rest pose: the faces whose centroid lies within
// `radius` of the rest joint and whose dominant bone is the joint itself, its parent or one of
// its children. In SMPL's convention a joint's weight moves the segment from the joint to its
// child, so for an elbow that is the upper arm, the forearm and the hand (the latter cut off by
// the radius): the skin that bends at this joint, without the neighbouring torso.
std::vector<int> joint_region(const Vertices& rest_vertices, const Faces& faces,
                              const std::vector<int>& face_bones, const std::vector<int>& parents,
                              const Vertices& rest_joints, const JointRegion& region);

// Signed volume of the cones from `apex` over the faces: sum of det(a-c, b-c, d-c) / 6. For a
// sleeve of skin around a joint with the apex at the joint it is the volume of the sleeve
// closed by two cones to the joint. It depends only on the faces relative to the apex, so a
// rigid motion of the region together with its joint leaves it unchanged, while a limb that
// collapses at the joint (or bulges) changes it. The sign follows the mesh's winding.
double cone_volume(const Vertices& vertices, const Faces& faces, const std::vector<int>& region,
                   const Eigen::Vector3d& apex);

// 100 (V_posed - V_rest) / |V_rest| of cone_volume with the apex at the rest and posed joint;
// NaN for an empty region or a vanishing rest volume.
double volume_change_percent(const Vertices& rest_vertices, const Vertices& posed_vertices,
                             const Faces& faces, const std::vector<int>& region,
                             const Eigen::Vector3d& rest_apex, const Eigen::Vector3d& posed_apex);

// The largest change, rest to posed, of the signed dihedral angle (between the normals of the
// two faces, signed by convex or concave along the edge) across the region's interior edges
// (edges shared by two region faces), in degrees 0..180. A crease that folds over reads near
// 180 even where the unsigned angle would look small. 0 for a region without interior edges.
struct Fold {
  double degrees = 0.0;
  int face_a = -1;  // the two faces of the sharpest fold (-1: none)
  int face_b = -1;
};
Fold sharpest_fold(const Vertices& rest_vertices, const Vertices& posed_vertices,
                   const Faces& faces, const std::vector<int>& region);

// Whether two triangles intersect (share at least one point), by the interval-overlap method
// of Moller (1997, "A fast triangle-triangle intersection test"), with the coplanar case
// tested in the plane. Degenerate (zero-area) triangles never intersect.
bool triangles_intersect(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                         const Eigen::Vector3d& p2, const Eigen::Vector3d& q0,
                         const Eigen::Vector3d& q1, const Eigen::Vector3d& q2);

// Every pair (f < g) of faces with no vertex in common that intersect, found through a uniform
// grid over the faces' bounding boxes (each pair is tested once, in the first cell both boxes
// share), so ~20k faces take well under a second.
std::vector<std::pair<int, int>> intersecting_face_pairs(const Vertices& vertices,
                                                         const Faces& faces);

// Pairs that intersect in the posed mesh but did not in the rest mesh; pairs whose two faces
// are both marked in `exempt_faces` (one entry per face, or empty for none) are counted apart
// (the fist's fingers touching the palm are contact, not a defect).
struct Intersections {
  int pairs = 0;
  int exempt_pairs = 0;
};
Intersections new_self_intersections(const Vertices& rest_vertices, const Vertices& posed_vertices,
                                     const Faces& faces,
                                     const std::vector<char>& exempt_faces = {});

// The three figures of one posed body.
struct PoseFigures {
  // The region with the largest |volume change| among the measured joints (NaN: no region).
  double volume_change_percent = std::numeric_limits<double>::quiet_NaN();
  // The sharpest fold over all measured joints' regions.
  double sharpest_fold_degrees = 0.0;
  Intersections intersections;
  int region_faces = 0;  // faces of all measured regions together
};

// The rest and posed mesh of one body; joints J x 3.
struct RestAndPosed {
  const Vertices& rest_vertices;
  const Vertices& posed_vertices;
  const Vertices& rest_joints;
  const Vertices& posed_joints;
  const Faces& faces;
};

// The figures at `regions` (each joint's region, its apex at that joint); faces dominated by an
// `exempt_bones` joint are exempt from the intersection count (see new_self_intersections).
PoseFigures measure_pose(const RestAndPosed& mesh, const Eigen::MatrixXf& weights,
                         const std::vector<int>& parents, const std::vector<JointRegion>& regions,
                         const std::vector<int>& exempt_bones = {});

}  // namespace body
