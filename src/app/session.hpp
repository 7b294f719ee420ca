// The whole state of one design session as plain data: which model, the settings, the plane
// search (all preference data), the cells clicked on the current plane, the history of chosen
// bodies, and the point the user started from. Every change is a method; nothing here knows
// about GL, ImGui or threads. Serializes to JSON (see session_store.hpp for files).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/cell_visibility.hpp"
#include "app/constraint_projector.hpp"
#include "sps/plane_search.hpp"
#include "sps/zoom_grid.hpp"

namespace app {

struct SessionSettings {
  std::string space;       // the design space's kind (app/space_catalogue.hpp); empty: the default
  std::string model_path;  // the space's source file; empty = its built-in default
  int components = 10;     // search dimensions (a body's shape components)
  int grid_size = 3;       // 3 or 5
  int zoom_levels = 4;     // clicks per plane
  std::uint64_t seed = 1;
};

// One finished plane: the body chosen on it and how the user got there.
struct HistoryEntry {
  Eigen::VectorXd chosen;           // x_chosen, in [0,1]^n
  std::vector<sps::GridCell> path;  // the clicks on that plane
  // Chosen with the expert sliders ("Use this"): `path` holds the clicks made on the plane
  // before, all of which undo gives back (a finished plane's last click is what finished it).
  bool set_by_sliders = false;
};

// What a click did.
enum class ClickResult {
  kIgnored,        // out of range, or a submission is pending
  kZoomed,         // one level deeper on the same plane
  kPlaneFinished,  // the last zoom level: call submission() and then finish_plane()
};

// How different the bodies of some search points look: entry (i, j) is the largest vertex
// distance in millimetres between the bodies of xs[i] and xs[j] (symmetric, zero diagonal).
// The body space supplies it (body::ShapeDistance::pairwise_max_mm); the session uses it to
// never show a grid with look-alike cells.
using PairwiseDistance = std::function<Eigen::MatrixXd(const std::vector<Eigen::VectorXd>&)>;

// Cells closer than this (largest vertex distance) are look-alikes: no grid may hold two.
constexpr double kCloneMm = 5.0;

// The paper's zoom: each level halves the grid's spacing. Used without a distance hook.
constexpr double kPaperZoomFactor = 0.5;

// How a zoom level adapts when the distance hook is set.
struct ZoomPolicy {
  // Neighbouring cells of a grid must differ by at least this much (mm, largest vertex
  // distance) for the grid to be shown; below it the session zooms by less, and when even the
  // smallest zoom step would show look-alikes the plane ends early (the click is the choice).
  double distinct_mm = 10.0;
  // Zoom steps tried in order (new spacing / old spacing). Gentler than the paper's factor 2
  // (kPaperZoomFactor): a person cannot tell apart bodies within a few millimetres of each
  // other's distance to the one in mind, so after two halvings the cells of the third and
  // fourth levels all look equally good and those clicks are guesses, both as the choice and
  // as preference data. Shrinking by 0.7 keeps every level's cells far enough apart for the
  // click to say something: on the body benchmark (200 trials) the mean gap at plane 10 was
  // 0.7 mm lower than with 0.5 (docs/benchmarks.md).
  std::vector<double> factors{0.7, 0.8};
  // A click on a zoom level counts as "better than" only the cells of that grid that differ
  // from the clicked one by at least this much (mm, largest vertex distance): between near
  // neighbours a person's pick is mostly a guess, and taken as a preference it misleads the
  // model (body benchmark, docs/benchmarks.md). 0 counts every cell.
  double compare_mm = 40.0;
  // No grid shown may hold two cells closer than this (mm, largest vertex distance): a first
  // grid that would is widened where the box has room, and with holds a projected grid is
  // checked too. The window and the benchmark's pixel person set it to what the cells show.
  double look_alike_mm = kCloneMm;
};

// The zoom policy for cells of `cell_px` pixels and a person who resolves `jnd_px`
// (app/cell_visibility.hpp): grids whose cells differ by less than what that shows (never
// below kCloneMm) are neither zoomed into nor, where widening helps, shown as first grids.
ZoomPolicy zoom_policy_for_cells(double cell_px, double jnd_px = kDefaultJndPx);

// The submission a finished plane produces for sps::PlaneSearch::submit().
struct Submission {
  Eigen::VectorXd chosen;
  std::vector<std::vector<Eigen::VectorXd>> extra_comparisons;
  // With holds: the plane's representatives as shown (projected), for submit()'s third
  // argument; empty: the optimizer's own plane was shown.
  std::vector<Eigen::VectorXd> representatives;
  // A point the user set directly (sliders, typed targets): the next plane is centred on it
  // (sps::PlaneSearch::submit).
  bool set_directly = false;
};

// Holds: the next plane's held version and its first grid, made off the window thread (the
// optimizer's worker, app/worker.hpp) because projecting onto girths slices a mesh per cell
// (a new plane took 150-210 ms on the window thread). Session::finish_plane() installs it
// when it belongs to the plane the optimizer returned.
struct PreparedPlane {
  sps::Plane plane;                                  // the optimizer's plane it was made from
  std::shared_ptr<const ConstraintProjector> holds;  // the holds it was made with
  std::shared_ptr<const sps::HeldPlane> held;        // sps::hold_plane(*holds, plane)
  std::vector<sps::GridPoint> first_cells;           // the held cells of the plane's first view
};
// Makes the PreparedPlane of a search's current plane; thread-safe.
using PlanePreparer = std::function<PreparedPlane(const sps::PlaneSearch&)>;
// Checks a search's new plane right after submit() and may have it replaced
// (sps::PlaneSearch::replace_uncertainty_plane); thread-safe.
using PlaneVetter = std::function<void(sps::PlaneSearch&)>;

class Session {
 public:
  explicit Session(const SessionSettings& settings);
  // The same with the optimizer's options (method, threads, model settings) given; dims and
  // seed come from `settings`. For benchmarks and tests.
  Session(const SessionSettings& settings, sps::SearchOptions search_options);

  // Installs (or, with an empty function, removes) the perceptual distance between cells.
  // Recomputes the zoom levels of the current plane. Not saved with the session.
  void set_perceptual_distance(PairwiseDistance distance, ZoomPolicy policy = {});
  // A new policy for the zoom levels still to come (the window's cells changed size): the
  // grid on screen stays as it is.
  void set_zoom_policy(const ZoomPolicy& policy) { policy_ = policy; }
  const ZoomPolicy& zoom_policy() const { return policy_; }
  bool has_perceptual_distance() const { return static_cast<bool>(distance_); }
  const PairwiseDistance& perceptual_distance() const { return distance_; }
  // How much each search coordinate changes the body over its range (mm, e.g.
  // body::ShapeDistance::direction_rms_mm()); the optimizer scales its length scales and
  // shapes its planes with it from the next plane on (saved with the search). Empty: none.
  // Before the first click of a new session it also starts from the plane of the two most
  // visible directions (sps::visible_first_plane). `metric`: empty, or the full perceptual
  // metric (sps::SearchOptions::perceptual_metric, mm^2), saved with the search too.
  void set_perceptual_scale(const Eigen::VectorXd& mm_per_unit,
                            const Eigen::MatrixXd& metric = Eigen::MatrixXd());
  // Where the space's designs typically lie (e.g. SpacePerception::population()); with a
  // perceptual scale the planes are then centred on the estimate of the design the person has
  // in mind (sps::SearchOptions::population), from the next plane on (saved with the search).
  // Before the first click a population whose coordinates change together also gives the
  // first plane (sps::PlaneSearch::use_visible_first_plane), as does set_plane_axes.
  void set_population(const sps::Population& population);
  // The smallest length of a plane's sides in the perceptual scale's units
  // (sps::SearchOptions::min_plane_length), from the next plane on (saved with the search).
  void set_min_plane_length(double length) { search_.set_min_plane_length(length); }
  // The smallest side of uncertainty planes a person needs at the cells' size
  // (sps::SearchOptions::uncertainty_min_side), from the next plane on (saved with the search).
  void set_uncertainty_min_side(double length) { search_.set_uncertainty_min_side(length); }
  // How noisy the person's choices are for the estimate of the design in mind
  // (sps::SearchOptions::choice_temperature_mm), from the next plane on (saved with the search
  // when it has a population, the only case it is used in).
  void set_choice_temperature(double mm) { search_.set_choice_temperature(mm); }
  // The axes of the next planes (sps::SearchOptions::plane_axes; saved with the search).
  void set_plane_axes(sps::PlaneAxes axes);
  // How large uncertainty planes are: standard deviations along each axis and at least how
  // many smallest plane lengths (sps::SearchOptions::uncertainty_extent and
  // uncertainty_min_lengths; saved with the search).
  void set_uncertainty_size(const sps::UncertaintyPlaneSize& size);

  // Holds (app/constraint_projector.hpp): with a projector every plane shown is the
  // held plane and every cell (and so every point the optimizer learns from) is projected
  // onto the holds. nullptr releases them; the preference data stay. The projector's
  // held_values() are saved with the session; a session read from a file has them in
  // saved_holds() until the window installs a projector again (the projector itself is the
  // design space's, so it is not made here).
  void set_constraint_projector(std::shared_ptr<const ConstraintProjector> projector);
  const std::vector<HeldValue>& saved_holds() const { return saved_holds_; }
  const ConstraintProjector* constraint_projector() const { return projector_.get(); }
  // The plane the cells lie on: the held plane with holds, else the optimizer's.
  const sps::Plane& shown_plane() const { return held_ ? held_->plane : search_.current_plane(); }

  const SessionSettings& settings() const { return settings_; }
  const sps::PlaneSearch& search() const { return search_; }
  const std::vector<sps::GridCell>& path() const { return path_; }
  const std::vector<HistoryEntry>& history() const { return history_; }
  int planes_done() const { return static_cast<int>(history_.size()); }
  int clicks_on_plane() const { return static_cast<int>(path_.size()); }

  // The grid the user sees now (after the clicks so far on this plane). The window draws
  // sps::grid_points(plane, n, view()), which equals cells() for every plane (for a line, SLS,
  // cells() lays n*n points along the segment instead).
  sps::GridView view() const { return views_.back(); }
  std::vector<sps::GridPoint> cells() const { return cells_at(views_.back()); }
  // The view of each zoom level so far: views()[0] is the whole plane (wider when the plane
  // would show look-alikes and the box has room), views()[k] the grid after k clicks.
  const std::vector<sps::GridView>& views() const { return views_; }
  std::vector<sps::GridPoint> cells_at(const sps::GridView& view) const;

  // True when the plane ended before its last zoom level because a further zoom would have
  // shown look-alike cells: "no visible change left in this direction".
  bool ended_early() const { return ended_early_; }
  // The same in plain words for the window, or "" when the plane did not end early.
  std::string plane_note() const;
  // Plain words for a cell at the edge of the search range (some shape coordinate at its
  // limit, +-3 standard deviations for a body model), or "".
  static std::string cell_note(const sps::GridPoint& cell);

  // Clicking cell (col,row) of the current grid.
  ClickResult click(const sps::GridCell& cell);
  // True once the last zoom level was clicked and the plane waits for the optimizer.
  bool submission_pending() const {
    return static_cast<int>(path_.size()) >= settings_.zoom_levels || ended_early_;
  }
  // The choice and the intermediate levels as extra comparisons {clicked, other cells...}.
  Submission submission() const;
  // The clicks made so far on this plane's zoom levels, each as {clicked, other cells...}:
  // what submission() passes on, also when the plane is left unfinished (the expert sliders'
  // "Use this"), so no click the user made is lost.
  std::vector<std::vector<Eigen::VectorXd>> level_comparisons() const;
  // Installs the search state computed from submission() (on a worker) and starts the next plane.
  // `prepared` (from plane_preparer(), on the same worker) saves the window thread the holds'
  // projections; it is ignored when it belongs to another plane.
  void finish_plane(sps::PlaneSearch updated_search, std::optional<PreparedPlane> prepared = {});
  // With holds, what a worker runs after the optimizer to prepare the next plane (it holds
  // the projector and the grid size, not the session); empty without holds.
  PlanePreparer plane_preparer() const;
  // For the optimizer's worker, right after submit(): an uncertainty plane whose first grid
  // cannot show nine cells that look different (however it is widened or narrowed, as
  // update_views() tries) is replaced by the paper's plane. Empty with holds or without a
  // perceptual distance.
  PlaneVetter plane_vetter() const;
  // Installs the search state computed from a point the user set directly (expert sliders,
  // submitted as preferred over the previous best): it ends the current plane as if chosen
  // there, with no clicks in its history entry.
  void adopt_point(const Eigen::VectorXd& chosen, sps::PlaneSearch updated_search,
                   std::optional<PreparedPlane> prepared = {});

  // Undo the last click; with no click on this plane, reopens the previous plane with its
  // clicks minus the last one. False if there is nothing to undo.
  bool undo_click();
  // Undo the whole last finished plane (or the clicks on the current one if any).
  bool undo_plane();
  // Discards all preference data and history; keeps the settings (the seed advances).
  void start_over();

  // The body to show as the current best: the last click on this plane if any, else x+.
  Eigen::VectorXd current_best() const;
  // The body the user started from (the centre of the first plane).
  const Eigen::VectorXd& start_point() const { return start_point_; }

  // Redo: the states Undo and Start over took back, newest last, each a whole session
  // without a redo stack of its own. Kept with the session (and in its file), so that Redo
  // still brings them back after the window was closed and the session resumed.
  int redo_depth() const { return static_cast<int>(redo_.size()); }
  // `before` is this session as it was before the change that made it what it is now; its
  // own redo stack is dropped. `by_undo`: this session's search is `before`'s with
  // submissions undone (Undo), which lets the file store a count instead of a second copy
  // of a long search. Keeps at most kMaxRedo states (the oldest go).
  void push_redo(Session before, bool by_undo);
  // The newest state taken back, carrying the rest of the stack, with this session's
  // perceptual distance and holds where it has none (a state read from a file has neither:
  // they are not saved); nullopt when there is none.
  std::optional<Session> pop_redo();
  void clear_redo() { redo_.clear(); }
  static constexpr int kMaxRedo = 64;
  // Why the redo part of the file this session was read from could not be used ("redo[2]
  // history_kept: ..."), or "". The session itself is then loaded without a redo stack.
  const std::string& redo_problem() const { return redo_problem_; }

  std::string to_json() const;
  // Throws std::runtime_error with a readable message on anything malformed.
  static Session from_json(const std::string& text);

 private:
  // Before the first click: the first plane again, from what the search knows now.
  void retake_first_plane();
  // Recomputes views_ and ended_early_ from the plane, the path and the distance hook.
  void update_views();
  sps::GridView next_view(const sps::GridView& view, const sps::GridCell& clicked, bool check,
                          bool& distinct) const;
  // On decision_cells(view), or with `projected` on the cells as shown.
  bool shows_look_alikes(const sps::GridView& view, double threshold_mm,
                         bool projected = false) const;
  // The cells the zoom decisions look at: the grid as shown where it was projected already,
  // else (holds) the held plane's own points, first-order held. A zoom click tries up to four
  // grids and projecting one onto a girth slices a mesh per cell (~4 ms each, on the window's
  // thread); a projection moves a cell only by what brings its held measurements back within
  // tolerance, little against the 10 mm neighbours must differ by.
  std::vector<sps::GridPoint> decision_cells(const sps::GridView& view) const;

  SessionSettings settings_;
  sps::PlaneSearch search_;
  std::vector<sps::GridCell> path_;
  std::vector<HistoryEntry> history_;
  Eigen::VectorXd start_point_;
  PairwiseDistance distance_;
  ZoomPolicy policy_;
  std::vector<sps::GridView> views_;  // path_.size() + 1 entries
  bool ended_early_ = false;
  // Holds: the projector, the current plane held (made in update_views) and the projected
  // cells of the views asked for so far on this plane.
  std::shared_ptr<const ConstraintProjector> projector_;
  std::shared_ptr<const sps::HeldPlane> held_;
  // With holds, the current best on the held surface (the held plane's centre, or its point
  // where the plane's current best lies off the centre, moved onto the holds); set with held_.
  Eigen::VectorXd held_best_;
  mutable std::vector<std::pair<sps::GridView, std::vector<sps::GridPoint>>> held_cells_;
  std::vector<HeldValue> saved_holds_;     // what to_json() writes as "holds"
  std::optional<PreparedPlane> prepared_;  // for the next update_views(), if it matches
  // The redo stack, oldest first. The states are shared, never changed, so a copy of the
  // session (autosave hands one to its thread) does not copy them.
  struct RedoEntry {
    std::shared_ptr<const Session> state;
    // The next newer state's search (the next entry's, or this session's for the newest) is
    // this one's with submissions undone.
    bool next_by_undo = false;
  };
  std::vector<RedoEntry> redo_;
  std::string redo_problem_;
  friend struct SessionJson;
};

}  // namespace app
