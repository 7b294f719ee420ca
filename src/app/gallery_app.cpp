#include "app/gallery_app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "app/body_scene.hpp"
#include "app/body_view.hpp"
#include "app/session.hpp"
#include "app/session_store.hpp"
#include "app/worker.hpp"
#include "body/gltf_export.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"
#include "render/body_renderer.hpp"
#include "render/cell_framebuffer.hpp"
#include "render/png_writer.hpp"

namespace app {

namespace {

using Clock = std::chrono::steady_clock;

// Preview and history thumbnail sizes (pixels; shown 1:1). Wide enough for an A-pose.
constexpr int kPreviewW = 260;
constexpr int kPreviewH = 320;
constexpr int kThumbW = 58;
constexpr int kThumbH = 72;
namespace fs = std::filesystem;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void disable_blending(const ImDrawList* /*list*/, const ImDrawCmd* /*cmd*/) {
  glDisable(GL_BLEND);
}

ImTextureID texture_id(GLuint texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture));
}

std::string format_metres(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f cm", m * 100.0);
  return text;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

class GalleryApp {
 public:
  explicit GalleryApp(const GalleryOptions& options) : options_(options) {
    camera_.set_preset(options.view);
    active_preset_ = options.view == render::ViewPreset::kFront  ? 0
                     : options.view == render::ViewPreset::kSide ? 1
                                                                 : 2;
    save_path_ = options.save_path;
  }
  ~GalleryApp() { shutdown(); }

  int run();

 private:
  enum class MessageKind { kInfo, kSuccess, kError };
  enum class Animation { kNone, kZoom, kMorph };

  // Start-up and teardown.
  bool create_window();
  void shutdown();
  bool load_initial_state();
  body::Model load_model_or_default(const std::string& path, int components, std::string& error);

  // Session changes (each one autosaves and starts a transition).
  void click_cell(int col, int row);
  void undo_click();
  void undo_plane();
  void start_over();
  void open_model(const std::string& path, int components, int grid_size, int zoom_levels);
  void adopt_session(Session session, body::Model model);
  void save_gltf();
  void autosave();
  void after_change(const sps::Plane& plane_before);
  void poll_worker();

  // Per frame.
  void update_grid_bodies();
  void render_cells();
  int px(int logical) const;  // logical UI size -> framebuffer pixels
  void draw_ui();
  void draw_toolbar();
  void draw_grid(float size);
  void draw_side_panel();
  void draw_preview(const char* title, BodyView& view, float w, float h);
  void draw_resume_prompt();
  void draw_spinner(ImVec2 centre, float radius);
  void handle_shortcuts();
  void write_screenshot(const fs::path& path);
  void benchmark_step();
  void message(MessageKind kind, std::string text);

  static void on_drop(GLFWwindow* window, int count, const char** paths);
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);

  struct KeyPress {
    int key;
    int mods;
    bool repeat;
  };
  std::vector<KeyPress> key_presses_;
  bool screenshot_requested_ = false;

  GalleryOptions options_;
  GLFWwindow* window_ = nullptr;
  bool imgui_ready_ = false;

  body::Model model_;
  std::optional<Session> session_;
  std::optional<Session> pending_resume_;  // offered at start-up
  body::Model pending_resume_model_;
  SubmitWorker worker_;
  int generation_ = 0;
  int submitted_generation_ = -1;
  double last_submit_seconds_ = 0.0;
  bool autosave_enabled_ = true;
  AutosaveStatus autosave_status_;  // shown until a save succeeds again

  std::unique_ptr<render::BodyRenderer> renderer_;
  render::Camera camera_;
  int active_preset_ = 0;  // index into the view buttons, -1 after a free orbit
  int camera_version_ = 0;
  std::vector<BodyView> cells_;
  BodyView best_view_;
  BodyView start_view_;
  BodyView inspect_view_;
  std::vector<BodyView> history_views_;
  int inspected_ = -1;  // history index shown in the preview, -1 = current best
  int cell_pixels_ = 300;
  int hovered_cell_ = -1;

  Animation animation_ = Animation::kNone;
  Clock::time_point animation_start_;
  double animation_seconds_ = 1.5;
  sps::GridView view_from_, view_to_, displayed_view_;
  std::vector<Eigen::VectorXd> morph_from_;

  std::string save_path_;
  std::string model_path_field_;
  int components_field_ = 10;
  int grid_field_ = 3;
  int zoom_levels_field_ = 4;
  std::string message_;
  MessageKind message_kind_ = MessageKind::kInfo;
  std::string pending_drop_;

  // Measurements.
  long frame_ = 0;
  bool first_grid_shown_ = false;
  double launch_to_first_grid_ = 0.0;
  std::vector<double> animation_frame_ms_;
  std::vector<double> body_ms_;     // body evaluation + upload per animation frame
  std::vector<double> cells_ms_;    // UI build + cell rendering (GL finished) per frame
  std::vector<double> present_ms_;  // ImGui drawing of the window + swap
  std::vector<double> swap_ms_;     // of which the swap
  int benchmark_clicks_done_ = 0;
  Clock::time_point last_frame_start_;
  bool previous_frame_zoomed_ = false;
  bool quit_ = false;
};

void GalleryApp::message(MessageKind kind, std::string text) {
  message_kind_ = kind;
  message_ = std::move(text);
  if (kind == MessageKind::kError) {
    std::cerr << "sequential-gallery: " << message_ << std::endl;
  } else {
    std::cout << "[gallery] " << message_ << std::endl;
  }
}

bool GalleryApp::create_window() {
  glfwSetErrorCallback([](int code, const char* text) {
    std::cerr << "GLFW error " << code << ": " << text << "\n";
  });
  if (glfwInit() != GLFW_TRUE) {
    std::cerr << "sequential-gallery: cannot open a window (no display? set DISPLAY or run under "
                 "xvfb-run); headless rendering: `sequential-gallery render`\n";
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(options_.window_width, options_.window_height, "Sequential Gallery",
                             nullptr, nullptr);
  if (window_ == nullptr) {
    std::cerr << "sequential-gallery: cannot create an OpenGL 3.3 core window\n";
    return false;
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options_.benchmark_clicks > 0 ? 0 : 1);
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, &GalleryApp::on_drop);
  glfwSetKeyCallback(window_, &GalleryApp::on_key);  // before ImGui, which chains to it

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written into the working directory
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.FrameRounding = 3.0f;
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ready_ = true;
  renderer_ = std::make_unique<render::BodyRenderer>();
  return true;
}

void GalleryApp::shutdown() {
  if (worker_.busy()) worker_.wait();  // let a running submit finish; its result is dropped
  cells_.clear();
  history_views_.clear();
  best_view_ = BodyView{};
  start_view_ = BodyView{};
  inspect_view_ = BodyView{};
  renderer_.reset();
  if (imgui_ready_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    imgui_ready_ = false;
  }
  if (window_ != nullptr) {
    glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
  }
}

void GalleryApp::on_drop(GLFWwindow* window, int count, const char** paths) {
  auto* self = static_cast<GalleryApp*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && count > 0) self->pending_drop_ = paths[0];
}

body::Model GalleryApp::load_model_or_default(const std::string& path, int components,
                                              std::string& error) {
  if (!path.empty()) {
    try {
      return body::load_model(path, components);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  return body::load_default_model(components);
}

bool GalleryApp::load_initial_state() {
  std::string error;
  try {
    model_ = load_model_or_default(options_.model_path.value_or(""), options_.components, error);
  } catch (const std::exception& e) {
    std::cerr << "sequential-gallery: no body model: " << (error.empty() ? "" : error + "; ")
              << e.what() << "\n";
    return false;
  }
  if (!error.empty()) message(MessageKind::kError, error + " (showing the default model)");
  SessionSettings settings;
  settings.model_path = error.empty() ? options_.model_path.value_or("") : "";
  settings.components = model_.component_count();
  settings.grid_size = options_.grid_size;
  settings.zoom_levels = options_.zoom_levels;
  settings.seed = options_.seed;
  session_.emplace(settings);
  model_path_field_ = settings.model_path;

  LoadResult loaded = load_session(options_.session_path);
  if (!loaded.problem.empty()) {
    message(MessageKind::kError, loaded.problem);
    if (loaded.set_aside.empty()) {
      autosave_enabled_ = false;  // never overwrite a file we could not read or move
      message_ += " -- autosave is OFF for this run";
    }
  }
  if (loaded.session) {
    const auto& s = loaded.session->settings();
    std::string model_error;
    body::Model resumed_model;
    try {
      resumed_model = s.model_path.empty() ? body::load_default_model(s.components)
                                           : body::load_model(s.model_path, s.components);
      if (resumed_model.component_count() != s.components) {
        throw std::runtime_error("the model now has " +
                                 std::to_string(resumed_model.component_count()) +
                                 " components, the session " + std::to_string(s.components));
      }
    } catch (const std::exception& e) {
      model_error = e.what();
    }
    if (!model_error.empty()) {
      std::string kept;
      try {
        kept = "kept it as " + set_aside_session(options_.session_path).string();
      } catch (const std::exception& e) {
        kept = e.what();
      }
      message(MessageKind::kError,
              "cannot resume the previous session: " + model_error + "; " + kept);
    } else if (options_.resume == GalleryOptions::Resume::kYes) {
      adopt_session(std::move(*loaded.session), std::move(resumed_model));
      message(MessageKind::kInfo, "resumed the session from " + options_.session_path.string());
    } else if (options_.resume == GalleryOptions::Resume::kAsk) {
      pending_resume_ = std::move(loaded.session);
      pending_resume_model_ = std::move(resumed_model);
    } else {
      try {
        set_aside_session(options_.session_path);
      } catch (const std::exception& e) {
        message(MessageKind::kError, e.what());
      }
    }
  }
  components_field_ = session_->settings().components;
  grid_field_ = session_->settings().grid_size;
  zoom_levels_field_ = session_->settings().zoom_levels;
  displayed_view_ = session_->view();
  return true;
}

void GalleryApp::adopt_session(Session session, body::Model model) {
  model_ = std::move(model);
  session_ = std::move(session);
  ++generation_;
  cells_.clear();
  history_views_.clear();
  best_view_ = BodyView{};
  start_view_ = BodyView{};
  inspect_view_ = BodyView{};
  inspected_ = -1;
  animation_ = Animation::kNone;
  displayed_view_ = session_->view();
  model_path_field_ = session_->settings().model_path;
  components_field_ = session_->settings().components;
  grid_field_ = session_->settings().grid_size;
  zoom_levels_field_ = session_->settings().zoom_levels;
}

void GalleryApp::autosave() {
  if (!autosave_enabled_ || pending_resume_) return;
  try {
    save_session(*session_, options_.session_path);
    autosave_status_.succeeded();
  } catch (const std::exception& e) {
    autosave_status_.failed(e.what());
    message(MessageKind::kError, std::string("autosave failed: ") + e.what());
  }
}

// After any change of the session: save, and animate from what is on screen to the new grid.
void GalleryApp::after_change(const sps::Plane& plane_before) {
  ++generation_;
  autosave();
  const auto& plane = session_->search().current_plane();
  const bool same_plane = plane.c.size() == plane_before.c.size() && plane.c == plane_before.c &&
                          plane.u == plane_before.u && plane.v == plane_before.v;
  animation_start_ = Clock::now();
  if (same_plane) {
    view_from_ = displayed_view_;
    view_to_ = session_->view();
    animation_ = Animation::kZoom;
    animation_seconds_ = options_.zoom_seconds;
  } else {
    morph_from_.clear();
    for (const auto& c : cells_) morph_from_.push_back(c.x);
    view_to_ = session_->view();
    animation_ = Animation::kMorph;
    animation_seconds_ = 0.6;
  }
}

void GalleryApp::click_cell(int col, int row) {
  if (pending_resume_) return;
  if (session_->submission_pending()) {
    message(MessageKind::kInfo, "computing the next plane, one moment...");
    return;
  }
  const sps::Plane before = session_->search().current_plane();
  const ClickResult r = session_->click({col, row});
  if (r == ClickResult::kIgnored) return;
  inspected_ = -1;
  after_change(before);
  std::cout << "[gallery] click cell " << row * session_->settings().grid_size + col + 1
            << " (plane " << session_->planes_done() + 1 << ", level "
            << session_->clicks_on_plane() << ")" << std::endl;
  if (r == ClickResult::kPlaneFinished) {
    message(MessageKind::kInfo, "choice submitted; computing the next plane...");
  }
}

void GalleryApp::undo_click() {
  const sps::Plane before = session_->search().current_plane();
  if (session_->undo_click()) {
    after_change(before);
    message(MessageKind::kInfo, "undid the last click");
  } else {
    message(MessageKind::kInfo, "nothing to undo");
  }
}

void GalleryApp::undo_plane() {
  const sps::Plane before = session_->search().current_plane();
  if (session_->undo_plane()) {
    inspected_ = -1;
    after_change(before);
    message(MessageKind::kInfo, "undid the last plane");
  } else {
    message(MessageKind::kInfo, "nothing to undo");
  }
}

void GalleryApp::start_over() {
  const sps::Plane before = session_->search().current_plane();
  session_->start_over();
  inspected_ = -1;
  history_views_.clear();
  after_change(before);
  message(MessageKind::kInfo, "started over: all preference data discarded");
}

void GalleryApp::open_model(const std::string& path, int components, int grid_size,
                            int zoom_levels) {
  try {
    body::Model model =
        path.empty() ? body::load_default_model(components) : body::load_model(path, components);
    SessionSettings settings;
    settings.model_path = path;
    settings.components = model.component_count();
    settings.grid_size = grid_size;
    settings.zoom_levels = zoom_levels;
    settings.seed = session_->settings().seed + 1;
    Session fresh(settings);
    const std::string name = model.name;
    adopt_session(std::move(fresh), std::move(model));
    autosave();
    message(MessageKind::kSuccess,
            "opened " + (path.empty() ? std::string("the default model") : path) + " (" + name +
                ", " + std::to_string(settings.components) + " components); new search started");
  } catch (const std::exception& e) {
    message(MessageKind::kError, std::string("cannot open model: ") + e.what());
  }
}

void GalleryApp::save_gltf() {
  if (save_path_.empty()) {
    message(MessageKind::kError, "enter a file name ending in .glb or .gltf");
    return;
  }
  const Eigen::VectorXd x = inspected_ >= 0
                                ? session_->history()[static_cast<size_t>(inspected_)].chosen
                                : session_->current_best();
  try {
    body::export_gltf(model_, body::betas_from_unit(x), save_path_);
    std::error_code ec;
    const auto bytes = fs::file_size(save_path_, ec);
    std::ostringstream text;
    text << "saved " << fs::absolute(save_path_).string();
    if (!ec) text << " (" << (bytes + 512) / 1024 << " KiB)";
    message(MessageKind::kSuccess, text.str());
    std::cout << "saved glTF: " << save_path_ << std::endl;
  } catch (const std::exception& e) {
    message(MessageKind::kError, std::string("save failed: ") + e.what());
  }
}

void GalleryApp::poll_worker() {
  if (session_->submission_pending() && !worker_.busy() && submitted_generation_ != generation_ &&
      !pending_resume_) {
    worker_.start(session_->search(), session_->submission(), generation_,
                  std::chrono::milliseconds(options_.optimizer_delay_ms));
    submitted_generation_ = generation_;
  }
  auto result = worker_.poll();
  if (!result) return;
  if (result->generation != generation_ || !session_->submission_pending()) return;  // stale
  if (!result->search) {
    const sps::Plane before = session_->search().current_plane();
    session_->undo_click();
    after_change(before);
    message(MessageKind::kError,
            "the optimizer failed: " + result->error + " (last click undone; please click again)");
    return;
  }
  last_submit_seconds_ = result->seconds;
  const sps::Plane before = session_->search().current_plane();
  session_->finish_plane(std::move(*result->search));
  after_change(before);
  char text[96];
  std::snprintf(text, sizeof text, "plane %d done (optimizer %.2f s); here is the next one",
                session_->planes_done(), last_submit_seconds_);
  message(MessageKind::kSuccess, text);
}

void GalleryApp::update_grid_bodies() {
  const int n = session_->settings().grid_size;
  const auto& plane = session_->search().current_plane();
  double alpha = 1.0;
  if (animation_ != Animation::kNone) {
    const double t = std::clamp(seconds_since(animation_start_) / animation_seconds_, 0.0, 1.0);
    alpha = t * t * (3.0 - 2.0 * t);  // ease in and out
    if (t >= 1.0) animation_ = Animation::kNone;
  }
  std::vector<sps::GridPoint> points;
  if (animation_ == Animation::kZoom) {
    displayed_view_ = sps::interpolate_views(view_from_, view_to_, alpha);
    points = sps::grid_points(plane, n, displayed_view_);
  } else {
    displayed_view_ = session_->view();
    points = sps::grid_points(plane, n, displayed_view_);
    if (animation_ == Animation::kMorph && morph_from_.size() == points.size()) {
      for (size_t i = 0; i < points.size(); ++i) {
        if (morph_from_[i].size() == points[i].x.size()) {
          points[i].x = (1.0 - alpha) * morph_from_[i] + alpha * points[i].x;
        }
      }
    }
  }
  if (cells_.size() != points.size()) {
    cells_.clear();
    cells_.resize(points.size());
  }
  for (size_t i = 0; i < points.size(); ++i) {
    cells_[i].set_body(model_, points[i].x, false);
    cells_[i].clamped = points[i].clamped;
  }
  // Previews and history.
  const bool inspecting = inspected_ >= 0 && inspected_ < session_->planes_done();
  if (!inspecting) inspected_ = -1;
  best_view_.set_body(model_, session_->current_best(), true);
  start_view_.set_body(model_, session_->start_point(), true);
  if (inspecting) {
    inspect_view_.set_body(model_, session_->history()[static_cast<size_t>(inspected_)].chosen,
                           true);
  }
  const auto& history = session_->history();
  if (history_views_.size() != history.size()) history_views_.resize(history.size());
  for (size_t i = 0; i < history.size(); ++i) {
    history_views_[i].set_body(model_, history[i].chosen, false);
  }
}

int GalleryApp::px(int logical) const {
  const float dpi = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
  return static_cast<int>(std::lround(dpi * static_cast<float>(logical)));
}

void GalleryApp::render_cells() {
  const render::BodyStyle style = cell_style();
  // While bodies morph, cells render without multisampling (llvmpipe pays 4x per sample);
  // the settled grid is drawn again with full antialiasing.
  const bool fast = animation_ != Animation::kNone || ImGui::IsMouseDragging(ImGuiMouseButton_Left);
  for (auto& cell : cells_) {
    cell.draw(*renderer_, camera_, camera_version_, cell_pixels_, cell_pixels_, options_.samples,
              style, fast, options_.animation_scale, options_.animation_samples > 0);
  }
  render::BodyStyle preview = style;
  best_view_.draw(*renderer_, camera_, camera_version_, px(kPreviewW), px(kPreviewH),
                  options_.samples, preview);
  if (inspected_ >= 0) {
    inspect_view_.draw(*renderer_, camera_, camera_version_, px(kPreviewW), px(kPreviewH),
                       options_.samples, preview);
  }
  preview.albedo = {0.62f, 0.66f, 0.72f};
  start_view_.draw(*renderer_, camera_, camera_version_, px(kPreviewW), px(kPreviewH),
                   options_.samples, preview);
  render::BodyStyle thumb = style;
  for (auto& h : history_views_) {
    h.draw(*renderer_, camera_, camera_version_, px(kThumbW), px(kThumbH), options_.samples, thumb);
  }
}

void GalleryApp::draw_spinner(ImVec2 centre, float radius) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float t = static_cast<float>(ImGui::GetTime());
  const float start = t * 6.0f;
  dl->PathArcTo(centre, radius, start, start + 4.2f, 32);
  dl->PathStroke(IM_COL32(80, 160, 255, 255), 0, radius * 0.25f);
}

void GalleryApp::draw_toolbar() {
  const bool busy = session_->submission_pending();
  ImGui::BeginDisabled(busy);
  if (ImGui::Button("Undo click")) undo_click();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Backspace / Ctrl+Z");
  ImGui::SameLine();
  if (ImGui::Button("Undo plane")) undo_plane();
  ImGui::SameLine();
  if (ImGui::Button("Start over")) ImGui::OpenPopup("Start over?");
  ImGui::EndDisabled();
  if (ImGui::BeginPopupModal("Start over?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("Discard all preference data and the history?");
    if (ImGui::Button("Start over")) {
      start_over();
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  ImGui::TextUnformatted("View:");
  const render::ViewPreset presets[] = {render::ViewPreset::kFront, render::ViewPreset::kSide,
                                        render::ViewPreset::kThreeQuarter};
  const char* labels[] = {"Front", "Side", "3/4"};
  for (int i = 0; i < 3; ++i) {
    ImGui::SameLine();
    if (ImGui::RadioButton(labels[i], active_preset_ == i)) {
      camera_.set_preset(presets[i]);
      active_preset_ = i;
      ++camera_version_;
    }
  }
  ImGui::SameLine();
  ImGui::TextDisabled("|");
  ImGui::SameLine();
  const auto& s = session_->settings();
  ImGui::Text("Plane %d   click %d of %d", session_->planes_done() + 1,
              std::min(session_->clicks_on_plane() + (busy ? 0 : 1), s.zoom_levels), s.zoom_levels);
}

void GalleryApp::draw_grid(float size) {
  const int n = session_->settings().grid_size;
  const float gap = 6.0f;
  const float cell = std::floor((size - gap * static_cast<float>(n - 1)) / static_cast<float>(n));
  // Framebuffers are sized in physical pixels so cells stay sharp on high-DPI screens.
  const float dpi = std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x);
  cell_pixels_ = static_cast<int>(
      std::lround(dpi * (options_.cell_size > 0 ? static_cast<float>(options_.cell_size)
                                                : std::max(32.0f, cell))));
  const float shown = options_.cell_size > 0 ? static_cast<float>(options_.cell_size) : cell;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImGuiIO& io = ImGui::GetIO();
  hovered_cell_ = -1;
  const bool busy = session_->submission_pending();
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      const int index = row * n + col;
      const ImVec2 p0(origin.x + static_cast<float>(col) * (shown + gap),
                      origin.y + static_cast<float>(row) * (shown + gap));
      const ImVec2 p1(p0.x + shown, p0.y + shown);
      ImGui::SetCursorScreenPos(p0);
      ImGui::PushID(index);
      const bool pressed = ImGui::InvisibleButton("cell", ImVec2(shown, shown));
      const bool hovered = ImGui::IsItemHovered();
      const bool dragging = ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left);
      ImGui::PopID();
      if (dragging && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
        camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
        active_preset_ = -1;  // a free orbit
        ++camera_version_;
      }
      const float drag_threshold = io.MouseDragThreshold * io.MouseDragThreshold;
      if (pressed && io.MouseDragMaxDistanceSqr[0] < drag_threshold) click_cell(col, row);
      if (options_.report_layout && frame_ == 3) {
        std::cout << "[layout] cell " << index + 1 << " " << p0.x << " " << p0.y << " " << shown
                  << std::endl;
      }
      if (static_cast<size_t>(index) < cells_.size()) {
        const BodyView& view = cells_[static_cast<size_t>(index)];
        const auto uv = view.uv();
        const ImVec2 uv0(uv[0], uv[1]), uv1(uv[2], uv[3]);
        // Cells are opaque: drawing them without blending saves a software rasterizer
        // reading back 9 x 400 x 400 pixels every frame.
        dl->AddCallback(&disable_blending, nullptr);
        dl->AddImage(texture_id(view.fbo.texture()), p0, p1, uv0, uv1);
        dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
      }
      if (hovered && !busy) {
        hovered_cell_ = index;
        dl->AddRectFilled(p0, p1, IM_COL32(255, 255, 255, 22));
        dl->AddRect(p0, p1, IM_COL32(255, 190, 60, 255), 0.0f, 0, 4.0f);
      } else {
        dl->AddRect(p0, p1, IM_COL32(40, 40, 48, 255), 0.0f, 0, 1.0f);
      }
      if (n == 3) {
        char label[16];
        std::snprintf(label, sizeof label, "%d", index + 1);
        dl->AddText(ImVec2(p0.x + 8, p0.y + 6), IM_COL32(60, 60, 70, 220), label);
      }
      if (static_cast<size_t>(index) < cells_.size() &&
          cells_[static_cast<size_t>(index)].clamped) {
        dl->AddText(ImVec2(p0.x + 8, p1.y - 22), IM_COL32(200, 90, 20, 255), "at the bound");
      }
    }
  }
  const float total = static_cast<float>(n) * shown + static_cast<float>(n - 1) * gap;
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(ImVec2(total, total));
  if (busy) {
    const ImVec2 c(origin.x + total * 0.5f, origin.y + total * 0.5f);
    dl->AddRectFilled(ImVec2(c.x - 170, c.y - 46), ImVec2(c.x + 170, c.y + 46),
                      IM_COL32(20, 22, 28, 200), 8.0f);
    draw_spinner(ImVec2(c.x - 130, c.y), 18.0f);
    dl->AddText(ImVec2(c.x - 100, c.y - 8), IM_COL32(235, 235, 240, 255),
                "Computing the next plane...");
  }
}

void GalleryApp::draw_preview(const char* title, BodyView& view, float w, float h) {
  ImGui::BeginGroup();
  ImGui::TextUnformatted(title);
  ImGui::Image(texture_id(view.fbo.texture()), ImVec2(w, h), ImVec2(0, 1), ImVec2(1, 0));
  ImGui::EndGroup();
}

void GalleryApp::draw_side_panel() {
  BodyView& shown = inspected_ >= 0 ? inspect_view_ : best_view_;
  char title[64];
  if (inspected_ >= 0) {
    std::snprintf(title, sizeof title, "Plane %d choice", inspected_ + 1);
  } else {
    std::snprintf(title, sizeof title, "Current best");
  }
  draw_preview(title, shown, kPreviewW, kPreviewH);
  ImGui::SameLine();
  draw_preview("Started from", start_view_, kPreviewW, kPreviewH);
  if (inspected_ >= 0) {
    if (ImGui::Button("Back to current best")) inspected_ = -1;
  }
  if (ImGui::BeginTable("measurements", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn(inspected_ >= 0 ? "Chosen" : "Current");
    ImGui::TableSetupColumn("Start");
    ImGui::TableHeadersRow();
    const body::Measurements a = shown.measurements.value_or(body::Measurements{});
    const body::Measurements b = start_view_.measurements.value_or(body::Measurements{});
    const std::pair<const char*, std::pair<double, double>> rows[] = {
        {"Height", {a.height, b.height}},
        {"Chest", {a.chest, b.chest}},
        {"Waist", {a.waist, b.waist}},
        {"Hips", {a.hips, b.hips}}};
    for (const auto& r : rows) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(r.first);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(format_metres(r.second.first).c_str());
      ImGui::TableSetColumnIndex(2);
      ImGui::TextUnformatted(format_metres(r.second.second).c_str());
    }
    ImGui::EndTable();
  }

  ImGui::Separator();
  ImGui::Text("History: %d finished plane%s (click to inspect)", session_->planes_done(),
              session_->planes_done() == 1 ? "" : "s");
  ImGui::BeginChild("history", ImVec2(0, 128), true, ImGuiWindowFlags_HorizontalScrollbar);
  for (size_t i = 0; i < history_views_.size(); ++i) {
    if (i > 0) ImGui::SameLine();
    ImGui::PushID(static_cast<int>(i));
    ImGui::BeginGroup();
    const bool selected = inspected_ == static_cast<int>(i);
    if (selected) ImGui::PushStyleColor(ImGuiCol_Button, IM_COL32(255, 170, 40, 255));
    if (ImGui::ImageButton(texture_id(history_views_[i].fbo.texture()), ImVec2(kThumbW, kThumbH),
                           ImVec2(0, 1), ImVec2(1, 0), 2)) {
      inspected_ = selected ? -1 : static_cast<int>(i);
    }
    if (selected) ImGui::PopStyleColor();
    ImGui::Text("#%zu", i + 1);
    ImGui::EndGroup();
    ImGui::PopID();
  }
  if (history_views_.empty()) ImGui::TextDisabled("chosen bodies of finished planes appear here");
  ImGui::EndChild();

  ImGui::Separator();
  ImGui::TextUnformatted("Save the shown body as glTF");
  ImGui::SetNextItemWidth(300);
  ImGui::InputText("##savepath", &save_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save glTF...")) save_gltf();

  ImGui::Separator();
  ImGui::TextUnformatted("Body model (.npz; empty = default; or drop a file here)");
  ImGui::SetNextItemWidth(300);
  ImGui::InputText("##modelpath", &model_path_field_);
  ImGui::SetNextItemWidth(120);
  ImGui::InputInt("components", &components_field_);
  components_field_ = std::clamp(components_field_, 1, sps::kMaxSearchDims);
  ImGui::TextUnformatted("Grid");
  ImGui::SameLine();
  ImGui::RadioButton("3x3", &grid_field_, 3);
  ImGui::SameLine();
  ImGui::RadioButton("5x5", &grid_field_, 5);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::InputInt("clicks/plane", &zoom_levels_field_);
  zoom_levels_field_ = std::clamp(zoom_levels_field_, 1, 8);
  ImGui::BeginDisabled(session_->submission_pending());
  if (ImGui::Button("Open / apply (starts a new search)")) {
    open_model(model_path_field_, components_field_, grid_field_, zoom_levels_field_);
  }
  ImGui::EndDisabled();

  ImGui::Separator();
  ImGui::TextDisabled("Model: %s (%d components)", model_.name.c_str(), model_.component_count());
  ImGui::TextDisabled("Session: %s%s", options_.session_path.string().c_str(),
                      autosave_enabled_ ? "" : " (autosave OFF)");
  if (autosave_status_.failing()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.3f, 0.25f, 1));
    ImGui::TextWrapped(
        "AUTOSAVE IS FAILING - new clicks are not saved (the last good file is "
        "kept): %s",
        autosave_status_.error().c_str());
    ImGui::PopStyleColor();
  }
  ImGui::TextDisabled("Keys: 1-9 pick a cell, Backspace/Ctrl+Z undo, Ctrl+S save");
  ImGui::TextDisabled("Drag a cell to orbit all bodies");
  if (!message_.empty()) {
    const ImVec4 colour = message_kind_ == MessageKind::kError     ? ImVec4(1.0f, 0.45f, 0.4f, 1)
                          : message_kind_ == MessageKind::kSuccess ? ImVec4(0.5f, 0.9f, 0.5f, 1)
                                                                   : ImVec4(0.85f, 0.85f, 0.9f, 1);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
  }
}

void GalleryApp::draw_resume_prompt() {
  if (!pending_resume_) return;
  if (!ImGui::IsPopupOpen("Resume session?")) ImGui::OpenPopup("Resume session?");
  if (ImGui::BeginPopupModal("Resume session?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    const auto& s = *pending_resume_;
    ImGui::Text("A previous session was found: %s", options_.session_path.string().c_str());
    ImGui::Text("Model: %s, %d components, %d finished plane(s), %d click(s) on the current plane",
                s.settings().model_path.empty() ? "default" : s.settings().model_path.c_str(),
                s.settings().components, s.planes_done(), s.clicks_on_plane());
    if (ImGui::Button("Resume", ImVec2(140, 0))) {
      Session resumed = std::move(*pending_resume_);
      pending_resume_.reset();
      adopt_session(std::move(resumed), std::move(pending_resume_model_));
      message(MessageKind::kInfo, "resumed the previous session");
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Start new", ImVec2(140, 0))) {
      pending_resume_.reset();
      try {
        message(MessageKind::kInfo, "new session; the previous one is kept as " +
                                        set_aside_session(options_.session_path).string());
      } catch (const std::exception& e) {
        message(MessageKind::kError, e.what());
      }
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

// Keys come from our own GLFW callback (ImGui's backend chains to it), queued per event:
// ImGui 1.86 keeps only key states, so a press and release inside one frame (as scripted
// input or a fast typist produces) would be lost.
void GalleryApp::on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  auto* self = static_cast<GalleryApp*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && (action == GLFW_PRESS || action == GLFW_REPEAT)) {
    self->key_presses_.push_back({key, mods, action == GLFW_REPEAT});
  }
}

void GalleryApp::handle_shortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  std::vector<KeyPress> presses;
  presses.swap(key_presses_);
  if (pending_resume_) return;
  for (const KeyPress& p : presses) {
    const bool ctrl = (p.mods & GLFW_MOD_CONTROL) != 0;
    if (ctrl && p.key == GLFW_KEY_S && !p.repeat) {
      save_gltf();
      continue;
    }
    if (p.key == GLFW_KEY_F12 && !options_.screenshot_path.empty()) {
      screenshot_requested_ = true;
      continue;
    }
    if (io.WantTextInput) continue;  // typing into a path field
    const bool busy = session_->submission_pending();
    if ((ctrl && p.key == GLFW_KEY_Z) || (!ctrl && p.key == GLFW_KEY_BACKSPACE)) {
      if (!busy) undo_click();
      continue;
    }
    if (!ctrl && !p.repeat && session_->settings().grid_size == 3) {
      int k = -1;
      if (p.key >= GLFW_KEY_1 && p.key <= GLFW_KEY_9) k = p.key - GLFW_KEY_1;
      if (p.key >= GLFW_KEY_KP_1 && p.key <= GLFW_KEY_KP_9) k = p.key - GLFW_KEY_KP_1;
      if (k >= 0) {
        click_cell(k % 3, k / 3);
      }
    }
  }
}

void GalleryApp::draw_ui() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("Sequential Gallery", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoBackground);  // glClear paints it, far cheaper
  const float side_width = 2.0f * kPreviewW + 24.0f;
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float toolbar_height = ImGui::GetFrameHeightWithSpacing();
  const int n = session_->settings().grid_size;
  const float fixed_grid = static_cast<float>(n * options_.cell_size + (n - 1) * 6);
  const float grid_size = options_.cell_size > 0
                              ? fixed_grid
                              : std::min(avail.x - side_width, avail.y - toolbar_height);
  // The side panel sits right beside the grid and takes the rest of the width.
  const float left_width = std::max({grid_size, 660.0f, 96.0f});
  ImGui::BeginChild("left", ImVec2(std::min(left_width, avail.x - 200.0f), 0), false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  draw_toolbar();
  const ImVec2 grid_avail = ImGui::GetContentRegionAvail();
  draw_grid(std::max(96.0f, std::min(grid_avail.x, grid_avail.y)));
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginChild("right", ImVec2(0, 0), false);
  draw_side_panel();
  ImGui::EndChild();
  draw_resume_prompt();
  ImGui::End();
}

void GalleryApp::write_screenshot(const fs::path& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  std::vector<std::uint8_t> pixels(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  for (size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 255;
  try {
    render::write_png(path, w, h, pixels);
    std::cout << "screenshot: " << path.string() << std::endl;
  } catch (const std::exception& e) {
    message(MessageKind::kError, e.what());
  }
}

void GalleryApp::benchmark_step() {
  if (options_.benchmark_clicks <= 0 || !first_grid_shown_) return;
  if (animation_ != Animation::kNone || session_->submission_pending()) return;
  if (benchmark_clicks_done_ >= options_.benchmark_clicks) {
    const double median = percentile(animation_frame_ms_, 0.5);
    const double p95 = percentile(animation_frame_ms_, 0.95);
    const double worst =
        animation_frame_ms_.empty()
            ? 0.0
            : *std::max_element(animation_frame_ms_.begin(), animation_frame_ms_.end());
    const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    std::printf("renderer: %s\n", gl_renderer != nullptr ? gl_renderer : "?");
    std::printf("model: %s (%d vertices, %d components)\n", model_.name.c_str(),
                model_.vertex_count(), model_.component_count());
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window_, &fb_w, &fb_h);
    std::printf(
        "grid: %dx%d cells of %dx%d px, MSAA %d samples at rest; while animating %s at %.2f "
        "resolution; window %dx%d\n",
        session_->settings().grid_size, session_->settings().grid_size, cell_pixels_, cell_pixels_,
        options_.samples, options_.animation_samples > 0 ? "MSAA" : "no MSAA",
        static_cast<double>(options_.animation_scale), fb_w, fb_h);
    std::printf("launch to first grid: %.0f ms\n", launch_to_first_grid_ * 1000.0);
    std::printf("zoom animation frames: %zu over %d clicks\n", animation_frame_ms_.size(),
                benchmark_clicks_done_);
    std::printf("frame time median: %.1f ms  p95: %.1f ms  max: %.1f ms\n", median, p95, worst);
    if (options_.benchmark_breakdown) {
      std::printf(
          "  medians: body evaluation + upload %.1f ms, UI + 9 cells rendered %.1f ms, "
          "window drawn + swapped %.1f ms (swap %.1f ms)\n",
          percentile(body_ms_, 0.5), percentile(cells_ms_, 0.5), percentile(present_ms_, 0.5),
          percentile(swap_ms_, 0.5));
    } else {
      std::printf("  (--breakdown times the phases of a frame; it adds glFinish calls)\n");
    }
    std::printf("last optimizer submit: %.2f s (worker thread)\n", last_submit_seconds_);
    std::fflush(stdout);
    quit_ = true;
    return;
  }
  const int n = session_->settings().grid_size;
  static const int pattern[][2] = {{0, 0}, {2, 1}, {1, 2}, {2, 2}, {0, 1}, {1, 0}, {2, 0}, {0, 2}};
  const auto& p = pattern[benchmark_clicks_done_ % 8];
  click_cell(std::min(p[0], n - 1), std::min(p[1], n - 1));
  ++benchmark_clicks_done_;
}

int GalleryApp::run() {
  if (!load_initial_state()) return 1;
  if (!create_window()) return 1;
  last_frame_start_ = Clock::now();
  while (!glfwWindowShouldClose(window_) && !quit_) {
    const bool active = animation_ != Animation::kNone || session_->submission_pending() ||
                        !first_grid_shown_ || options_.benchmark_clicks > 0 ||
                        options_.screenshot_after_frames >= 0 || ImGui::IsAnyMouseDown();
    if (active) {
      glfwPollEvents();
    } else {
      glfwWaitEventsTimeout(0.25);
    }
    const auto frame_start = Clock::now();
    const double frame_ms =
        std::chrono::duration<double, std::milli>(frame_start - last_frame_start_).count();
    if (previous_frame_zoomed_ && options_.benchmark_clicks > 0) {
      animation_frame_ms_.push_back(frame_ms);
    }
    last_frame_start_ = frame_start;

    if (!pending_drop_.empty()) {
      model_path_field_ = pending_drop_;
      pending_drop_.clear();
      open_model(model_path_field_, components_field_, grid_field_, zoom_levels_field_);
    }
    poll_worker();
    benchmark_step();

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_shortcuts();
    previous_frame_zoomed_ = animation_ == Animation::kZoom;
    const auto t0 = Clock::now();
    update_grid_bodies();
    const auto t1 = Clock::now();
    draw_ui();  // decides the cell size; clicks start animations for the next frame
    render_cells();
    if (options_.benchmark_breakdown) glFinish();  // attribute GL time to the cells
    const auto t2 = Clock::now();
    if (previous_frame_zoomed_ && options_.benchmark_breakdown) {
      body_ms_.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      cells_ms_.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    }
    ImGui::Render();
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (options_.benchmark_breakdown) glFinish();
    const auto t3 = Clock::now();
    ++frame_;
    if (frame_ >= 1 && !first_grid_shown_ && !cells_.empty()) {
      first_grid_shown_ = true;
      glFinish();
      launch_to_first_grid_ = seconds_since(options_.launch_time);
      std::cerr << "first grid shown " << static_cast<int>(launch_to_first_grid_ * 1000.0)
                << " ms after launch\n";
    }
    if (screenshot_requested_) {
      screenshot_requested_ = false;
      write_screenshot(options_.screenshot_path);
    }
    if (options_.screenshot_after_frames >= 0 && frame_ == options_.screenshot_after_frames &&
        !options_.screenshot_path.empty()) {
      write_screenshot(options_.screenshot_path);
      if (options_.quit_after_screenshot) quit_ = true;
    }
    glfwSwapBuffers(window_);
    if (previous_frame_zoomed_ && options_.benchmark_breakdown) {
      glFinish();
      present_ms_.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t2).count());
      swap_ms_.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t3).count());
    }
  }
  if (session_ && !pending_resume_) autosave();
  return 0;
}

}  // namespace

int run_gallery(const GalleryOptions& options) {
  GalleryApp app(options);
  return app.run();
}

}  // namespace app
