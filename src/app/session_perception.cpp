#include "app/session_perception.hpp"

#include "sps/perceptual_metric.hpp"

namespace app {

Eigen::MatrixXd usable_metric(const SpacePerception& perception, const Eigen::VectorXd& scale) {
  const Eigen::MatrixXd metric = perception.perceptual_metric();
  if (metric.size() == 0 || sps::metric_matrix_problem(metric, scale.size())) return {};
  const Eigen::ArrayXd ratio = metric.diagonal().array() / scale.array().square();
  if ((ratio - 1.0).abs().maxCoeff() > 1e-3) return {};
  return metric;
}

namespace {

bool has_scale(const Session& session) {
  return session.search().options().perceptual_scale.size() > 0;
}

void set_cell_dependent(Session& session, const SpacePerception& perception, int cell_px) {
  if (const double length = perception.min_plane_length(cell_px); length > 0.0) {
    session.set_min_plane_length(length);
  }
  if (const double t = perception.choice_temperature(cell_px); t > 0.0) {
    session.set_choice_temperature(t);
  }
  if (const double side = perception.uncertainty_min_side(cell_px); side > 0.0) {
    session.set_uncertainty_min_side(side);
  }
}

}  // namespace

void install_perception(Session& session, const SpacePerception& perception, int cell_px,
                        bool perceptual_zoom) {
  if (!has_scale(session)) {
    const Eigen::VectorXd scale = perception.perceptual_scale();
    if (scale.size() == session.settings().components && scale.allFinite() &&
        (scale.array() > 0.0).all()) {
      session.set_perceptual_scale(scale, usable_metric(perception, scale));
      set_cell_dependent(session, perception, cell_px);
      session.set_uncertainty_size(perception.uncertainty_size());
      session.set_plane_axes(perception.plane_axes());
    }
  }
  // Sessions saved before the full metric see the coordinates independently; their later
  // estimates and planes measure in it too (it only reads the saved choices and scale).
  if (const sps::SearchOptions& saved = session.search().options();
      saved.perceptual_scale.size() > 0 && saved.perceptual_metric.size() == 0) {
    const Eigen::MatrixXd metric = usable_metric(perception, saved.perceptual_scale);
    if (metric.size() > 0) session.set_perceptual_scale(saved.perceptual_scale, metric);
  }
  // Sessions saved before the target estimate existed have a scale but no population: their
  // later planes are centred on the estimate too (it only reads the saved choices).
  if (const sps::SearchOptions& search = session.search().options();
      search.perceptual_scale.size() > 0 && search.population.empty()) {
    const sps::Population population = perception.population();
    if (population.mean.size() == search.dims) session.set_population(population);
  }
  if (perceptual_zoom) {
    session.set_perceptual_distance(perception.perceptual_distance(),
                                    perception.zoom_policy(cell_px));
  }
}

void follow_cell_size(Session& session, const SpacePerception& perception, int cell_px) {
  session.set_zoom_policy(perception.zoom_policy(cell_px));
  if (has_scale(session)) set_cell_dependent(session, perception, cell_px);
}

}  // namespace app
