// Sequential plane search (Koyama et al., SIGGRAPH 2020): the public API the viewer and the
// simulate command use. Plain value type; submit() is blocking (tens of milliseconds) and the
// object is not thread-safe, so a UI runs it on a worker thread on a copy or under a lock.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sps/held_search.hpp"
#include "sps/perceptual_metric.hpp"
#include "sps/plane.hpp"
#include "sps/preference_data.hpp"
#include "sps/preference_model.hpp"
#include "sps/target_estimate.hpp"

namespace sps {

enum class Method {
  kSps,        // the paper's plane construction (x+, x_EI, v by plane-integral EI)
  kSpsRandom,  // c = x+, random orthogonal u, v of length 1 (paper's baseline)
  kSls,        // sequential line search: the segment x+ -> x_EI (plane with v = 0)
};

// What the axes of an SPS plane follow once the design in mind is estimated (a population and
// a perceptual scale): the paper's expected improvement of the goodness model, or where that
// estimate is least certain.
enum class PlaneAxes {
  kExpectedImprovement,  // u towards x_EI, v maximizing the plane's mean EI (the paper)
  kTargetUncertainty,    // u and v the two most uncertain directions of the estimate
};

enum class CurrentBest {
  kPosteriorMean,  // observed point with the largest posterior mean (paper's evaluation)
  kLastSelection,  // the user's last choice
};

struct SearchOptions {
  int dims = 10;
  std::uint64_t seed = 1;
  Method method = Method::kSps;
  CurrentBest current_best = CurrentBest::kPosteriorMean;
  int plane_restarts = 10;  // random restarts for v (paper: 10)
  int ei_restarts = 0;      // multi-start count for x_EI; 0 = automatic
  int threads = 2;          // restarts run in parallel
  // Points of the plane the choice is preferred over: 5 is the paper's c, c+-u, c+-v; 9 (the
  // default) adds the four edge midpoints, i.e. the coarsest 3x3 grid: more information per
  // plane for little cost (docs/benchmarks.md).
  int representatives = 9;
  ModelSettings model;  // priors and likelihood of the preference model
  // Empty, or how much each coordinate changes what the user sees per unit (e.g. RMS vertex
  // displacement in mm over the whole range). When set, the length-scale priors follow it
  // (see set_perceptual_scale) and SPS planes are kept usable for a person: a current best
  // near a bound becomes a corner of the plane instead of a fold, and v is not left much
  // shorter than u (in these units), using only coordinates with room on both sides.
  Eigen::VectorXd perceptual_scale;
  // Empty, or with a perceptual scale the full perceptual metric (sps/perceptual_metric.hpp;
  // its diagonal is the scale squared) for coordinates that are not seen independently: the
  // estimate of the design in mind and the uncertainty planes measure in it (the built-in body
  // models, whose components 1 and 2 are turned to carry stature and mass: mean gap at plane
  // 10 9.19 -> 6.69 mm with it, docs/benchmarks.md). The rest of the plane construction keeps
  // the scale.
  Eigen::MatrixXd perceptual_metric;
  // With a perceptual scale: the smallest length of u and of v in its units (the plane's
  // half-diagonals; RMS mm for a body model: 12 and 20 measured alike, 30 worse), so
  // that a plane always shows differences a person can see; and whether the length-scale
  // priors follow the scale.
  double min_plane_length = 12.0;
  // The length-scale prior of each direction is inversely proportional to how visible it is
  // (within a factor of 16 of the geometric mean), so the model expects the goodness to change
  // as fast along every direction per millimetre of visible change. Measured on the body
  // benchmark together with the two options below (docs/benchmarks.md); alone, with the
  // paper's centre and sharp likelihood, it pinned coordinates and did not help.
  bool perceptual_length_scales = true;
  // With a perceptual scale: the plane is centred on the maximum of the posterior mean (the
  // model's best estimate, which averages many noisy clicks) instead of the observed point
  // with the largest mean (a single click, which for a person is often a guess between cells
  // that look equally good).
  bool centre_on_mean_maximum = true;
  // With a perceptual scale: the BTL temperature used instead of model.btl_scale. A person
  // cannot rank bodies that differ by less than a few millimetres, so their clicks are noisy
  // and a soft likelihood (the data as weak evidence that many clicks average out) fits them;
  // the sharp 0.01 treats every click as certain and the model chases the noise.
  double perceptual_btl_scale = 1.0;
  // With a perceptual scale and centre_on_mean_maximum: where the designs of the space
  // typically lie (a body model's population; empty: unknown). When set, the plane is centred
  // on the estimate of the design the person has in mind (sps/target_estimate.hpp: an
  // ideal-point model of their choices with this prior) instead of the posterior-mean
  // maximum, which with a person's guesses between look-alike cells wanders along the
  // directions the clicks never resolved (body benchmark: mean gap at plane 10 down by about
  // 1.8 mm over 200 trials, docs/benchmarks.md).
  Population population;
  double choice_temperature_mm = 3.0;  // TargetModel::temperature_mm
  // TargetModel::region_slack_temperatures: what a choice's region says of where the design
  // in mind is, in the uncertainty planes' covariance; negative (the default, and files saved
  // before it): nothing. A design space asks for it with its UncertaintyPlaneSize.
  double choice_region_slack = -1.0;
  // With a population: kTargetUncertainty spans the planes along where the estimate of the
  // design in mind is least certain, each half-diagonal `uncertainty_extent` of its standard
  // deviations and at least `uncertainty_min_lengths` times min_plane_length long. For a person
  // who cannot tell near neighbours apart (the window's cells, the benchmark's pixel person)
  // this finds the body sooner than the paper's expected improvement, which assumes a precise
  // chooser. With the choices' regions (choice_region_slack) it serves a precise chooser best
  // too (body benchmark, perfect chooser: mean gap at plane 10 4.97 mm against 6.96); without
  // them such a chooser stalled on it (docs/benchmarks.md).
  // The smallest side is 2 lengths, not 3: with close-ups the smallest length is already
  // what 2 px show of the framed band, and 3 kept the later planes too coarse for where the
  // estimate had got to (pixel person at 230 px, 200 trials: mean gap at plane 10 down by
  // 0.66 mm; 1, 1.5 and 2.5 lengths were between the two; 400 px unchanged).
  PlaneAxes plane_axes = PlaneAxes::kExpectedImprovement;
  double uncertainty_extent = 5.0;
  double uncertainty_min_lengths = 2.0;
  // And at least this long (the perceptual scale's units; 0: no such bound): the side a
  // person needs to tell the cells of a plane's deepest zoom level apart, which the design
  // space derives from what its cells show that person (spaces::body_uncertainty_min_side).
  // min_plane_length alone is what a person sees at all; a person who sees only coarser
  // differences resolves a plane no finer than a few of their thresholds, and planes sized
  // for a finer eye leave their last clicks as guesses (body benchmark, the 5 mm person:
  // median gap at plane 15 5.06 -> 4.53 mm, docs/benchmarks.md).
  double uncertainty_min_side = 0.0;
};

// How large uncertainty planes are (SearchOptions::uncertainty_extent and
// uncertainty_min_lengths), as a design space asks for them.
struct UncertaintyPlaneSize {
  double extent = SearchOptions{}.uncertainty_extent;
  double min_lengths = SearchOptions{}.uncertainty_min_lengths;
  // SearchOptions::choice_region_slack: how far the estimate's covariance, which sizes and
  // turns these planes, trusts the regions of the choices.
  double region_slack = SearchOptions{}.choice_region_slack;
};

// The options' three uncertainty-plane values.
UncertaintyPlaneSize uncertainty_size(const SearchOptions& options);

// The one check of an uncertainty plane size, for the setter, the options and the command
// line: throws std::invalid_argument naming the first value outside its range (extent
// [0.1, 10], smallest length [0, 10] min_plane_lengths, region slack [-1, 1000]).
void validate_uncertainty_size(const UncertaintyPlaneSize& size);

// The half-diagonal (in [0, 1] units) of the first plane with a perceptual scale: the plane
// spans the two most visible directions over +-2.4 standard deviations for a body model.
constexpr double kVisibleFirstPlaneExtent = 0.4;

// The first plane with a perceptual scale (Design Galleries' idea of a first choice among
// the most different designs): centred at 0.5, u along the most visible coordinate and v along
// the second, each kVisibleFirstPlaneExtent long. A line along the first with one dimension.
Plane visible_first_plane(const Eigen::VectorXd& scale);

// The largest search space a session may have (the paper explores up to ~20 dimensions; more
// is not searchable by clicking and only costs memory).
constexpr int kMaxSearchDims = 64;

// Throws std::invalid_argument naming the first option outside its sane range (dims 1-64,
// positive finite hyperparameter priors, ...). Called before anything is allocated.
void validate_options(const SearchOptions& options);

const char* method_name(Method m);
const char* plane_axes_name(PlaneAxes a);
bool parse_plane_axes(const std::string& name, PlaneAxes& out);
bool parse_method(const std::string& name, Method& out);

class PlaneSearch {
 public:
  explicit PlaneSearch(const SearchOptions& options);

  const SearchOptions& options() const { return options_; }
  int dims() const { return options_.dims; }
  int iteration() const { return static_cast<int>(history_.size()); }

  // The plane (or, for SLS, the segment c -> c+u with v = 0) the user should search now.
  const Plane& current_plane() const { return plane_; }

  // The user's answer on the current plane: `chosen` is preferred over the plane's
  // representatives c, c+-u, c+-v. `extra_rejected` adds more points the user saw and passed
  // over (e.g. the other cells of each zoom level); each list in it is one extra comparison
  // "its preferred point > the rest", given as {preferred, rejected...}.
  // Recomputes the model and proposes the next plane. Points are clamped into [0,1]^n;
  // throws std::invalid_argument on a wrong size or non-finite entries.
  // `shown_representatives`, when given, replaces those points by what the user was shown for
  // them (e.g. each projected onto holds), in the order of representative_coordinates().
  // `set_directly`: the user set the point (sliders, typed targets), so the next plane is
  // centred on it (not on the best observed point or the posterior-mean maximum) and the user
  // sees the body they asked for as the current best.
  void submit(const Eigen::VectorXd& chosen,
              const std::vector<std::vector<Eigen::VectorXd>>& extra_comparisons = {},
              const std::vector<Eigen::VectorXd>& shown_representatives = {},
              bool set_directly = false);
  // Where submit() takes the plane's representatives, in Plane::point coordinates (s, t):
  // c, c+u, then for a plane c-u, c+v, c-v and (options().representatives >= 9) the edge
  // midpoints.
  std::vector<std::pair<double, double>> representative_coordinates() const;

  // Current best point (x+): the point the current plane was built around (its centre,
  // unless the plane was moved to fit the box: Plane::best).
  Eigen::VectorXd x_plus() const { return plane_.best(); }

  // Posterior of the goodness model at x (0 mean / prior variance before any data).
  double posterior_mean(const Eigen::VectorXd& x) const;
  double posterior_variance(const Eigen::VectorXd& x) const;
  double expected_improvement(const Eigen::VectorXd& x) const;

  // Discard all preference data and start from a fresh first plane (seed advances).
  void start_over();
  // Remove the last submission and return to the plane it answered; false if none.
  bool undo();

  // Whole state as JSON text; from_json(to_json()) reproduces every plane and every future
  // proposal exactly. from_json throws std::runtime_error with a readable message.
  std::string to_json() const;
  static PlaneSearch from_json(const std::string& json_text);

  // Sets options().perceptual_scale (empty: none) and perceptual_metric (empty: the scale
  // alone; ignored without a scale) for the next submissions. Throws std::invalid_argument on
  // a wrong size, a non-positive or non-finite scale entry, or a metric that
  // validate_metric_matrix refuses; nothing changes then.
  void set_perceptual_scale(const Eigen::VectorXd& scale,
                            const Eigen::MatrixXd& metric = Eigen::MatrixXd());
  // Before the first submission and with a perceptual scale: replaces the current plane by
  // visible_first_plane() and returns true (start_over() then starts from it too); otherwise
  // false and nothing changes.
  bool use_visible_first_plane();
  // Sets options().population (empty: none) for the next submissions. Throws
  // std::invalid_argument on wrong sizes, a mean outside [0, 1] or a non-positive SD.
  void set_population(const Population& population);
  // Sets options().min_plane_length (in the perceptual scale's units) for the next planes.
  // Throws std::invalid_argument outside [0, 10000].
  void set_min_plane_length(double length);
  // Sets options().uncertainty_min_side (in the perceptual scale's units) for the next planes.
  // Throws std::invalid_argument outside [0, 10000].
  void set_uncertainty_min_side(double length);
  // Sets options().choice_temperature_mm (how noisy the person's choices are, in the
  // perceptual scale's units) for the next planes. Throws std::invalid_argument outside
  // [1e-6, 10000].
  void set_choice_temperature(double mm);
  // Sets options().plane_axes for the next planes.
  void set_plane_axes(PlaneAxes axes) { options_.plane_axes = axes; }
  // Right after submit(): where its plane is an uncertainty plane (PlaneAxes::
  // kTargetUncertainty) that the person could not tell apart after all (the caller's measure
  // of what cells look like, e.g. a grid with no two cells visibly different), the paper's
  // plane for the same choice instead; returns whether the plane was replaced.
  bool replace_uncertainty_plane();
  // The last resort after that, for the window's planes (PlaneAxes::kTargetUncertainty with a
  // population): where the plane still cannot be told apart (the paper's plane, built where
  // the estimate had no uncertainty plane, can be one whose cells clamp onto the same faces
  // of the box), a plane through the same centre along the population's principal axes as a
  // person sees them, slid and shrunk into the box as uncertainty planes are (the first
  // plane's construction, moved to the centre). `axes_pair` picks other pairs of those axes
  // (sps::uncertainty_plane). Returns whether the plane was replaced.
  bool replace_with_population_plane(int axes_pair = 0);
  // The very last resort, where no plane above shows cells a person can tell apart (near the
  // box's faces cells clamp onto the same designs, and the caller's measure can see less than
  // the perceptual scale predicts, e.g. a photo's clipped highlights): the current plane's
  // part around (s, t), `half` wide (sps::plane_part), that the caller found its cells
  // distinct on. Returns whether the plane was replaced (not for lines, or where the part
  // does not hold the current best).
  bool replace_with_plane_part(double s, double t, double half);
  // Sets options().uncertainty_extent and uncertainty_min_lengths for the next planes. Throws
  // std::invalid_argument outside [0.1, 10] and [0, 10].
  void set_uncertainty_size(const UncertaintyPlaneSize& size);

  // Holds (sps/held_search.hpp): with a hold the planes are built on its surface (the centre
  // projected onto it; uncertainty planes along the estimate's uncertainty given the held
  // values, covariance_given_holds, else x_EI and v in its tangent space; the first plane
  // along its most visible tangent directions, from use_visible_first_plane() and
  // start_over() on); nullptr
  // releases it. The current plane stays until the next one is made. Not saved with the
  // state: the caller installs it again after from_json(). Without a hold nothing changes.
  void set_hold(std::shared_ptr<const SearchHold> hold);
  const SearchHold* hold() const { return hold_.get(); }

  // Seconds spent inside the last submit() (absorbing the choice and proposing the plane).
  double last_submit_seconds() const { return last_submit_seconds_; }

  const PreferenceData& data() const { return data_; }
  const PreferenceModel& model() const { return *model_; }

 private:
  // Everything needed to go back to the moment before a submission.
  struct Snapshot {
    Plane plane;
    int points = 0;
    int preferences = 0;
    KernelParams params;
    Eigen::VectorXd latent;
    std::string rng_state;
  };

  void propose_next_plane(const Eigen::VectorXd& last_choice, bool set_directly);
  // propose_next_plane's construction; returns the current best it built the plane around.
  Eigen::VectorXd build_next_plane(const Eigen::VectorXd& last_choice, bool set_directly);
  // The first plane for the current options and hold (visible_first_plane or
  // held_first_plane), or false when there is no perceptual scale.
  bool visible_start(Plane& plane) const;
  // The plane through c along the population's principal axes as a person sees them (sized
  // like the uncertainty planes), for the window's planes (SPS, PlaneAxes::kTargetUncertainty,
  // a population and a perceptual scale, no hold); nullopt otherwise or where no plane of
  // told-apart cells fits.
  std::optional<Plane> population_plane(const Eigen::VectorXd& c, int axes_pair = 0) const;
  std::string rng_state() const;
  void set_rng_state(const std::string& state);

  SearchOptions options_;
  std::mt19937_64 rng_;
  PreferenceData data_;
  std::shared_ptr<const PreferenceModel> model_;  // immutable; shared by copies
  Plane plane_;
  std::vector<Snapshot> history_;           // one per submission, oldest first
  std::shared_ptr<const SearchHold> hold_;  // shared by copies; const and thread-safe
  int start_overs_ = 0;
  double last_submit_seconds_ = 0.0;
  // The last submission's choice and whether it was set directly, and whether its plane is an
  // uncertainty plane (replace_uncertainty_plane; not saved: only right after submit()).
  Eigen::VectorXd last_choice_;
  bool last_set_directly_ = false;
  bool uncertainty_plane_ = false;
  // model.btl_scale as given, restored when the perceptual scale is removed.
  double plain_btl_scale_ = 0.01;
  // options_'s perceptual scale with its full metric where there is one, factored once
  // (set_perceptual_scale); empty without a scale.
  std::optional<PerceptualMetric> metric_;
};

}  // namespace sps
