// The gallery's state and every change to it, without GL or ImGui: the design space, the session
// (preference data, clicks, history), the optimizer worker, autosave, the resume question, the
// grid animation and the message line.
//
// Nothing changes while a frame is being built: the view and the input handlers queue intents,
// and begin_frame() applies them at the start of the next frame, before the UI toolkit starts a
// new frame. So a texture the UI has queued for drawing is never freed under it (the order
// polyscope's draw() keeps: apply changes, then build and draw the UI).
#pragma once

#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "app/design_space.hpp"
#include "app/session.hpp"
#include "app/session_store.hpp"
#include "app/session_writer.hpp"
#include "app/space_catalogue.hpp"
#include "app/worker.hpp"
#include "sps/zoom_grid.hpp"
#include "util/file_lock.hpp"

namespace app {

enum class ResumePolicy { kAsk, kYes, kNo };

struct ControllerOptions {
  SpaceSettings space;        // the space of a new search (a resumed session brings its own)
  bool space_chosen = false;  // `space` was asked for (the command line), not a default
  int grid_size = 0;          // 0 = the kind's default grid (SpaceKind::grid_size)
  // The kinds of space, for their default grids (also of a new search on another kind).
  const SpaceCatalogue* catalogue = nullptr;
  int zoom_levels = 4;
  std::uint64_t seed = 1;
  std::filesystem::path session_path;  // autosave file; empty = no autosave
  ResumePolicy resume = ResumePolicy::kAsk;
  double zoom_seconds = 1.5;
  double morph_seconds = 0.6;
  int optimizer_delay_ms = 0;  // testing: hold each optimizer run back
  // testing: false leaves the space's perceptual distance out (the paper's fixed zoom, so a
  // plane always takes zoom_levels clicks), for tests of what clicks do to a session.
  bool perceptual_zoom = true;
  // Body grids framed on where their cells differ (View: Close-ups, remembered in ui.json):
  // set on every space the controller opens, before its first grid is framed.
  bool close_ups = true;
  bool log = true;  // messages also go to stdout / stderr
  // Each message also as one "[message] error|success|info TEXT" line on stdout, so that
  // scripted window tests read what the window shows by its kind, not by a log's wording.
  bool report_messages = false;
  // Autosave on a thread of its own (the window); off, every save is done before the intent
  // that caused it returns (tests read the file right after).
  bool background_autosave = false;
  // From the command line: "name=value" targets to go to first, then holds.
  std::vector<std::string> targets;
  std::vector<std::string> holds;
};

// Opens a design space (loads a model, an image...); throws with a readable message.
using SpaceOpener = std::function<std::unique_ptr<DesignSpace>(const SpaceSettings&)>;

namespace intent {
struct ClickCell {
  int col = 0;
  int row = 0;
};
struct UndoClick {};
struct UndoPlane {};  // always: discard the last finished plane (and clicks made after it)
struct Redo {};
struct StartOver {};
struct Open {  // a new search in another (or the same) space
  SpaceSettings space;
  int grid_size = 0;
  int zoom_levels = 4;
};
struct Resume {};
struct StartNew {};
struct Export {
  std::filesystem::path path;
};
struct Inspect {
  int history_index = -1;  // -1: back to the current best
};
// Expert sliders' "use this": x becomes the current best, submitted as preferred over the
// previous best (it ends the current plane).
struct UsePoint {
  Eigen::VectorXd x;
};
// Holds: the whole set, each "name" (held at the current best's value) or
// "name=value"; empty releases them (the preference data stay).
struct SetHolds {
  std::vector<std::string> holds;
  bool resumed = false;  // a resumed session's own holds, held again (its redo steps stay)
};
// "Go": the point nearest to the current best meeting "name=value" targets becomes the current
// best (as UsePoint), or the message says which targets are out of reach.
struct GoToTargets {
  std::vector<std::string> targets;
};
// The view's cells are now this many pixels high: the look-alike threshold of the zoom
// levels still to come follows (SpacePerception::zoom_policy).
struct SetCellPixels {
  int pixels = 0;
};
// Frame body grids on where their cells differ, or whole (DesignSpace::set_close_ups): the
// look-alike test of the zoom levels still to come follows; the grid on screen stays.
struct SetCloseUps {
  bool on = true;
};
}  // namespace intent

using Intent = std::variant<intent::ClickCell, intent::UndoClick, intent::UndoPlane, intent::Redo,
                            intent::StartOver, intent::Open, intent::Resume, intent::StartNew,
                            intent::Export, intent::Inspect, intent::UsePoint, intent::SetHolds,
                            intent::GoToTargets, intent::SetCellPixels, intent::SetCloseUps>;

enum class MessageKind { kInfo, kSuccess, kError };
struct Message {
  MessageKind kind = MessageKind::kInfo;
  std::string text;
};

class GalleryController {
 public:
  // Opens the space (falling back to its default with an error message if the file fails) and
  // loads the session file per the resume policy. Throws if not even the default space opens.
  GalleryController(ControllerOptions options, SpaceOpener opener, double now_seconds = 0.0);
  ~GalleryController();
  GalleryController(const GalleryController&) = delete;
  GalleryController& operator=(const GalleryController&) = delete;

  void queue(Intent intent) { queue_.push_back(std::move(intent)); }
  // Start of a frame: installs a finished optimizer result, applies the queued intents in
  // order, starts the next optimizer run if one is due, and advances the grid animation.
  void begin_frame(double now_seconds);
  // Blocks until a running optimizer job ends and installs its result (tests; shutdown).
  void wait_for_optimizer(double now_seconds);
  // Saves the session now (end of the program).
  void save_now();
  // A problem found outside the controller (a broken ui.json) shown as its message.
  void report_problem(std::string text) { say(MessageKind::kError, std::move(text)); }

  // --- State (read by the view) ---
  const Session& session() const { return *session_; }
  const DesignSpace& space() const { return *space_; }
  DesignSpace& space() { return *space_; }
  int space_generation() const { return space_generation_; }  // bumps when space_ is replaced
  int generation() const { return generation_; }              // bumps on every session change

  // The resume question at start-up.
  const Session* resume_candidate() const { return pending_resume_ ? &*pending_resume_ : nullptr; }
  std::string resume_description() const;
  // The kind of search asked for when it is not the resumable session's ("photo" while a body
  // session waits), else empty: the question then offers that search instead of a plain
  // "Start new".
  std::string asked_kind_instead() const;
  // The kind of the resumable session ("body"; a file that names none: the default kind).
  std::string resume_kind() const;

  // The optimizer is due or running.
  bool busy() const { return session_->submission_pending() || point_job_.has_value(); }
  bool animating() const { return animation_ != Animation::kNone; }
  bool zooming() const { return animation_ == Animation::kZoom; }
  // The points the grid shows this frame (between two grids while animating).
  const std::vector<sps::GridPoint>& displayed_cells() const { return displayed_; }

  int inspected() const { return inspected_; }  // history index shown, -1 = current best
  Eigen::VectorXd shown_point() const;          // the inspected choice or the current best

  bool can_undo_click() const;
  bool can_undo_plane() const { return !busy() && session_->planes_done() > 0; }
  bool can_redo() const { return !busy() && session_->redo_depth() > 0; }
  // Clicks or finished planes that a new search would discard.
  bool has_progress() const {
    return session_->planes_done() > 0 || session_->clicks_on_plane() > 0;
  }

  const Message& message() const { return message_; }
  // Persistent: the last autosave failed (cleared by the next one that succeeds).
  const std::string& autosave_problem() const { return autosave_status_.error(); }
  bool autosave_enabled() const { return autosave_enabled_; }
  // Another window holds this session file's lock: this one shows it without saving.
  bool open_elsewhere() const { return open_elsewhere_; }
  const std::filesystem::path& session_path() const { return options_.session_path; }
  const std::filesystem::path& last_export() const { return last_export_; }
  double last_submit_seconds() const { return last_submit_seconds_; }
  int ignored_clicks() const { return ignored_clicks_; }  // clicks dropped while animating
  // The holds in force (as the SetHolds intent gave them) and what they hold, in words.
  const std::vector<std::string>& holds() const { return holds_; }
  std::string holds_description() const;
  const ControllerOptions& options() const { return options_; }

 private:
  enum class Animation { kNone, kZoom, kMorph };

  void apply(const Intent& intent);
  void click(const intent::ClickCell& c);
  void undo_click();
  void undo_plane();
  void redo();
  void start_over();
  void open(const intent::Open& o);
  void resume();
  void start_new();
  void export_point(const std::filesystem::path& path);
  // `what`: the point's origin for messages ("the slider values", "the body meeting the
  // targets"). A slider point is moved onto the holds in force first (the sliders know nothing
  // of them), so that what is held stays held.
  void use_point(const Eigen::VectorXd& x, const std::string& what, bool onto_holds);
  void set_holds(const std::vector<std::string>& holds, bool resumed = false);
  void go_to_targets(const std::vector<std::string>& targets);

  void adopt(Session session, std::unique_ptr<DesignSpace> space);
  // The space's perceptual hooks on `session_` (never saved, so after every load too).
  void install_perception();
  // The zoom policy, the planes' smallest side and the choice temperature for the cells' size
  // and framing now (the grid on screen stays).
  void follow_cells();
  // `asked`, or the kind's default grid where it is 0.
  int grid_for(const DesignSpace& space, int asked) const;
  void after_change(const sps::Plane& plane_before);
  void poll_worker();
  void autosave();
  void take_save_result(const GuardedSave& result);
  void keep_old_session_file(const std::string& why);
  void install(SubmitWorker::Result result);
  void update_display();
  void say(MessageKind kind, std::string text);

  ControllerOptions options_;
  SpaceOpener opener_;
  std::unique_ptr<DesignSpace> space_;
  std::optional<Session> session_;
  std::optional<Session> pending_resume_;
  std::unique_ptr<DesignSpace> pending_resume_space_;
  std::string pending_redo_problem_;  // said once the session is resumed
  std::deque<Intent> queue_;

  SubmitWorker worker_;
  std::optional<Eigen::VectorXd> point_job_;  // a slider point being submitted
  std::string point_job_what_;                // what it is, for the message when it is in
  std::string finished_plane_note_;           // why the plane being submitted ended early
  int generation_ = 0;
  int space_generation_ = 0;
  int submitted_generation_ = -1;
  double last_submit_seconds_ = 0.0;

  bool autosave_enabled_ = true;
  AutosaveStatus autosave_status_;
  std::optional<util::FileLock> session_lock_;  // held while this window owns the session file
  bool open_elsewhere_ = false;
  FileStamp session_file_stamp_;           // the file as this window last read or wrote it
  std::unique_ptr<SessionWriter> writer_;  // with background_autosave
  Message message_;
  std::filesystem::path last_export_;
  int inspected_ = -1;
  int ignored_clicks_ = 0;
  int cell_pixels_ = 0;  // the view's cell height; 0 until a view says
  std::vector<std::string> holds_;
  std::vector<Intent> deferred_;  // holds and targets asked for while the optimizer ran

  double now_ = 0.0;
  Animation animation_ = Animation::kNone;
  double animation_start_ = 0.0;
  double animation_seconds_ = 1.0;
  sps::GridView view_from_, view_to_, displayed_view_;
  std::vector<Eigen::VectorXd> morph_from_;
  std::vector<sps::GridPoint> displayed_;
};

}  // namespace app
