#include "app/session.hpp"

#include <climits>
#include <cstdint>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace app {

namespace {

using nlohmann::json;

// A stored integer, checked before use: a float (1e300 as int is undefined), a string or a
// value out of range is an error naming the field.
long long integer_from(const json& j, const std::string& what, long long lo, long long hi) {
  long long v = 0;
  if (j.is_number_unsigned()) {
    if (j.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
      throw std::runtime_error(what + " is " + j.dump() + ", must lie in [" + std::to_string(lo) +
                               ", " + std::to_string(hi) + "]");
    }
    v = static_cast<long long>(j.get<std::uint64_t>());
  } else if (j.is_number_integer()) {
    v = j.get<std::int64_t>();
  } else {
    throw std::runtime_error(what + " must be an integer, found " + j.dump());
  }
  if (v < lo || v > hi) {
    throw std::runtime_error(what + " is " + std::to_string(v) + ", must lie in [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
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

}  // namespace

sps::SearchOptions Session::search_options(const SessionSettings& settings) {
  sps::SearchOptions options;
  options.dims = settings.components;
  options.seed = settings.seed;
  return options;
}

Session::Session(const SessionSettings& settings)
    : settings_(settings), search_(search_options(settings)) {
  if (settings_.grid_size != 3 && settings_.grid_size != 5) {
    throw std::invalid_argument("grid size must be 3 or 5");
  }
  if (settings_.zoom_levels < 1 || settings_.zoom_levels > 8) {
    throw std::invalid_argument("zoom levels must be between 1 and 8");
  }
  if (settings_.components < 1) throw std::invalid_argument("components must be at least 1");
  start_point_ = search_.current_plane().c;
}

sps::GridView Session::view() const {
  return sps::grid_view(settings_.grid_size, path_);
}

std::vector<sps::GridPoint> Session::cells() const {
  return sps::grid_points(search_.current_plane(), settings_.grid_size, view());
}

ClickResult Session::click(const sps::GridCell& cell) {
  const int n = settings_.grid_size;
  if (submission_pending() || cell.col < 0 || cell.col >= n || cell.row < 0 || cell.row >= n) {
    return ClickResult::kIgnored;
  }
  path_.push_back(cell);
  return submission_pending() ? ClickResult::kPlaneFinished : ClickResult::kZoomed;
}

Submission Session::submission() const {
  if (!submission_pending()) throw std::logic_error("no finished plane to submit");
  const int n = settings_.grid_size;
  const auto& plane = search_.current_plane();
  Submission s;
  s.chosen = sps::chosen_point(plane, n, path_).x;
  std::vector<sps::GridCell> prefix;
  for (const auto& clicked : path_) {
    const auto points = sps::grid_points(plane, n, prefix);
    const auto& preferred = points[static_cast<size_t>(clicked.row * n + clicked.col)].x;
    std::vector<Eigen::VectorXd> comparison{preferred};
    for (const auto& p : points) {
      if ((p.x - preferred).norm() > 1e-9) comparison.push_back(p.x);
    }
    if (comparison.size() > 1) s.extra_comparisons.push_back(std::move(comparison));
    prefix.push_back(clicked);
  }
  return s;
}

void Session::finish_plane(sps::PlaneSearch updated_search) {
  if (!submission_pending()) throw std::logic_error("finish_plane without a finished plane");
  history_.push_back(
      {sps::chosen_point(search_.current_plane(), settings_.grid_size, path_).x, path_});
  search_ = std::move(updated_search);
  path_.clear();
}

bool Session::undo_click() {
  if (!path_.empty()) {
    path_.pop_back();
    return true;
  }
  if (history_.empty() || !search_.undo()) return false;
  path_ = history_.back().path;
  if (!path_.empty()) path_.pop_back();  // a point set by sliders has no clicks
  history_.pop_back();
  return true;
}

void Session::adopt_point(const Eigen::VectorXd& chosen, sps::PlaneSearch updated_search) {
  if (chosen.size() != settings_.components) {
    throw std::invalid_argument("adopt_point: the point has the wrong dimension");
  }
  history_.push_back({chosen, {}});
  search_ = std::move(updated_search);
  path_.clear();
}

bool Session::undo_plane() {
  if (!path_.empty()) {
    path_.clear();
    return true;
  }
  if (history_.empty() || !search_.undo()) return false;
  history_.pop_back();
  return true;
}

void Session::start_over() {
  search_.start_over();
  path_.clear();
  history_.clear();
  start_point_ = search_.current_plane().c;
}

Eigen::VectorXd Session::current_best() const {
  if (!path_.empty()) {
    return sps::chosen_point(search_.current_plane(), settings_.grid_size, path_).x;
  }
  return search_.x_plus();
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
  json history = json::array();
  for (const auto& h : history_) {
    history.push_back({{"chosen", vector_json(h.chosen)}, {"path", path_json(h.path)}});
  }
  j["history"] = history;
  // A model path that is not UTF-8 cannot be stored as it is; it is saved with U+FFFD
  // replacement characters (the resume then reports the model missing) rather than failing.
  return j.dump(1, ' ', false, json::error_handler_t::replace);
}

Session Session::from_json(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("not valid JSON (") + e.what() + ")");
  }
  try {
    if (!j.is_object() || j.value("format", "") != "sequential-gallery-session") {
      throw std::runtime_error("not a sequential-gallery session file");
    }
    if (integer_from(j.at("version"), "version", 0, 1000000) != 1) {
      throw std::runtime_error("unsupported session version " + j.at("version").dump());
    }
    // Every setting is checked before anything is sized by it.
    const auto& s = j.at("settings");
    SessionSettings settings;
    settings.space = s.value("space", "body");  // files from before photos were bodies
    settings.model_path = s.at("model_path").get<std::string>();
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
    if (!history.is_array()) throw std::runtime_error("history must be an array");
    if (static_cast<int>(history.size()) != session.search_.iteration()) {
      throw std::runtime_error("history length differs from the number of submissions");
    }
    for (const auto& h : history) {
      HistoryEntry entry;
      entry.chosen = vector_from(h.at("chosen"), settings.components, "history chosen");
      entry.path = path_from(h.at("path"), n, "history path");
      // Undo reopens a finished plane with its clicks minus the last: each finished plane has
      // exactly one click per zoom level.
      if (static_cast<int>(entry.path.size()) != settings.zoom_levels) {
        throw std::runtime_error("history path has " + std::to_string(entry.path.size()) +
                                 " clicks, expected " + std::to_string(settings.zoom_levels));
      }
      session.history_.push_back(std::move(entry));
    }
    if (static_cast<int>(session.history_.size()) != session.search_.iteration()) {
      throw std::runtime_error("history length differs from the number of submissions");
    }
    return session;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed session (") + e.what() + ")");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("bad settings in session (") + e.what() + ")");
  } catch (const std::length_error& e) {
    throw std::runtime_error(std::string("sizes out of range in session (") + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("session too large to load (out of memory)");
  }
}

}  // namespace app
