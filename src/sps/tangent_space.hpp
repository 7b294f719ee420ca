// The directions a search plane may take through its centre. A free search may move every
// coordinate; a held one (sps/held_search.hpp) only along the tangent space of the held
// surface there. The plane construction and the maximizations of EI and of the posterior
// mean are written once, for a tangent space; a free search passes the whole space, which is
// applied exactly (no matrix products), so it computes what it would without this layer.
#pragma once

#include <Eigen/Core>

namespace sps {

// The orthogonal projector onto the directions that keep every held quantity to first order:
// I - N^T (N N^T)^+ N (a pseudo-inverse, so dependent normals do no harm). n x n; the
// identity for no normals.
Eigen::MatrixXd tangent_projector(const Eigen::MatrixXd& normals, Eigen::Index dims);

// The k (1 or 2) most visible directions of the tangent space: the leading eigenvectors of
// P S^2 P (S = diag(scale)), each of Euclidean length 1, ordered by visibility.
Eigen::MatrixXd most_visible_tangent_directions(const Eigen::MatrixXd& projector,
                                                const Eigen::VectorXd& scale, int k);

class TangentSpace {
 public:
  // Every direction (a free search).
  TangentSpace() = default;
  // The directions orthogonal to the rows of `normals` (dims columns); every direction when
  // there are none.
  TangentSpace(const Eigen::MatrixXd& normals, Eigen::Index dims);

  // Whether every direction is allowed (then every call below returns its argument).
  bool whole() const { return normal_projector_.size() == 0 && mask_.size() == 0; }

  // The component of d in the space: P d, computed as d less its normal part, so that it is
  // d itself, to the last bit, where the normals do not reach.
  Eigen::VectorXd project(const Eigen::VectorXd& d) const;
  // The point of the affine plane through `origin` nearest to y: origin + P (y - origin),
  // computed as y less the normal part of y - origin (y itself on that plane).
  Eigen::VectorXd through(const Eigen::VectorXd& origin, const Eigen::VectorXd& y) const;

  // P as a dims x dims matrix (the identity for the whole space).
  Eigen::MatrixXd projector(Eigen::Index dims) const;

  // The directions of this space that also leave every coordinate k with keep(k) == 0
  // unchanged (keep holds 0 or 1 per coordinate): for the whole space a mask of coordinates,
  // applied as a product.
  TangentSpace without_coordinates(const Eigen::VectorXd& keep) const;

 private:
  Eigen::MatrixXd normals_;  // the held normals (none: no hold)
  // I - P: the projector onto the held normals and the coordinates taken out; empty without
  // held normals (then mask_ alone says which coordinates are taken out).
  Eigen::MatrixXd normal_projector_;
  Eigen::VectorXd mask_;  // 1 for a coordinate kept, 0 for one taken out (empty: all kept)
};

}  // namespace sps
