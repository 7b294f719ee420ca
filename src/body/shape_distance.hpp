// How different two bodies of one model look, in millimetres: the search compares cells with
// it (never show two look-alike cells) and the body benchmark scores choices with it. Bodies
// are linear in the betas, so a difference of two search points is one product with the
// shape directions; the template cancels. Distances are between raw model vertices (no
// placement on the ground), i.e. shape only.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"

namespace body {

class ShapeDistance {
 public:
  // Uses the model's kept components; search points have that many entries (x in [0,1],
  // beta = 6x - 3). Throws std::invalid_argument for a model without vertices.
  explicit ShapeDistance(const Model& model);

  int dims() const { return static_cast<int>(unit_dirs_mm_.cols()); }
  int vertex_count() const { return static_cast<int>(unit_dirs_mm_.rows() / 3); }

  // Vertex displacement (3V, mm) of search point x relative to search point `origin`.
  Eigen::VectorXf displacement_mm(const Eigen::VectorXd& x, const Eigen::VectorXd& origin) const;

  // Root-mean-square and largest vertex distance between the bodies of two search points.
  double rms_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double max_mm(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

  // RMS distance of each body to the body with the given betas (a target outside the box is
  // allowed).
  std::vector<double> rms_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                      const Eigen::VectorXf& target_betas) const;
  // Largest vertex distance of each body to that body: how far it visibly is from it (the
  // measure the window's look-alike test uses between cells).
  std::vector<double> max_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                      const Eigen::VectorXf& target_betas) const;

  // Largest vertex distance between every pair of bodies (symmetric, zero diagonal).
  Eigen::MatrixXd pairwise_max_mm(const std::vector<Eigen::VectorXd>& xs) const;

  // The same two over the given vertices only (what a cell framed on part of the body shows;
  // indices below vertex_count(), none: 0 everywhere).
  std::vector<double> max_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                      const Eigen::VectorXf& target_betas,
                                      const std::vector<int>& vertices) const;
  Eigen::MatrixXd pairwise_max_mm(const std::vector<Eigen::VectorXd>& xs,
                                  const std::vector<int>& vertices) const;

  // How much each search coordinate changes the body over its whole range [0, 1]: RMS vertex
  // displacement in mm (the perceptual scale of each direction).
  Eigen::VectorXd direction_rms_mm() const;
  // The RMS vertex distance between two bodies as a quadratic form of their search
  // coordinates: rms(x - y)^2 = (x - y)^T G (x - y), mm^2 (sps::PerceptualMetric). Its
  // diagonal is direction_rms_mm() squared; off the diagonal, how much two directions move the
  // same vertices the same way (none for components that are orthogonal in vertex space).
  Eigen::MatrixXd direction_gram_mm2() const;

 private:
  // `distance` of each body to the body with the given betas.
  std::vector<double> to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                  const Eigen::VectorXf& target_betas,
                                  double (ShapeDistance::*distance)(const Eigen::VectorXd&,
                                                                    const Eigen::VectorXd&)
                                      const) const;
  // 3V x n: each body's vertices less the first body's (mm).
  Eigen::MatrixXf displacements_from_first(const std::vector<Eigen::VectorXd>& xs) const;
  Eigen::MatrixXf unit_dirs_mm_;  // 3V x K: d vertices / d x, mm (6000 * shapedirs)
};

// Norms of the V vertices of a 3V displacement.
Eigen::VectorXf vertex_norms(const Eigen::VectorXf& displacement);

}  // namespace body
