#include "spaces/body_framing.hpp"

namespace spaces {

FramedBodies::FramedBodies(const body::Model& model, BodyFraming framing)
    : framing_(framing), distance_(model), bands_(model) {}

FramedBodies::View FramedBodies::view(const std::vector<Eigen::VectorXd>& xs) const {
  const auto whole = [](double tallest_m) {
    return View{{app::cell_frame_scale(tallest_m), 0.0}, {}};
  };
  if (framing_ == BodyFraming::kWholeBody || xs.size() < 2) {
    return whole(bands_.heights().tallest_m(xs));
  }
  body::FramedBand framed = bands_.frame(xs);
  const View all = whole(framed.tallest_m);
  const app::GridFrame frame = app::cell_frame_for_band(framed.band.bottom_m, framed.band.top_m);
  // A band that needs (nearly) the whole body's frame is shown as the whole body.
  if (frame.scale >= 0.95 * all.frame.scale) return all;
  return {frame, std::move(framed.vertices)};
}

double typical_frame_scale(BodyFraming framing) {
  return framing == BodyFraming::kCloseUps ? kCloseUpScale : 1.0;
}

app::GridFrame FramedBodies::grid_frame(const std::vector<Eigen::VectorXd>& xs) const {
  return view(xs).frame;
}

Eigen::MatrixXd FramedBodies::seen_pairwise_mm(const std::vector<Eigen::VectorXd>& xs) const {
  const View v = view(xs);
  const Eigen::MatrixXd mm = v.vertices.empty() ? distance_.pairwise_max_mm(xs)
                                                : distance_.pairwise_max_mm(xs, v.vertices);
  return mm / v.frame.scale;
}

std::vector<double> FramedBodies::seen_to_betas_mm(const std::vector<Eigen::VectorXd>& xs,
                                                   const Eigen::VectorXf& target_betas) const {
  const View v = view(xs);
  std::vector<double> mm = v.vertices.empty()
                               ? distance_.max_to_betas_mm(xs, target_betas)
                               : distance_.max_to_betas_mm(xs, target_betas, v.vertices);
  for (double& d : mm) d /= v.frame.scale;
  return mm;
}

app::PairwiseDistance seen_body_distance(std::shared_ptr<const FramedBodies> bodies) {
  return [bodies = std::move(bodies)](const std::vector<Eigen::VectorXd>& xs) {
    return bodies->seen_pairwise_mm(xs);
  };
}

}  // namespace spaces
