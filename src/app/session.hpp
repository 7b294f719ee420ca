// The whole state of one design session as plain data: which model, the settings, the plane
// search (all preference data), the cells clicked on the current plane, the history of chosen
// bodies, and the point the user started from. Every change is a method; nothing here knows
// about GL, ImGui or threads. Serializes to JSON (see session_store.hpp for files).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sps/plane_search.hpp"
#include "sps/zoom_grid.hpp"

namespace app {

struct SessionSettings {
  std::string space = "body";  // the design space's kind (see app/design_space.hpp)
  std::string model_path;      // the space's source file; empty = its built-in default
  int components = 10;         // search dimensions (a body's shape components)
  int grid_size = 3;           // 3 or 5
  int zoom_levels = 4;         // clicks per plane
  std::uint64_t seed = 1;
};

// One finished plane: the body chosen on it and how the user got there.
struct HistoryEntry {
  Eigen::VectorXd chosen;           // x_chosen, in [0,1]^n
  std::vector<sps::GridCell> path;  // the clicks on that plane
};

// What a click did.
enum class ClickResult {
  kIgnored,        // out of range, or a submission is pending
  kZoomed,         // one level deeper on the same plane
  kPlaneFinished,  // the last zoom level: call submission() and then finish_plane()
};

// The submission a finished plane produces for sps::PlaneSearch::submit().
struct Submission {
  Eigen::VectorXd chosen;
  std::vector<std::vector<Eigen::VectorXd>> extra_comparisons;
};

class Session {
 public:
  explicit Session(const SessionSettings& settings);

  const SessionSettings& settings() const { return settings_; }
  const sps::PlaneSearch& search() const { return search_; }
  const std::vector<sps::GridCell>& path() const { return path_; }
  const std::vector<HistoryEntry>& history() const { return history_; }
  int planes_done() const { return static_cast<int>(history_.size()); }
  int clicks_on_plane() const { return static_cast<int>(path_.size()); }

  // The grid the user sees now (after the clicks so far on this plane).
  sps::GridView view() const;
  std::vector<sps::GridPoint> cells() const;

  // Clicking cell (col,row) of the current grid.
  ClickResult click(const sps::GridCell& cell);
  // True once the last zoom level was clicked and the plane waits for the optimizer.
  bool submission_pending() const {
    return static_cast<int>(path_.size()) >= settings_.zoom_levels;
  }
  // The choice and the intermediate levels as extra comparisons {clicked, other cells...}.
  Submission submission() const;
  // Installs the search state computed from submission() (on a worker) and starts the next plane.
  void finish_plane(sps::PlaneSearch updated_search);
  // Installs the search state computed from a point the user set directly (expert sliders,
  // submitted as preferred over the previous best): it ends the current plane as if chosen
  // there, with no clicks in its history entry.
  void adopt_point(const Eigen::VectorXd& chosen, sps::PlaneSearch updated_search);

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

  std::string to_json() const;
  // Throws std::runtime_error with a readable message on anything malformed.
  static Session from_json(const std::string& text);

 private:
  static sps::SearchOptions search_options(const SessionSettings& settings);

  SessionSettings settings_;
  sps::PlaneSearch search_;
  std::vector<sps::GridCell> path_;
  std::vector<HistoryEntry> history_;
  Eigen::VectorXd start_point_;
};

}  // namespace app
