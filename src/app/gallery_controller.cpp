#include "app/gallery_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "app/session_perception.hpp"
#include "app/session_store.hpp"

namespace app {

namespace fs = std::filesystem;

namespace {

// Long enough for the frame after a click to be drawn (25-60 ms on a software renderer), short
// enough that a crash right after a click still finds it saved almost always.
constexpr std::chrono::milliseconds kAutosaveDelay(120);

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

SessionSettings session_settings(const SpaceSettings& space, int grid_size, int zoom_levels,
                                 std::uint64_t seed) {
  SessionSettings s;
  s.space = space.kind;
  s.model_path = space.source;
  s.components = space.dimensions;
  s.grid_size = grid_size;
  s.zoom_levels = zoom_levels;
  s.seed = seed;
  return s;
}

SpaceSettings space_of(const SessionSettings& s) {
  return SpaceSettings{s.space, s.model_path, s.components};
}

// A body model with fewer components than asked for explores all it has; say so rather than
// searching fewer dimensions without a word.
std::string fewer_dimensions_note(const SpaceSettings& asked, const DesignSpace& space) {
  if (asked.kind != space.settings().kind || space.dimensions() >= asked.dimensions) return "";
  return space.source_label() + " has only " + std::to_string(space.dimensions()) +
         " components: exploring " + std::to_string(space.dimensions()) + ", not the " +
         std::to_string(asked.dimensions) + " asked for";
}

bool same_plane(const sps::Plane& a, const sps::Plane& b) {
  return a.c.size() == b.c.size() && a.c == b.c && a.u == b.u && a.v == b.v;
}

}  // namespace

GalleryController::GalleryController(ControllerOptions options, SpaceOpener opener,
                                     double now_seconds)
    : options_(std::move(options)), opener_(std::move(opener)), now_(now_seconds) {
  try {
    space_ = opener_(options_.space);
  } catch (const std::exception& e) {
    if (options_.space.source.empty()) throw;  // not even the built-in default opens
    say(MessageKind::kError, std::string(e.what()) + " (showing the default instead)");
    options_.space.source.clear();
    space_ = opener_(options_.space);
  }
  if (const std::string note = fewer_dimensions_note(options_.space, *space_); !note.empty()) {
    say(MessageKind::kError, note);
  }
  options_.space = space_->settings();
  const int grid = grid_for(*space_, options_.grid_size);
  session_.emplace(session_settings(options_.space, grid, options_.zoom_levels, options_.seed));
  install_perception();

  if (options_.session_path.empty()) {
    autosave_enabled_ = false;
  } else {
    // One window per session file: a second window on the same file would overwrite the
    // first one's clicks (or the first one, closed last, the second's).
    std::string lock_problem;
    const auto lock = util::FileLock::try_acquire(util::lock_path_for(options_.session_path),
                                                  session_lock_, &lock_problem);
    if (lock == util::FileLock::Outcome::kHeldElsewhere) {
      open_elsewhere_ = true;
      autosave_enabled_ = false;
      autosave_status_.failed(
          "this search is open in another window, so this one saves nothing: view it here "
          "read-only, or start a new search (not saved; export what you find). Close the other "
          "window to continue it here.");
    } else if (lock == util::FileLock::Outcome::kUnavailable && options_.log) {
      std::cerr << "sequential-gallery: " << lock_problem
                << " (another window on the same session would not be noticed)" << std::endl;
    }
    LoadResult loaded = load_session(options_.session_path, !open_elsewhere_);
    session_file_stamp_ = loaded.stamp;
    if (open_elsewhere_) {
      say(MessageKind::kError, autosave_status_.error());
      if (!loaded.problem.empty()) say(MessageKind::kError, loaded.problem);
    } else if (!loaded.problem.empty()) {
      say(MessageKind::kError, loaded.problem);
      session_file_stamp_ = stamp_of(options_.session_path);  // moved aside: usually none now
      if (loaded.set_aside.empty()) {
        autosave_enabled_ = false;  // never overwrite a file we could not read or move
        message_.text += " -- autosave is OFF for this run";
      }
    }
    if (loaded.session) {
      std::unique_ptr<DesignSpace> resumed_space;
      std::string problem;
      try {
        // Resumed at once on the space already open: it is not opened a second time (a body
        // model takes about 0.1 s to load). Asking first keeps the session's own space for
        // the question.
        const SpaceSettings wanted = space_of(loaded.session->settings());
        const SpaceSettings& have = space_->settings();
        const bool same_space = options_.resume == ResumePolicy::kYes && wanted.kind == have.kind &&
                                wanted.source == have.source &&
                                wanted.dimensions == have.dimensions;
        if (!same_space) resumed_space = opener_(wanted);
        const int dimensions = same_space ? space_->dimensions() : resumed_space->dimensions();
        if (dimensions != loaded.session->settings().components) {
          throw std::runtime_error("the space now has " + std::to_string(dimensions) +
                                   " dimensions, the session " +
                                   std::to_string(loaded.session->settings().components));
        }
      } catch (const std::exception& e) {
        problem = e.what();
      }
      if (!problem.empty()) {
        if (open_elsewhere_) {
          say(MessageKind::kError, "cannot show the session open in another window: " + problem);
        } else {
          keep_old_session_file("cannot resume the previous session: " + problem);
        }
      } else if (options_.resume == ResumePolicy::kYes) {
        adopt(std::move(*loaded.session), std::move(resumed_space));
        say(MessageKind::kInfo, "resumed the session from " + options_.session_path.string());
        if (!loaded.redo_problem.empty()) say(MessageKind::kError, loaded.redo_problem);
      } else if (options_.resume == ResumePolicy::kAsk) {
        pending_resume_ = std::move(loaded.session);
        pending_resume_space_ = std::move(resumed_space);
        pending_redo_problem_ = std::move(loaded.redo_problem);
      } else {
        keep_old_session_file("");
      }
    }
  }
  if (autosave_enabled_ && options_.background_autosave) {
    // The copy waits a few frames, so the frame that answers the click does not share the CPU
    // with writing it (a long session's save is tens of ms); clicks in that time replace it.
    writer_ = std::make_unique<SessionWriter>(session_file_stamp_, kAutosaveDelay);
  }
  // Command-line targets, then holds: applied at the first frame that may (after the resume
  // question; a target's point goes through the optimizer before the holds are built).
  if (!options_.targets.empty()) deferred_.push_back(intent::GoToTargets{options_.targets});
  if (!options_.holds.empty()) deferred_.push_back(intent::SetHolds{options_.holds});
  displayed_view_ = session_->view();
  update_display();
}

GalleryController::~GalleryController() {
  if (worker_.busy()) worker_.wait();  // a running submit finishes; its result is dropped
}

void GalleryController::say(MessageKind kind, std::string text) {
  message_ = {kind, std::move(text)};
  if (options_.report_messages) {
    const char* name = kind == MessageKind::kError     ? "error"
                       : kind == MessageKind::kSuccess ? "success"
                                                       : "info";
    std::cout << "[message] " << name << ' ' << message_.text << std::endl;
  }
  if (!options_.log) return;
  if (kind == MessageKind::kError) {
    std::cerr << "sequential-gallery: " << message_.text << std::endl;
  } else {
    std::cout << "[gallery] " << message_.text << std::endl;
  }
}

std::string GalleryController::resume_description() const {
  if (!pending_resume_) return "";
  const auto& s = pending_resume_->settings();
  // The space's description already counts its dimensions ("..., 10 components").
  const std::string what =
      pending_resume_space_ ? pending_resume_space_->description()
                            : resume_kind() + ", " + std::to_string(s.components) + " dimensions";
  const int planes = pending_resume_->planes_done();
  const int clicks = pending_resume_->clicks_on_plane();
  char text[160];
  std::snprintf(text, sizeof text,
                "; %dx%d grid; %d finished plane%s, %d click%s on the current plane", s.grid_size,
                s.grid_size, planes, planes == 1 ? "" : "s", clicks, clicks == 1 ? "" : "s");
  return what + text;
}

std::string GalleryController::resume_kind() const {
  if (!pending_resume_) return "";
  const std::string& kind = pending_resume_->settings().space;
  return kind.empty() && options_.catalogue != nullptr ? options_.catalogue->default_kind().name
                                                       : kind;
}

std::string GalleryController::asked_kind_instead() const {
  if (!pending_resume_ || !options_.space_chosen) return "";
  return resume_kind() != options_.space.kind ? options_.space.kind : "";
}

void GalleryController::begin_frame(double now_seconds) {
  now_ = now_seconds;
  poll_worker();
  if (writer_) {
    if (auto r = writer_->poll()) take_save_result(*r);
  }
  if (!deferred_.empty() && !busy() && !worker_.busy() && !pending_resume_) {
    // One at a time: a target's point is submitted to the optimizer before the next applies.
    queue_.push_front(deferred_.front());
    deferred_.erase(deferred_.begin());
  }
  while (!queue_.empty()) {
    const Intent next = std::move(queue_.front());
    queue_.pop_front();
    apply(next);
  }
  if (session_->submission_pending() && !worker_.busy() && submitted_generation_ != generation_ &&
      !pending_resume_) {
    worker_.start(session_->search(), session_->submission(), generation_,
                  std::chrono::milliseconds(options_.optimizer_delay_ms),
                  session_->plane_preparer(), session_->plane_vetter());
    submitted_generation_ = generation_;
  }
  update_display();
}

void GalleryController::wait_for_optimizer(double now_seconds) {
  begin_frame(now_seconds);  // starts the job if one is due
  if (!worker_.busy()) return;
  if (auto result = worker_.wait()) install(std::move(*result));
  update_display();
}

void GalleryController::save_now() {
  if (!pending_resume_) autosave();
  if (writer_) {
    writer_->flush();
    if (auto r = writer_->poll()) take_save_result(*r);
  }
}

void GalleryController::apply(const Intent& i) {
  // While the resume question is open, only its answers count.
  if (pending_resume_ && !std::holds_alternative<intent::Resume>(i) &&
      !std::holds_alternative<intent::StartNew>(i) &&
      !std::holds_alternative<intent::SetCellPixels>(i)) {
    return;
  }
  std::visit(
      Overloaded{
          [&](const intent::ClickCell& c) { click(c); },
          [&](const intent::UndoClick&) { undo_click(); },
          [&](const intent::UndoPlane&) { undo_plane(); }, [&](const intent::Redo&) { redo(); },
          [&](const intent::StartOver&) { start_over(); }, [&](const intent::Open& o) { open(o); },
          [&](const intent::Resume&) { resume(); }, [&](const intent::StartNew&) { start_new(); },
          [&](const intent::Export& e) { export_point(e.path); },
          [&](const intent::UsePoint& u) { use_point(u.x, "the slider values", true); },
          [&](const intent::SetHolds& h) { set_holds(h.holds, h.resumed); },
          [&](const intent::GoToTargets& t) { go_to_targets(t.targets); },
          [&](const intent::SetCellPixels& p) {
            if (p.pixels == cell_pixels_ || p.pixels < 1) return;
            cell_pixels_ = p.pixels;
            follow_cells();
          },
          [&](const intent::SetCloseUps& f) {
            options_.close_ups = f.on;  // and for every search opened after this one
            if (space_->close_ups() == f.on) return;
            space_->set_close_ups(f.on);
            // The session's distance is the grids' as framed: install the new one.
            if (const SpacePerception* perception = space_->perception();
                perception != nullptr && options_.perceptual_zoom) {
              session_->set_perceptual_distance(perception->perceptual_distance(),
                                                perception->zoom_policy(cell_pixels_));
            }
            follow_cells();
          },
          [&](const intent::Inspect& n) {
            inspected_ = n.history_index >= 0 && n.history_index < session_->planes_done()
                             ? n.history_index
                             : -1;
          }},
      i);
}

void GalleryController::click(const intent::ClickCell& c) {
  if (session_->submission_pending()) {
    say(MessageKind::kInfo, "computing the next plane, one moment...");
    return;
  }
  // A click while the grid still zooms (a double-click's second click, an impatient click)
  // would pick a cell the user has not seen yet: it is dropped, not counted as a zoom step.
  if (animation_ == Animation::kZoom) {
    ++ignored_clicks_;
    return;
  }
  const sps::Plane before = session_->search().current_plane();
  const ClickResult r = session_->click({c.col, c.row});
  if (r == ClickResult::kIgnored) return;
  session_->clear_redo();
  inspected_ = -1;
  after_change(before);
  if (options_.log) {
    std::cout << "[gallery] click cell " << c.row * session_->settings().grid_size + c.col + 1
              << " (plane " << session_->planes_done() + 1 << ", level "
              << session_->clicks_on_plane() << ")" << std::endl;
  }
  if (r == ClickResult::kZoomed && message_.kind == MessageKind::kSuccess) {
    // The last plane's "done" line (and why it ended early) is about that plane: once this
    // one is clicked on it would read as if it were about the grid on screen.
    // No click count here: the line stays through the plane's later clicks, and the toolbar
    // counts them.
    say(MessageKind::kInfo, "zoomed in around your choice: pick the best again");
  }
  if (r == ClickResult::kPlaneFinished) {
    // A plane that ends before its last zoom level says why in plain words.
    const std::string note = session_->plane_note();
    // Kept for the message that announces the next plane, which would otherwise replace it
    // within a second.
    finished_plane_note_ = note;
    say(MessageKind::kInfo, note.empty() ? "choice submitted; computing the next plane..."
                                         : note + " Computing the next plane...");
  }
}

bool GalleryController::can_undo_click() const {
  return !busy() && (session_->clicks_on_plane() > 0 || session_->planes_done() > 0);
}

void GalleryController::undo_click() {
  if (busy()) return;
  const sps::Plane before = session_->search().current_plane();
  Session snapshot = *session_;
  if (session_->undo_click()) {
    session_->push_redo(std::move(snapshot), true);
    after_change(before);
    say(MessageKind::kInfo, "undid the last click");
  } else {
    say(MessageKind::kInfo, "nothing to undo");
  }
}

void GalleryController::undo_plane() {
  if (busy()) return;
  if (session_->planes_done() == 0) {
    say(MessageKind::kInfo, "no finished plane to undo (Undo click takes back clicks)");
    return;
  }
  const sps::Plane before = session_->search().current_plane();
  Session snapshot = *session_;
  // One meaning: back to the start of the last finished plane. Session::undo_plane drops the
  // clicks on the current plane when there are any, else the last finished plane: so one call
  // for the clicks, one for the plane, and never a third (it took a second plane away).
  if (session_->clicks_on_plane() > 0) session_->undo_plane();
  if (session_->undo_plane()) {
    if (session_->clicks_on_plane() > 0) session_->undo_plane();  // reopened without clicks
    session_->push_redo(std::move(snapshot), true);
    inspected_ = -1;
    after_change(before);
    say(MessageKind::kInfo,
        "undid plane " + std::to_string(session_->planes_done() + 1) + "; choose on it again");
  }
}

void GalleryController::redo() {
  if (busy() || session_->redo_depth() == 0) return;
  const sps::Plane before = session_->search().current_plane();
  // A step read from the session file has no perceptual distance or holds (never saved):
  // pop_redo gives it this session's.
  session_ = session_->pop_redo();
  inspected_ = -1;
  after_change(before);
  say(MessageKind::kInfo, "redone");
}

void GalleryController::start_over() {
  if (busy()) return;
  const sps::Plane before = session_->search().current_plane();
  Session snapshot = *session_;
  session_->start_over();
  session_->push_redo(std::move(snapshot), false);
  inspected_ = -1;
  after_change(before);
  say(MessageKind::kInfo, "started over: all preference data discarded (Redo brings it back)");
}

void GalleryController::open(const intent::Open& o) {
  if (busy()) return;
  try {
    std::unique_ptr<DesignSpace> space = opener_(o.space);
    const int grid = grid_for(*space, o.grid_size);
    Session fresh(
        session_settings(space->settings(), grid, o.zoom_levels, session_->settings().seed + 1));
    if (has_progress()) keep_old_session_file("");
    const std::string what = space->description();
    const std::string note = fewer_dimensions_note(o.space, *space);
    adopt(std::move(fresh), std::move(space));
    autosave();
    if (note.empty()) {
      say(MessageKind::kSuccess, "opened " + what + "; new search started");
    } else {
      say(MessageKind::kError, "new search started; " + note);
    }
  } catch (const std::exception& e) {
    // The space is opened before anything else changes: the current search goes on as it was.
    say(MessageKind::kError,
        std::string("cannot open ") + e.what() + " -- the current search is unchanged");
  }
}

void GalleryController::resume() {
  if (!pending_resume_) return;
  Session resumed = std::move(*pending_resume_);
  pending_resume_.reset();
  adopt(std::move(resumed), std::move(pending_resume_space_));
  say(MessageKind::kInfo, open_elsewhere_
                              ? "showing the search that is open in another window (read-only "
                                "here: nothing is saved)"
                              : "resumed the previous session");
  if (!pending_redo_problem_.empty()) say(MessageKind::kError, std::move(pending_redo_problem_));
  pending_redo_problem_.clear();
}

void GalleryController::start_new() {
  if (!pending_resume_) return;
  pending_resume_.reset();
  pending_resume_space_.reset();
  keep_old_session_file("");
}

void GalleryController::use_point(const Eigen::VectorXd& given, const std::string& what,
                                  bool onto_holds) {
  if (busy() || worker_.busy()) return;
  if (given.size() != space_->dimensions() || !given.allFinite() || given.minCoeff() < 0.0 ||
      given.maxCoeff() > 1.0) {
    say(MessageKind::kError, what + ": outside the search box");
    return;
  }
  Eigen::VectorXd x = given;
  std::string held_note;
  if (const auto* projector = session_->constraint_projector(); onto_holds && projector) {
    x = projector->project(given);
    held_note = ", moved onto the holds (" + projector->description() + ")";
  }
  const Eigen::VectorXd previous_best = session_->current_best();
  Submission submission;
  submission.chosen = x;
  submission.set_directly = true;
  // The clicks already made on this plane's zoom levels stay preference data.
  submission.extra_comparisons = session_->level_comparisons();
  if ((x - previous_best).norm() > 1e-9) submission.extra_comparisons.push_back({x, previous_best});
  session_->clear_redo();
  ++generation_;
  point_job_ = x;
  point_job_what_ = what + held_note;
  worker_.start(session_->search(), std::move(submission), generation_,
                std::chrono::milliseconds(options_.optimizer_delay_ms), session_->plane_preparer(),
                session_->plane_vetter());
  submitted_generation_ = generation_;
  say(MessageKind::kInfo, what + held_note + ": your choice; computing the next plane...");
}

std::string GalleryController::holds_description() const {
  const auto* projector = session_->constraint_projector();
  return projector != nullptr ? projector->description() : "";
}

// Holds change what the grid shows, not the preference data: the session keeps its search and
// only builds its planes and cells through the projector (Session::set_constraint_projector).
void GalleryController::set_holds(const std::vector<std::string>& holds, bool resumed) {
  if (busy() || worker_.busy()) {
    // After the optimizer's result is in (begin_frame): never discard it.
    deferred_.push_back(intent::SetHolds{holds, resumed});
    return;
  }
  std::shared_ptr<const ConstraintProjector> projector;
  if (!holds.empty()) {
    try {
      projector = measurements_to(*space_, "hold").hold_projector(holds, session_->current_best());
    } catch (const std::exception& e) {
      say(MessageKind::kError, std::string("cannot hold that: ") + e.what());
      return;
    }
  }
  session_->set_constraint_projector(projector);
  holds_ = projector ? holds : std::vector<std::string>{};
  // Redo steps were made under other holds, except those of a resumed session, saved under
  // the very holds held again now.
  if (!resumed) session_->clear_redo();
  ++generation_;
  animation_ = Animation::kNone;
  morph_from_.clear();
  displayed_view_ = session_->view();
  update_display();
  say(MessageKind::kInfo, projector ? "holding " + projector->description() + " in every cell"
                                    : "holds released; all your choices are kept");
}

void GalleryController::go_to_targets(const std::vector<std::string>& targets) {
  if (busy() || worker_.busy()) {
    // After the optimizer's result is in (begin_frame): never discard it.
    deferred_.push_back(intent::GoToTargets{targets});
    return;
  }
  if (targets.empty()) {
    say(MessageKind::kError, "type a value for at least one measurement, then Go");
    return;
  }
  TargetSolve solved;
  try {
    // The typed targets are solved with what is held, so the body found keeps the holds.
    std::vector<std::string> held;
    if (const auto* projector = session_->constraint_projector(); projector != nullptr) {
      held = hold_texts(projector->held_values());
    }
    solved =
        measurements_to(*space_, "aim for").solve_targets(targets, session_->current_best(), held);
  } catch (const std::exception& e) {
    say(MessageKind::kError, e.what());
    return;
  }
  if (!solved.reached) {
    say(MessageKind::kError, solved.message);
    return;
  }
  use_point(solved.x, "the body meeting the targets", false);
  say(MessageKind::kInfo, "targets " + solved.message + "; computing the next plane...");
}

void GalleryController::export_point(const fs::path& path) {
  if (path.empty()) {
    say(MessageKind::kError, "choose a file name (" + space_->export_hint() + ")");
    return;
  }
  try {
    const std::string summary = space_->export_point(shown_point(), path);
    last_export_ = path;
    say(MessageKind::kSuccess, "saved " + summary);
    if (options_.log) std::cout << "saved: " << path.string() << std::endl;
  } catch (const std::exception& e) {
    say(MessageKind::kError, std::string("save failed: ") + e.what());
  }
}

Eigen::VectorXd GalleryController::shown_point() const {
  if (inspected_ >= 0 && inspected_ < session_->planes_done()) {
    return session_->history()[static_cast<std::size_t>(inspected_)].chosen;
  }
  return session_->current_best();
}

int GalleryController::grid_for(const DesignSpace& space, int asked) const {
  if (asked > 0) return asked;
  if (options_.catalogue == nullptr)
    throw std::logic_error("the controller needs a catalogue of spaces for their default grid");
  return options_.catalogue->get(space.settings().kind).grid_size;
}

void GalleryController::follow_cells() {
  if (const SpacePerception* perception = space_->perception(); perception != nullptr) {
    follow_cell_size(*session_, *perception, cell_pixels_);
  }
}

void GalleryController::install_perception() {
  // Before the distance is taken: it compares the grids as they will be framed.
  space_->set_close_ups(options_.close_ups);
  if (const SpacePerception* perception = space_->perception(); perception != nullptr) {
    app::install_perception(*session_, *perception, cell_pixels_, options_.perceptual_zoom);
  }  // else the paper's fixed zoom
}

void GalleryController::adopt(Session session, std::unique_ptr<DesignSpace> space) {
  if (space) {
    space_ = std::move(space);
    ++space_generation_;
  }
  session_ = std::move(session);
  install_perception();
  holds_.clear();
  // A file saved by the previous search is not this search's: saving over it asks again.
  last_export_.clear();
  // A resumed session's holds are held again at the first frame that may (before any from the
  // command line, which then replace them); the space checks them like typed ones.
  if (!session_->saved_holds().empty()) {
    std::vector<std::string> holds = hold_texts(session_->saved_holds());
    deferred_.insert(deferred_.begin(), intent::SetHolds{std::move(holds), true});
  }
  ++generation_;
  inspected_ = -1;
  animation_ = Animation::kNone;
  morph_from_.clear();
  displayed_view_ = session_->view();
  update_display();
}

// What happens to a session file that a new search replaces: session_store's rotation of
// set-aside copies (<name>.previous, .previous.1, ...).
void GalleryController::keep_old_session_file(const std::string& why) {
  // Another window owns the file: it is not this window's to move.
  if (options_.session_path.empty() || open_elsewhere_) return;
  if (writer_) {
    // A save still queued would land after the move (or be the file to move); its outcome
    // counts first.
    writer_->flush();
    if (auto r = writer_->poll()) take_save_result(*r);
  }
  std::error_code ec;
  if (!fs::exists(options_.session_path, ec)) return;
  fs::path aside;
  try {
    aside = set_aside_session(options_.session_path);
  } catch (const std::exception& e) {
    say(MessageKind::kError, (why.empty() ? std::string() : why + "; ") + e.what());
    return;
  }
  session_file_stamp_ = stamp_of(options_.session_path);
  if (writer_) writer_->expect(session_file_stamp_);
  if (!why.empty()) {
    say(MessageKind::kError, why + "; kept it as " + aside.string());
  } else {
    say(MessageKind::kInfo, "new session; the previous one is kept as " + aside.string());
  }
}

void GalleryController::autosave() {
  if (!autosave_enabled_ || pending_resume_) return;
  if (writer_) {
    writer_->save(*session_, options_.session_path);
    return;
  }
  take_save_result(save_session_guarded(*session_, options_.session_path, session_file_stamp_));
}

// What a save did: the stamp to expect next time, the banner, and autosave off after a
// conflict (the file was changed by another window since this one saved it: it is left as it
// is, and this window's state was put beside it).
void GalleryController::take_save_result(const GuardedSave& r) {
  session_file_stamp_ = r.stamp;
  if (r.conflict) {
    autosave_enabled_ = false;
    autosave_status_.failed(
        options_.session_path.string() +
        " was changed by another window since this one saved it; it is left as it is and "
        "autosave is off here; " +
        (r.beside.empty() ? "this window's search could not be saved beside it: " + r.error
                          : "this window's search is saved as " + r.beside.string()));
    say(MessageKind::kError, autosave_status_.error());
    return;
  }
  if (r.saved) {
    autosave_status_.succeeded();
  } else {
    autosave_status_.failed(r.error);
    say(MessageKind::kError, "autosave failed: " + r.error);
  }
}

// After any change of the session: save, and animate from what is on screen to the new grid.
void GalleryController::after_change(const sps::Plane& plane_before) {
  ++generation_;
  autosave();
  animation_start_ = now_;
  if (same_plane(session_->search().current_plane(), plane_before)) {
    view_from_ = displayed_view_;
    view_to_ = session_->view();
    animation_ = Animation::kZoom;
    animation_seconds_ = options_.zoom_seconds;
  } else {
    morph_from_.clear();
    for (const auto& c : displayed_) morph_from_.push_back(c.x);
    view_to_ = session_->view();
    animation_ = Animation::kMorph;
    animation_seconds_ = options_.morph_seconds;
  }
}

void GalleryController::poll_worker() {
  if (auto result = worker_.poll()) install(std::move(*result));
}

void GalleryController::install(SubmitWorker::Result result) {
  if (point_job_) {
    const Eigen::VectorXd x = *point_job_;
    point_job_.reset();
    if (result.generation != generation_) return;
    if (!result.search) {
      say(MessageKind::kError, "the optimizer failed: " + result.error);
      return;
    }
    const sps::Plane before = session_->search().current_plane();
    last_submit_seconds_ = result.seconds;
    session_->adopt_point(x, std::move(*result.search), std::move(result.prepared));
    inspected_ = -1;
    after_change(before);
    say(MessageKind::kSuccess, point_job_what_ + ": now the current best (plane " +
                                   std::to_string(session_->planes_done()) + " done)");
    return;
  }
  if (result.generation != generation_ || !session_->submission_pending()) return;  // stale
  const sps::Plane before = session_->search().current_plane();
  if (!result.search) {
    session_->undo_click();
    after_change(before);
    say(MessageKind::kError,
        "the optimizer failed: " + result.error + " (last click undone; please click again)");
    return;
  }
  last_submit_seconds_ = result.seconds;
  session_->finish_plane(std::move(*result.search), std::move(result.prepared));
  after_change(before);
  char text[96];
  std::snprintf(text, sizeof text, "plane %d done (optimizer %.2f s); here is the next one",
                session_->planes_done(), last_submit_seconds_);
  const std::string note = std::move(finished_plane_note_);
  finished_plane_note_.clear();
  say(MessageKind::kSuccess, note.empty() ? std::string(text) : note + " " + text);
}

void GalleryController::update_display() {
  const int n = session_->settings().grid_size;
  const auto& plane = session_->search().current_plane();
  double alpha = 1.0;
  if (animation_ != Animation::kNone) {
    const double t = animation_seconds_ > 0.0
                         ? std::clamp((now_ - animation_start_) / animation_seconds_, 0.0, 1.0)
                         : 1.0;
    alpha = t * t * (3.0 - 2.0 * t);  // ease in and out
    if (t >= 1.0) animation_ = Animation::kNone;
  }
  const bool held = session_->constraint_projector() != nullptr;
  if (animation_ == Animation::kZoom) {
    displayed_view_ = sps::interpolate_views(view_from_, view_to_, alpha);
    // Holds: between two grids the held plane itself (first-order held); the grid the
    // animation ends on is projected.
    displayed_ = sps::grid_points(held ? session_->shown_plane() : plane, n, displayed_view_);
    return;
  }
  displayed_view_ = session_->view();
  displayed_ =
      held ? session_->cells_at(displayed_view_) : sps::grid_points(plane, n, displayed_view_);
  if (animation_ == Animation::kMorph && morph_from_.size() == displayed_.size()) {
    for (std::size_t i = 0; i < displayed_.size(); ++i) {
      if (morph_from_[i].size() == displayed_[i].x.size()) {
        displayed_[i].x = (1.0 - alpha) * morph_from_[i] + alpha * displayed_[i].x;
      }
    }
  }
}

}  // namespace app
