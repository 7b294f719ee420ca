#include "app/session.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "sps/json_fields.hpp"
#include "sps/parallel_for.hpp"

namespace app {

namespace {

using nlohmann::json;

// A stored integer, checked before use (sps/json_fields.hpp).
long long integer_from(const json& j, const std::string& what, long long lo, long long hi) {
  return sps::json_fields::integer(j, what, lo, hi);
}

json vector_json(const Eigen::VectorXd& x) {
  json a = json::array();
  for (Eigen::Index i = 0; i < x.size(); ++i) a.push_back(x[i]);
  return a;
}

Eigen::VectorXd vector_from(const json& a, int dims, const char* what) {
  if (!a.is_array() || static_cast<int>(a.size()) != dims) {
    throw std::runtime_error(std::string(what) + " must be an array of " + std::to_string(dims) +
                             " numbers");
  }
  Eigen::VectorXd x(dims);
  for (int i = 0; i < dims; ++i) {
    const json& e = a.at(static_cast<size_t>(i));
    if (!e.is_number()) throw std::runtime_error(std::string(what) + " holds a non-number");
    const double v = e.get<double>();
    if (!(v >= 0.0 && v <= 1.0)) {
      throw std::runtime_error(std::string(what) + " has an entry outside [0,1]");
    }
    x[i] = v;
  }
  return x;
}

json path_json(const std::vector<sps::GridCell>& path) {
  json a = json::array();
  for (const auto& c : path) a.push_back(json::array({c.col, c.row}));
  return a;
}

std::vector<sps::GridCell> path_from(const json& a, int n, const char* what) {
  if (!a.is_array()) throw std::runtime_error(std::string(what) + " must be an array");
  if (a.size() > 8) throw std::runtime_error(std::string(what) + " has more than 8 clicks");
  std::vector<sps::GridCell> path;
  for (const auto& c : a) {
    if (!c.is_array() || c.size() != 2) {
      throw std::runtime_error(std::string(what) + " entries must be [col, row]");
    }
    sps::GridCell cell{
        static_cast<int>(integer_from(c[0], std::string(what) + " column", 0, n - 1)),
        static_cast<int>(integer_from(c[1], std::string(what) + " row", 0, n - 1))};
    if (cell.col < 0 || cell.col >= n || cell.row < 0 || cell.row >= n) {
      throw std::runtime_error(std::string(what) + " has a cell outside the grid");
    }
    path.push_back(cell);
  }
  return path;
}

json history_json(const std::vector<HistoryEntry>& history) {
  json a = json::array();
  for (const auto& h : history) {
    json entry{{"chosen", vector_json(h.chosen)}, {"path", path_json(h.path)}};
    if (h.set_by_sliders) entry["set_by_sliders"] = true;
    a.push_back(std::move(entry));
  }
  return a;
}

std::vector<HistoryEntry> history_from(const json& history, const SessionSettings& settings) {
  if (!history.is_array()) throw std::runtime_error("history must be an array");
  std::vector<HistoryEntry> entries;
  for (const auto& h : history) {
    HistoryEntry entry;
    entry.chosen = vector_from(h.at("chosen"), settings.components, "history chosen");
    entry.path = path_from(h.at("path"), settings.grid_size, "history path");
    if (h.contains("set_by_sliders")) {
      if (!h.at("set_by_sliders").is_boolean()) {
        throw std::runtime_error("history set_by_sliders must be true or false");
      }
      entry.set_by_sliders = h.at("set_by_sliders").get<bool>();
    }
    // Undo reopens a finished plane with its clicks minus the last: each finished plane has
    // one click per zoom level, fewer when it ended early (no visible change left), or those
    // made before the point was set with the expert sliders (adopt_point).
    if (static_cast<int>(entry.path.size()) > settings.zoom_levels) {
      throw std::runtime_error("history path has " + std::to_string(entry.path.size()) +
                               " clicks, expected at most " + std::to_string(settings.zoom_levels));
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

bool same_entry(const HistoryEntry& a, const HistoryEntry& b) {
  return a.chosen.size() == b.chosen.size() && a.chosen == b.chosen && a.path == b.path &&
         a.set_by_sliders == b.set_by_sliders;
}

// `a` is the first a.size() entries of `b`.
bool is_prefix(const std::vector<HistoryEntry>& a, const std::vector<HistoryEntry>& b) {
  if (a.size() > b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same_entry(a[i], b[i])) return false;
  }
  return true;
}

}  // namespace

// Reading and writing the redo stack needs the session's insides; nlohmann's types stay out
// of the header.
struct SessionJson {
  // The redo stack, oldest first. A state whose search is the previous one's with
  // submissions undone (the usual case: each Undo pushes the state it took back) stores the
  // count ("search_undos"), and a history that begins the previous one's its length
  // ("history_kept"): a full copy of a 50-plane search is about a megabyte.
  static json redo_json(const Session& session) {
    json a = json::array();
    const Session* previous = nullptr;
    bool previous_by_undo = false;
    for (const auto& e : session.redo_) {
      const Session& s = *e.state;
      json entry{{"path", path_json(s.path_)}, {"start_point", vector_json(s.start_point_)}};
      const int undone = previous ? previous->search_.iteration() - s.search_.iteration() : -1;
      if (previous && previous_by_undo && undone >= 0) {
        entry["search_undos"] = undone;
      } else {
        entry["search"] = json::parse(s.search_.to_json());
      }
      if (previous && is_prefix(s.history_, previous->history_)) {
        entry["history_kept"] = s.history_.size();
      } else {
        entry["history"] = history_json(s.history_);
      }
      a.push_back(std::move(entry));
      previous = &s;
      previous_by_undo = e.next_by_undo;
    }
    if (!a.empty() && previous_by_undo) a.back()["undone_into_session"] = true;
    return a;
  }

  // Throws std::runtime_error "redo[i]: <problem>" on anything unusable.
  static void read_redo(Session& session, const json& a) {
    if (!a.is_array()) throw std::runtime_error("redo must be an array");
    if (a.size() > static_cast<std::size_t>(Session::kMaxRedo)) {
      throw std::runtime_error("redo has more than " + std::to_string(Session::kMaxRedo) +
                               " entries");
    }
    const SessionSettings& settings = session.settings_;
    std::shared_ptr<const Session> previous;
    for (std::size_t i = 0; i < a.size(); ++i) {
      try {
        const json& e = a[i];
        if (!e.is_object()) throw std::runtime_error("must be an object");
        Session s(settings);
        if (e.contains("search")) {
          s.search_ = sps::PlaneSearch::from_json(e.at("search").dump());
          if (s.search_.dims() != settings.components) {
            throw std::runtime_error("search dimensions differ from the component count");
          }
        } else if (e.contains("search_undos")) {
          if (!previous) throw std::runtime_error("search_undos without an earlier entry");
          const auto undos =
              integer_from(e.at("search_undos"), "search_undos", 0, previous->search_.iteration());
          s.search_ = previous->search_;
          for (long long k = 0; k < undos; ++k) (void)s.search_.undo();
        } else {
          throw std::runtime_error("search is missing");
        }
        s.path_ = path_from(sps::json_fields::field(e, "path", "path"), settings.grid_size, "path");
        if (static_cast<int>(s.path_.size()) > settings.zoom_levels) {
          throw std::runtime_error("path longer than the zoom levels");
        }
        s.start_point_ = vector_from(sps::json_fields::field(e, "start_point", "start_point"),
                                     settings.components, "start_point");
        if (e.contains("history")) {
          s.history_ = history_from(e.at("history"), settings);
        } else if (e.contains("history_kept")) {
          if (!previous) throw std::runtime_error("history_kept without an earlier entry");
          const auto kept = integer_from(e.at("history_kept"), "history_kept", 0,
                                         static_cast<long long>(previous->history_.size()));
          s.history_.assign(previous->history_.begin(),
                            previous->history_.begin() + static_cast<std::ptrdiff_t>(kept));
        } else {
          throw std::runtime_error("history is missing");
        }
        if (static_cast<int>(s.history_.size()) != s.search_.iteration()) {
          throw std::runtime_error("history length differs from the number of submissions");
        }
        bool undone_into_session = false;
        if (e.contains("undone_into_session")) {
          if (!e.at("undone_into_session").is_boolean()) {
            throw std::runtime_error("undone_into_session must be true or false");
          }
          undone_into_session = e.at("undone_into_session").get<bool>();
        }
        if (e.contains("search_undos")) session.redo_.back().next_by_undo = true;
        s.saved_holds_ = session.saved_holds_;
        s.update_views();
        previous = std::make_shared<const Session>(std::move(s));
        session.redo_.push_back({previous, undone_into_session && i + 1 == a.size()});
      } catch (const json::exception& ex) {
        throw std::runtime_error("redo[" + std::to_string(i) +
                                 "]: " + sps::json_fields::library_message(ex));
      } catch (const std::exception& ex) {
        throw std::runtime_error("redo[" + std::to_string(i) + "]: " + ex.what());
      }
    }
  }
};

Session::Session(const SessionSettings& settings) : Session(settings, sps::SearchOptions{}) {}

Session::Session(const SessionSettings& settings, sps::SearchOptions options)
    : settings_(settings), search_([&] {
        options.dims = settings.components;
        options.seed = settings.seed;
        return options;
      }()) {
  if (settings_.grid_size != 3 && settings_.grid_size != 5) {
    throw std::invalid_argument("grid size must be 3 or 5");
  }
  if (settings_.zoom_levels < 1 || settings_.zoom_levels > 8) {
    throw std::invalid_argument("zoom levels must be between 1 and 8");
  }
  if (settings_.components < 1) throw std::invalid_argument("components must be at least 1");
  start_point_ = search_.current_plane().c;
  update_views();
}

void Session::set_perceptual_scale(const Eigen::VectorXd& mm_per_unit,
                                   const Eigen::MatrixXd& metric) {
  search_.set_perceptual_scale(mm_per_unit, metric);
  if (path_.empty() && history_.empty() && search_.use_visible_first_plane()) {
    start_point_ = search_.current_plane().c;
  }
  update_views();
}

void Session::set_population(const sps::Population& population) {
  search_.set_population(population);
  retake_first_plane();
}

void Session::set_plane_axes(sps::PlaneAxes axes) {
  search_.set_plane_axes(axes);
  retake_first_plane();
}

void Session::set_uncertainty_size(const sps::UncertaintyPlaneSize& size) {
  search_.set_uncertainty_size(size);
  retake_first_plane();
}

void Session::set_perceptual_distance(PairwiseDistance distance, ZoomPolicy policy) {
  distance_ = std::move(distance);
  policy_ = std::move(policy);
  update_views();
}

namespace {

// A line (SLS) shows n*n points along its segment c -> c+u in reading order; the view's s is
// the centre in segment coordinates q in [-1, 1] (q = -1 is c, q = 1 is c + u).
int line_points(int n) {
  return n * n;
}

double line_coordinate(const sps::GridView& view, int n, int index) {
  const int m = line_points(n);
  return view.s + (static_cast<double>(index) - 0.5 * static_cast<double>(m - 1)) * view.spacing;
}

sps::GridView first_view(bool line, int n) {
  sps::GridView view;
  view.spacing =
      line ? 2.0 / static_cast<double>(line_points(n) - 1) : 2.0 / static_cast<double>(n - 1);
  return view;
}

// The points of `plane` a grid of size n shows at `view` (for a line, n*n points along it).
std::vector<sps::GridPoint> plane_cells(const sps::Plane& plane, int n, const sps::GridView& view) {
  if (!plane.is_line()) return sps::grid_points(plane, n, view);
  std::vector<sps::GridPoint> points;
  for (int k = 0; k < line_points(n); ++k) {
    sps::GridPoint p;
    p.s = line_coordinate(view, n, k);
    const Eigen::VectorXd raw = plane.c + (0.5 * (p.s + 1.0)) * plane.u;
    p.x = raw.cwiseMax(0.0).cwiseMin(1.0);
    p.clamped = (p.x - raw).cwiseAbs().maxCoeff() > 1e-12;
    points.push_back(std::move(p));
  }
  return points;
}

// Whether two of the cells look alike (closer than `threshold` by `distance`).
bool has_look_alike_pair(const std::vector<sps::GridPoint>& cells, const PairwiseDistance& distance,
                         double threshold) {
  std::vector<Eigen::VectorXd> xs;
  for (const auto& p : cells) xs.push_back(p.x);
  const Eigen::MatrixXd d = distance(xs);
  for (Eigen::Index i = 0; i < d.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < d.cols(); ++j) {
      if (!(d(i, j) >= threshold)) return true;
    }
  }
  return false;
}

// `base` widened or narrowed about the plane's current best (a cell of the base grid), which
// stays a cell.
sps::GridView scaled_about_best(const sps::GridView& base, const sps::Plane& plane, double factor) {
  sps::GridView view = base;
  view.spacing *= factor;
  view.s = plane.best_s + (base.s - plane.best_s) * factor;
  view.t = plane.best_t + (base.t - plane.best_t) * factor;
  return view;
}

// The first grid of a plane as shown: the plane's own square (`base`) where no two cells look
// alike; otherwise the plane is too small to see (e.g. it runs along directions that barely
// change the design), so a wider grid, as long as no cell leaves the box; then, as a last
// resort, wider ones with cells clamped onto the box (the outer cells then lie on the box's
// faces, off the plane); then narrower ones, because cells clamped onto the same faces can
// coincide however wide the grid is (a plane larger than the box, centred near a face).
// nullopt: none of them shows nine different cells.
std::optional<sps::GridView> distinct_first_view(
    const sps::GridView& base,
    const std::function<std::vector<sps::GridPoint>(const sps::GridView&)>& cells_of,
    const PairwiseDistance& distance, double threshold, const sps::Plane& plane) {
  if (!has_look_alike_pair(cells_of(base), distance, threshold)) return base;
  const auto scaled = [&](double factor) { return scaled_about_best(base, plane, factor); };
  const auto widen = [&](bool allow_clamped) -> std::optional<sps::GridView> {
    for (double factor : {1.25, 1.5, 2.0, 2.5, 3.0}) {
      const sps::GridView wider = scaled(factor);
      const std::vector<sps::GridPoint> cells = cells_of(wider);
      bool clamped = false;
      for (const auto& p : cells) clamped = clamped || p.clamped;
      if (clamped && !allow_clamped) return std::nullopt;
      if (!has_look_alike_pair(cells, distance, threshold)) return wider;
    }
    return std::nullopt;
  };
  if (auto wider = widen(false)) return wider;
  if (auto wider = widen(true)) return wider;
  for (double factor : {0.8, 0.64, 0.5, 0.4}) {
    const sps::GridView narrower = scaled(factor);
    if (!has_look_alike_pair(cells_of(narrower), distance, threshold)) return narrower;
  }
  return std::nullopt;
}

// Where no first grid of the plane about its current best shows n x n different cells: the
// grid moved by whole cells (the current best another cell of it), at the base spacing or
// narrower, nearest moves first; nullopt where none does either. Cells clamped onto the box's
// faces coincide on the far side of a face; moved away from it, the grid shows designs inside.
std::optional<sps::GridView> distinct_moved_view(
    const sps::GridView& base, int n,
    const std::function<std::vector<sps::GridPoint>(const sps::GridView&)>& cells_of,
    const PairwiseDistance& distance, double threshold, const sps::Plane& plane) {
  const int half_cells = (n - 1) / 2;
  for (double factor : {1.0, 0.8, 0.64, 0.5}) {
    const sps::GridView about_best = scaled_about_best(base, plane, factor);
    const double half = 0.5 * about_best.spacing * static_cast<double>(n - 1) + 1e-9;
    for (int moves = 1; moves <= 2 * half_cells; ++moves) {
      for (int i = -half_cells; i <= half_cells; ++i) {
        for (int j = -half_cells; j <= half_cells; ++j) {
          if (std::abs(i) + std::abs(j) != moves) continue;
          sps::GridView view = about_best;
          view.s += i * view.spacing;
          view.t += j * view.spacing;
          if (std::abs(plane.best_s - view.s) > half || std::abs(plane.best_t - view.t) > half) {
            continue;
          }
          if (!has_look_alike_pair(cells_of(view), distance, threshold)) return view;
        }
      }
    }
  }
  return std::nullopt;
}

// Each cell moved back onto the holds (inside the box), on two threads (projections are
// thread-safe).
void project_cells(const sps::SearchHold& hold, const sps::HeldPlane& held,
                   std::vector<sps::GridPoint>& cells) {
  sps::parallel_for(static_cast<int>(cells.size()), 2, [&](int i) {
    auto& p = cells[static_cast<std::size_t>(i)];
    p.x = hold.project_near(p.x, held.normals);
  });
}

bool same_plane(const sps::Plane& a, const sps::Plane& b) {
  return a.c == b.c && a.u == b.u && a.v.size() == b.v.size() && a.v == b.v &&
         a.u_neg_scale == b.u_neg_scale;
}

}  // namespace

void Session::retake_first_plane() {
  const sps::Plane before = search_.current_plane();
  if (path_.empty() && history_.empty() && search_.use_visible_first_plane() &&
      !same_plane(before, search_.current_plane())) {
    start_point_ = search_.current_plane().c;
    update_views();
  }
}

void Session::set_constraint_projector(std::shared_ptr<const ConstraintProjector> projector) {
  projector_ = std::move(projector);
  saved_holds_ = projector_ ? projector_->held_values() : std::vector<HeldValue>{};
  // The optimizer builds its next planes on the held surface; before the first click it also
  // chooses its first plane again (on the surface, or without the hold). The preference data
  // stay either way, and a plane already clicked on stays as it is (projected).
  search_.set_hold(projector_);
  if (path_.empty() && history_.empty() && search_.use_visible_first_plane()) {
    start_point_ = search_.current_plane().c;
  }
  update_views();
}

std::vector<sps::GridPoint> Session::cells_at(const sps::GridView& view) const {
  if (!held_) return plane_cells(search_.current_plane(), settings_.grid_size, view);
  for (const auto& [seen, cells] : held_cells_) {
    if (seen.s == view.s && seen.t == view.t && seen.spacing == view.spacing) return cells;
  }
  auto cells = plane_cells(held_->plane, settings_.grid_size, view);
  // Holds: each cell moved back onto the held measurements (a zoom level's grid, made on the
  // window's thread; the first grid of a new plane comes prepared from the worker).
  project_cells(*projector_, *held_, cells);
  held_cells_.emplace_back(view, cells);
  return cells;
}

PlaneVetter Session::plane_vetter() const {
  // Holds show projected cells (and keep the paper's planes); the paper's zoom has no
  // measure of what looks alike.
  if (projector_ || !distance_) return {};
  return [distance = distance_, threshold = policy_.look_alike_mm,
          n = settings_.grid_size](sps::PlaneSearch& search) {
    if (search.current_plane().is_line()) return;
    const auto distinct = [&] {
      const sps::Plane& plane = search.current_plane();
      const auto cells_of = [&](const sps::GridView& view) { return plane_cells(plane, n, view); };
      return distinct_first_view(first_view(false, n), cells_of, distance, threshold, plane)
          .has_value();
    };
    if (distinct()) return;
    // The paper's plane for the same choice; where that cannot be told apart either (or the
    // plane was the paper's already), the population's axes through the same centre.
    if (search.replace_uncertainty_plane() && distinct()) return;
    if (search.replace_with_population_plane()) {
      if (distinct()) return;
      // The other pairs of the population's four most uncertain axes through the same centre:
      // they vary other parameters, which may not clip where these do (5x5 photo grids, 20
      // trials: mean gap at plane 15 2.93 -> 2.72 against going straight to the part below).
      constexpr int kAxisPairs = 6;
      for (int pair = 1; pair < kAxisPairs; ++pair) {
        if (search.replace_with_population_plane(pair) && distinct()) return;
      }
      search.replace_with_population_plane(0);
    }
    // Last, that plane's part where its grid, moved by whole cells, shows n x n different
    // cells (on 5x5 photo grids near the faces the cells between the 3x3 ones clamped onto
    // the same colours: docs/benchmarks.md).
    const sps::Plane& plane = search.current_plane();
    if (plane.is_line()) return;
    const auto cells_of = [&](const sps::GridView& view) { return plane_cells(plane, n, view); };
    if (const auto view =
            distinct_moved_view(first_view(false, n), n, cells_of, distance, threshold, plane)) {
      search.replace_with_plane_part(view->s, view->t,
                                     0.5 * view->spacing * static_cast<double>(n - 1));
    }
  };
}

PlanePreparer Session::plane_preparer() const {
  if (!projector_) return {};
  return [projector = projector_, n = settings_.grid_size](const sps::PlaneSearch& search) {
    PreparedPlane prepared;
    prepared.plane = search.current_plane();
    prepared.holds = projector;
    prepared.held =
        std::make_shared<const sps::HeldPlane>(sps::hold_plane(*projector, prepared.plane));
    prepared.first_cells =
        plane_cells(prepared.held->plane, n, first_view(prepared.plane.is_line(), n));
    project_cells(*projector, *prepared.held, prepared.first_cells);
    return prepared;
  };
}

std::vector<sps::GridPoint> Session::decision_cells(const sps::GridView& view) const {
  if (!held_) return cells_at(view);
  for (const auto& [seen, cells] : held_cells_) {
    if (seen.s == view.s && seen.t == view.t && seen.spacing == view.spacing) return cells;
  }
  return plane_cells(held_->plane, settings_.grid_size, view);
}

bool Session::shows_look_alikes(const sps::GridView& view, double threshold_mm,
                                bool projected) const {
  if (!distance_) return false;
  return has_look_alike_pair(projected ? cells_at(view) : decision_cells(view), distance_,
                             threshold_mm);
}

sps::GridView Session::next_view(const sps::GridView& view, const sps::GridCell& clicked,
                                 bool check, bool& distinct) const {
  const int n = settings_.grid_size;
  const bool line = search_.current_plane().is_line();
  double s = 0.0, t = 0.0;
  if (line) {
    s = line_coordinate(view, n, clicked.row * n + clicked.col);
  } else {
    sps::cell_coordinates(view, n, clicked, s, t);
  }
  // The zoomed grid stays inside the plane's square (s, t in [-1, 1]), where an SPS plane lies
  // inside the box: cells are never clamped onto the bound (clamped cells become identical).
  // The clicked cell is then off-centre near the square's edge.
  const int span = line ? line_points(n) - 1 : n - 1;
  const auto zoomed = [&](double factor) {
    sps::GridView next;
    next.spacing = view.spacing * factor;
    const double half = 0.5 * next.spacing * static_cast<double>(span);
    // Within the first level's extent (the plane's square, or more when it was widened; off
    // centre when it was widened or narrowed about a current best off the centre).
    const sps::GridView& first = views_.front();
    const double extent = 0.5 * first.spacing * static_cast<double>(span);
    const double room = extent - half;
    next.s = room >= 0.0 ? std::clamp(s, first.s - room, first.s + room) : s;
    next.t = line ? 0.0 : (room >= 0.0 ? std::clamp(t, first.t - room, first.t + room) : t);
    return next;
  };
  distinct = true;
  // Without a distance hook: the paper's zoom. After the last level the grid is only shown
  // while the optimizer runs: no check.
  if (!distance_) return zoomed(kPaperZoomFactor);
  if (!check) return zoomed(policy_.factors.empty() ? kPaperZoomFactor : policy_.factors.front());
  for (double factor : policy_.factors) {
    const sps::GridView next = zoomed(factor);
    // With holds the grid is judged first-order (decision_cells); the one taken is projected
    // (it is shown next) and must still hold no look-alikes.
    if (!shows_look_alikes(next, policy_.distinct_mm) &&
        (!held_ || !shows_look_alikes(next, policy_.look_alike_mm, true))) {
      return next;
    }
  }
  distinct = false;
  return view;  // nothing visible left to zoom into: stay (the plane ends here)
}

void Session::update_views() {
  held_cells_.clear();
  held_ = nullptr;
  const bool line = search_.current_plane().is_line();
  if (projector_ && prepared_ && prepared_->holds == projector_ &&
      same_plane(prepared_->plane, search_.current_plane())) {
    held_ = prepared_->held;
    held_cells_.emplace_back(first_view(line, settings_.grid_size), prepared_->first_cells);
  } else if (projector_) {
    held_ = std::make_shared<const sps::HeldPlane>(
        sps::hold_plane(*projector_, search_.current_plane()));
  }
  prepared_.reset();
  held_best_.resize(0);
  if (held_) {
    const sps::Plane& plane = held_->plane;
    held_best_ =
        plane.best_is_centre()
            ? plane.c
            : projector_->project_near(plane.best().cwiseMax(0.0).cwiseMin(1.0), held_->normals);
  }
  views_.assign(1, first_view(line, settings_.grid_size));
  if (distance_ && !line) {
    const auto cells_of = [this](const sps::GridView& view) { return decision_cells(view); };
    if (auto shown = distinct_first_view(views_.front(), cells_of, distance_, policy_.look_alike_mm,
                                         search_.current_plane())) {
      views_.front() = *shown;
    }
  }
  ended_early_ = false;
  for (std::size_t i = 0; i < path_.size(); ++i) {
    bool distinct = true;
    const bool last_level = static_cast<int>(i) + 1 >= settings_.zoom_levels;
    views_.push_back(next_view(views_.back(), path_[i], !last_level, distinct));
    if (!distinct && !last_level && i + 1 == path_.size()) ended_early_ = true;
  }
}

ClickResult Session::click(const sps::GridCell& cell) {
  const int n = settings_.grid_size;
  if (submission_pending() || cell.col < 0 || cell.col >= n || cell.row < 0 || cell.row >= n) {
    return ClickResult::kIgnored;
  }
  path_.push_back(cell);
  // Only the new level: earlier ones are unchanged.
  bool distinct = true;
  const bool last_level = static_cast<int>(path_.size()) >= settings_.zoom_levels;
  views_.push_back(next_view(views_.back(), cell, !last_level, distinct));
  ended_early_ = !distinct && !last_level;
  return submission_pending() ? ClickResult::kPlaneFinished : ClickResult::kZoomed;
}

std::string Session::plane_note() const {
  return ended_early_ ? "No visible change left in this direction: this click is your choice." : "";
}

std::string Session::cell_note(const sps::GridPoint& cell) {
  if (cell.clamped) return "Beyond the edge of the search range (shown at the edge).";
  for (Eigen::Index i = 0; i < cell.x.size(); ++i) {
    if (cell.x[i] <= 1e-3 || cell.x[i] >= 1.0 - 1e-3) return "At the edge of the search range.";
  }
  return "";
}

std::vector<std::vector<Eigen::VectorXd>> Session::level_comparisons() const {
  const int n = settings_.grid_size;
  std::vector<std::vector<Eigen::VectorXd>> comparisons;
  for (std::size_t level = 0; level < path_.size(); ++level) {
    const auto points = cells_at(views_[level]);
    const auto& clicked = path_[level];
    const auto index = static_cast<Eigen::Index>(clicked.row * n + clicked.col);
    const auto& preferred = points[static_cast<size_t>(index)].x;
    Eigen::MatrixXd pairwise;
    if (distance_ && policy_.compare_mm > 0.0) {
      std::vector<Eigen::VectorXd> xs;
      for (const auto& p : points) xs.push_back(p.x);
      pairwise = distance_(xs);
    }
    std::vector<Eigen::VectorXd> comparison{preferred};
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto& p = points[k];
      if ((p.x - preferred).norm() <= 1e-9) continue;
      if (pairwise.size() > 0 &&
          !(pairwise(index, static_cast<Eigen::Index>(k)) >= policy_.compare_mm)) {
        continue;
      }
      comparison.push_back(p.x);
    }
    if (comparison.size() > 1) comparisons.push_back(std::move(comparison));
  }
  return comparisons;
}

Submission Session::submission() const {
  if (!submission_pending()) throw std::logic_error("no finished plane to submit");
  Submission s;
  s.chosen = current_best();
  s.extra_comparisons = level_comparisons();
  if (held_) {
    // The optimizer compares the choice with the plane's representatives (c, c+-u, c+-v...):
    // with holds, the held bodies shown there, never the unprojected plane's. Taken from the
    // cells already projected where a grid showed them, projected otherwise.
    for (const auto& [ps, pt] : search_.representative_coordinates()) {
      std::optional<Eigen::VectorXd> shown;
      if (!held_->plane.is_line()) {
        for (const auto& seen : held_cells_) {
          for (const auto& cell : seen.second) {
            if (std::abs(cell.s - ps) < 1e-9 && std::abs(cell.t - pt) < 1e-9) shown = cell.x;
          }
        }
      }
      if (!shown) {
        shown = projector_->project_near(held_->plane.point(ps, pt).cwiseMax(0.0).cwiseMin(1.0),
                                         held_->normals);
      }
      s.representatives.push_back(*shown);
    }
  }
  return s;
}

void Session::finish_plane(sps::PlaneSearch updated_search, std::optional<PreparedPlane> prepared) {
  if (!submission_pending()) throw std::logic_error("finish_plane without a finished plane");
  history_.push_back({current_best(), path_});
  search_ = std::move(updated_search);
  path_.clear();
  prepared_ = std::move(prepared);
  update_views();
}

bool Session::undo_click() {
  if (!path_.empty()) {
    path_.pop_back();
    update_views();
    return true;
  }
  if (history_.empty() || !search_.undo()) return false;
  path_ = history_.back().path;
  if (!history_.back().set_by_sliders && !path_.empty()) path_.pop_back();
  history_.pop_back();
  update_views();
  return true;
}

void Session::adopt_point(const Eigen::VectorXd& chosen, sps::PlaneSearch updated_search,
                          std::optional<PreparedPlane> prepared) {
  if (chosen.size() != settings_.components) {
    throw std::invalid_argument("adopt_point: the point has the wrong dimension");
  }
  history_.push_back({chosen, path_, true});
  search_ = std::move(updated_search);
  path_.clear();
  prepared_ = std::move(prepared);
  update_views();
}

bool Session::undo_plane() {
  if (!path_.empty()) {
    path_.clear();
    update_views();
    return true;
  }
  if (history_.empty() || !search_.undo()) return false;
  history_.pop_back();
  update_views();
  return true;
}

void Session::start_over() {
  search_.start_over();
  path_.clear();
  history_.clear();
  start_point_ = search_.current_plane().c;
  update_views();
}

void Session::push_redo(Session before, bool by_undo) {
  before.redo_.clear();
  before.redo_problem_.clear();
  before.prepared_.reset();
  redo_.push_back({std::make_shared<const Session>(std::move(before)), by_undo});
  if (static_cast<int>(redo_.size()) > kMaxRedo) redo_.erase(redo_.begin());
}

std::optional<Session> Session::pop_redo() {
  if (redo_.empty()) return std::nullopt;
  Session next = *redo_.back().state;
  redo_.pop_back();
  next.redo_ = std::move(redo_);
  redo_.clear();
  if (!next.projector_ && projector_) next.set_constraint_projector(projector_);
  if (!next.distance_ && distance_) next.set_perceptual_distance(distance_, policy_);
  return next;
}

Eigen::VectorXd Session::current_best() const {
  if (!path_.empty()) {
    const auto& clicked = path_.back();
    const auto points = cells_at(views_[path_.size() - 1]);
    return points[static_cast<size_t>(clicked.row * settings_.grid_size + clicked.col)].x;
  }
  return held_ ? held_best_ : search_.x_plus();
}

std::string Session::to_json() const {
  json j;
  j["format"] = "sequential-gallery-session";
  j["version"] = 1;
  j["settings"] = {{"space", settings_.space},
                   {"model_path", settings_.model_path},
                   {"components", settings_.components},
                   {"grid_size", settings_.grid_size},
                   {"zoom_levels", settings_.zoom_levels},
                   {"seed", settings_.seed}};
  j["search"] = json::parse(search_.to_json());
  j["path"] = path_json(path_);
  j["start_point"] = vector_json(start_point_);
  j["history"] = history_json(history_);
  if (!saved_holds_.empty()) {
    json holds = json::array();
    for (const auto& h : saved_holds_) holds.push_back({{"name", h.name}, {"value", h.value}});
    j["holds"] = holds;
  }
  if (!redo_.empty()) j["redo"] = SessionJson::redo_json(*this);
  // A model path that is not UTF-8 cannot be stored as it is; it is saved with U+FFFD
  // replacement characters (the resume then reports the model missing) rather than failing.
  return j.dump(1, ' ', false, json::error_handler_t::replace);
}

Session Session::from_json(const std::string& text) {
  // Refuses text nested too deep or holding huge strings before a tree exists (throws
  // std::runtime_error naming the problem and its byte offset).
  const json j = sps::json_fields::parse_bounded(text);
  try {
    if (!j.is_object() || j.value("format", "") != "sequential-gallery-session") {
      throw std::runtime_error("not a sequential-gallery session file");
    }
    if (integer_from(j.at("version"), "version", 0, 1000000) != 1) {
      throw std::runtime_error("unsupported session version " +
                               sps::json_fields::brief(j.at("version")));
    }
    // Every setting is checked before anything is sized by it.
    const auto& s = sps::json_fields::field(j, "settings", "settings");
    if (!s.is_object()) throw std::runtime_error("settings must be an object");
    SessionSettings settings;
    // Files from before photos were bodies.
    settings.space = s.contains("space") ? sps::json_fields::text(s, "space", "settings.space", 64)
                                         : std::string("body");
    // A path longer than the system allows (PATH_MAX) cannot name a file.
    settings.model_path = sps::json_fields::text(s, "model_path", "settings.model_path", 4096);
    settings.components =
        static_cast<int>(integer_from(s.at("components"), "components", 1, sps::kMaxSearchDims));
    settings.grid_size = static_cast<int>(integer_from(s.at("grid_size"), "grid_size", 3, 5));
    settings.zoom_levels = static_cast<int>(integer_from(s.at("zoom_levels"), "zoom_levels", 1, 8));
    if (!s.at("seed").is_number_unsigned()) {
      (void)integer_from(s.at("seed"), "seed", 0, LLONG_MAX);  // says why (negative, float)
    }
    settings.seed = s.at("seed").get<std::uint64_t>();
    Session session(settings);
    session.search_ = sps::PlaneSearch::from_json(j.at("search").dump());
    if (session.search_.dims() != settings.components) {
      throw std::runtime_error("search dimensions differ from the component count");
    }
    const int n = settings.grid_size;
    session.path_ = path_from(j.at("path"), n, "path");
    if (static_cast<int>(session.path_.size()) > settings.zoom_levels) {
      throw std::runtime_error("path longer than the zoom levels");
    }
    session.start_point_ = vector_from(j.at("start_point"), settings.components, "start_point");
    const json& history = j.at("history");
    if (history.is_array() && static_cast<int>(history.size()) != session.search_.iteration()) {
      throw std::runtime_error("history length differs from the number of submissions");
    }
    session.history_ = history_from(history, settings);
    if (static_cast<int>(session.history_.size()) != session.search_.iteration()) {
      throw std::runtime_error("history length differs from the number of submissions");
    }
    // Holds (optional: files from before holds existed have none). Only their form is checked here;
    // the design space checks names and values when the window holds them again.
    if (j.contains("holds")) {
      const json& holds = j.at("holds");
      if (!holds.is_array()) throw std::runtime_error("holds must be an array");
      if (holds.size() > 64) throw std::runtime_error("holds has more than 64 entries");
      for (const auto& h : holds) {
        if (!h.is_object() || !h.contains("name") || !h.at("name").is_string() ||
            !h.contains("value") || !h.at("value").is_number()) {
          throw std::runtime_error("holds entries must be {\"name\": text, \"value\": number}");
        }
        HeldValue held{h.at("name").get<std::string>(), h.at("value").get<double>()};
        if (held.name.empty() || held.name.size() > 64) {
          throw std::runtime_error("holds has a name that is empty or longer than 64 characters");
        }
        if (!std::isfinite(held.value) || !(held.value > 0.0) || held.value > 1e6) {
          throw std::runtime_error("holds value of " + held.name + " is not a positive number");
        }
        session.saved_holds_.push_back(std::move(held));
      }
    }
    // Redo (optional: older files have none). A broken redo part costs only the redo stack:
    // the session itself was read, and redo_problem() says what was wrong where.
    if (j.contains("redo")) {
      try {
        SessionJson::read_redo(session, j.at("redo"));
      } catch (const std::exception& e) {
        session.redo_.clear();
        session.redo_problem_ = e.what();
      }
    }
    session.update_views();
    return session;
  } catch (const json::exception& e) {
    throw std::runtime_error("malformed session (" + sps::json_fields::library_message(e) + ")");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("bad settings in session (") + e.what() + ")");
  } catch (const std::length_error& e) {
    throw std::runtime_error(std::string("sizes out of range in session (") + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("session too large to load (out of memory)");
  }
}

}  // namespace app
