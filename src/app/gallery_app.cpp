#include "app/gallery_app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <vector>

#include "app/gallery_layout.hpp"
#include "app/gallery_view.hpp"
#include "app/ui_prefs.hpp"
#include "render/png_writer.hpp"

namespace app {

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// The primary monitor's work area; unknown (0x0) without one. GLFW must be initialized.
WorkArea primary_work_area() {
  WorkArea area;
  if (GLFWmonitor* monitor = glfwGetPrimaryMonitor(); monitor != nullptr) {
    int x = 0, y = 0;
    glfwGetMonitorWorkarea(monitor, &x, &y, &area.w, &area.h);
  }
  return area;
}

SpaceOpener space_opener(const SpaceCatalogue& catalogue) {
  return [&catalogue](const SpaceSettings& s) { return catalogue.open(s); };
}

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

class GalleryWindow {
 public:
  explicit GalleryWindow(const GalleryOptions& options)
      : options_(options), observer_(options.observer.get()) {}
  ~GalleryWindow() { shutdown(); }
  int run();

 private:
  struct KeyPress {
    int key;
    int mods;
    bool repeat;
  };

  // The controller, the window and the view; false (said on stderr) if one cannot be made.
  bool set_up();
  // A benchmark's frame: what it measures of the frame about to start, its click queued.
  FrameObserver::Request observed_frame_start();
  // One frame: state changes, the cells, the UI, the present.
  void frame(const FrameObserver::Request& request);
  void after_render();
  bool create_window(int width, int height, bool fit_to_screen);
  void shutdown();
  void handle_keys();
  void write_screenshot(const fs::path& path);
  WindowFacts facts() const;
  double now() const { return seconds_since(start_); }
  UiPrefs current_prefs() const {
    UiPrefs prefs = view_->prefs();
    glfwGetWindowSize(window_, &prefs.window_width, &prefs.window_height);
    return prefs;
  }

  static void on_drop(GLFWwindow* window, int count, const char** paths);
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);

  GalleryOptions options_;
  Clock::time_point start_ = Clock::now();
  GLFWwindow* window_ = nullptr;
  bool imgui_ready_ = false;
  std::unique_ptr<GalleryController> controller_;
  std::unique_ptr<GalleryView> view_;
  fs::path prefs_path_;
  std::optional<UiPrefsSaver> prefs_saver_;

  std::vector<KeyPress> key_presses_;
  std::string pending_drop_;
  bool screenshot_requested_ = false;

  long frame_ = 0;
  bool first_grid_shown_ = false;
  bool previous_frame_zoomed_ = false;     // the last frame drew a zoom animation step
  bool previous_frame_submitted_ = false;  // the last frame's click ended the plane
  FrameObserver* observer_;                // options_.observer's, or none
  bool quit_ = false;
};

bool GalleryWindow::create_window(int width, int height, bool fit_to_screen) {
  glfwSetErrorCallback([](int code, const char* text) {
    std::cerr << "GLFW error " << code << ": " << text << "\n";
  });
  if (glfwInit() != GLFW_TRUE) {
    std::cerr << "sequential-gallery: cannot open a window (no display? set DISPLAY or run under "
                 "xvfb-run); headless rendering: `sequential-gallery render` or `render-grid`\n";
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  if (fit_to_screen) {
    // A remembered size from a larger monitor (or a file saying 8192x8192) would put the grid
    // and the side panel off-screen, or ask for framebuffers the GPU cannot make.
    const auto fitted = fit_window_to(width, height, primary_work_area());
    width = fitted.first;
    height = fitted.second;
  }
  window_ = glfwCreateWindow(width, height, "Sequential Gallery", nullptr, nullptr);
  if (window_ == nullptr) {
    std::cerr << "sequential-gallery: cannot create an OpenGL 3.3 core window\n";
    return false;
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(observer_ != nullptr ? 0 : 1);
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, &GalleryWindow::on_drop);
  glfwSetKeyCallback(window_, &GalleryWindow::on_key);  // before ImGui, which chains to it

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is ours (ui.json), nothing in the working directory
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0.0f;
  style.FrameRounding = 3.0f;
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ready_ = true;
  return true;
}

void GalleryWindow::shutdown() {
  controller_.reset();  // waits for a running optimizer job
  if (view_) view_->release_gl();
  view_.reset();
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

void GalleryWindow::on_drop(GLFWwindow* window, int count, const char** paths) {
  auto* self = static_cast<GalleryWindow*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && count > 0) self->pending_drop_ = paths[0];
}

// Keys come from our own GLFW callback (ImGui's backend chains to it), queued per event:
// ImGui 1.86 keeps only key states, so a press and release inside one frame (as scripted
// input or a fast typist produces) would be lost.
void GalleryWindow::on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  auto* self = static_cast<GalleryWindow*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && (action == GLFW_PRESS || action == GLFW_REPEAT)) {
    self->key_presses_.push_back({key, mods, action == GLFW_REPEAT});
  }
}

void GalleryWindow::handle_keys() {
  std::vector<KeyPress> presses;
  presses.swap(key_presses_);
  GalleryController& c = *controller_;
  for (const KeyPress& p : presses) {
    const bool ctrl = (p.mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (p.mods & GLFW_MOD_SHIFT) != 0;
    if (p.key == GLFW_KEY_F12 && !options_.screenshot_path.empty()) {
      screenshot_requested_ = true;
      continue;
    }
    if (ctrl && p.key == GLFW_KEY_Q && !p.repeat) {
      // As closing the window: the session is saved on the way out.
      glfwSetWindowShouldClose(window_, GLFW_TRUE);
      continue;
    }
    if (c.resume_candidate() != nullptr) continue;
    if (ctrl && p.key == GLFW_KEY_S && !p.repeat) {
      view_->quick_save(c);
      continue;
    }
    if (view_->text_input_active()) continue;  // typing into a path field
    if ((ctrl && p.key == GLFW_KEY_Y) || (ctrl && shift && p.key == GLFW_KEY_Z)) {
      c.queue(intent::Redo{});
      continue;
    }
    if ((ctrl && p.key == GLFW_KEY_Z) || (!ctrl && p.key == GLFW_KEY_BACKSPACE)) {
      c.queue(intent::UndoClick{});
      continue;
    }
    if (ctrl || p.repeat) continue;
    const int n = c.session().settings().grid_size;
    int index = -1;
    if (n == 3) {
      if (p.key >= GLFW_KEY_1 && p.key <= GLFW_KEY_9) index = p.key - GLFW_KEY_1;
      if (p.key >= GLFW_KEY_KP_1 && p.key <= GLFW_KEY_KP_9) index = p.key - GLFW_KEY_KP_1;
    } else if (p.key >= GLFW_KEY_A && p.key < GLFW_KEY_A + n * n) {
      index = p.key - GLFW_KEY_A;  // cells are labelled A-Y
    }
    if (index >= 0) view_->press_cell(c, index);
  }
}

void GalleryWindow::write_screenshot(const fs::path& path) {
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
    std::cerr << "sequential-gallery: " << e.what() << "\n";
  }
}

WindowFacts GalleryWindow::facts() const {
  WindowFacts f;
  const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  f.renderer = gl_renderer != nullptr ? gl_renderer : "?";
  f.space = controller_->space().description();
  f.grid_size = controller_->session().settings().grid_size;
  f.cell_pixels = view_->cell_pixels();
  f.samples = options_.samples;
  f.animation_multisample = options_.animation_samples > 0;
  f.animation_scale = options_.animation_scale;
  glfwGetFramebufferSize(window_, &f.framebuffer_w, &f.framebuffer_h);
  f.last_submit_seconds = controller_->last_submit_seconds();
  f.planes_done = controller_->session().planes_done();
  return f;
}

bool GalleryWindow::set_up() {
  UiPrefs prefs;
  std::string prefs_problem;
  if (options_.remember_ui && !options_.session_path.empty()) {
    prefs_path_ = ui_prefs_path(options_.session_path);
    prefs = load_ui_prefs(prefs_path_, &prefs_problem);
  }
  try {
    // A benchmark measures the model it was given (or the default), whatever was chosen before.
    controller_ = std::make_unique<GalleryController>(
        observer_ != nullptr ? controller_options(options_) : controller_options(options_, prefs),
        space_opener(*options_.catalogue), now());
  } catch (const std::exception& e) {
    std::cerr << "sequential-gallery: " << e.what() << "\n";
    return false;
  }
  if (options_.view) {
    prefs.view_preset = *options_.view == render::ViewPreset::kFront  ? 0
                        : *options_.view == render::ViewPreset::kSide ? 1
                                                                      : 2;
  }
  if (!prefs_problem.empty()) controller_->report_problem(prefs_problem);
  int width = options_.window_width, height = options_.window_height;
  const bool fit_to_screen = width <= 0 || height <= 0;
  if (fit_to_screen) {
    width = prefs.window_width > 0 ? prefs.window_width : 1600;
    height = prefs.window_height > 0 ? prefs.window_height : 1000;
  }
  if (!create_window(width, height, fit_to_screen)) return false;
  ViewOptions vo;
  vo.cell_size = options_.cell_size;
  vo.samples = options_.samples;
  vo.animation_samples = options_.animation_samples;
  vo.animation_scale = options_.animation_scale;
  vo.save_path = options_.save_path;
  vo.report_layout = options_.report_layout;
  vo.file_dialog = options_.file_dialog;
  view_ = std::make_unique<GalleryView>(vo, prefs, *options_.catalogue);
  if (!prefs_path_.empty() && observer_ == nullptr) {
    prefs_saver_.emplace(prefs_path_, load_ui_prefs(prefs_path_));
  }
  return true;
}

int GalleryWindow::run() {
  if (!set_up()) return 1;
  while (!glfwWindowShouldClose(window_) && !quit_) {
    const bool active = controller_->animating() || controller_->busy() || !first_grid_shown_ ||
                        observer_ != nullptr || options_.screenshot_after_frames >= 0 ||
                        ImGui::IsAnyMouseDown() || view_->waiting_for_dialog();
    if (active) {
      glfwPollEvents();
    } else {
      glfwWaitEventsTimeout(0.25);
    }
    FrameObserver::Request request;
    if (observer_ != nullptr) {
      request = observed_frame_start();
      if (request.quit) break;
    }
    frame(request);
  }
  controller_->save_now();
  if (prefs_saver_) prefs_saver_->flush(current_prefs());
  return 0;
}

FrameObserver::Request GalleryWindow::observed_frame_start() {
  FrameObserver::Request request = observer_->frame_started(
      {Clock::now(), !controller_->animating() && !controller_->busy(), first_grid_shown_,
       previous_frame_zoomed_, previous_frame_submitted_});
  if (request.quit) {
    observer_->report(facts());
    return request;
  }
  if (request.click) {
    const int n = controller_->session().settings().grid_size;
    controller_->queue(intent::ClickCell{std::min(request.click->first, n - 1),
                                         std::min(request.click->second, n - 1)});
  }
  return request;
}

void GalleryWindow::frame(const FrameObserver::Request& request) {
  // A benchmark's breakdown of the frame (glFinish between the phases) slows every frame, so
  // it is only done when asked for.
  const bool breakdown = observer_ != nullptr && observer_->wants_breakdown();
  if (!pending_drop_.empty()) {
    view_->open_dropped(*controller_, pending_drop_);
    pending_drop_.clear();
  }
  // 1. State changes, all of them, before anything of this frame is drawn.
  const bool was_busy = controller_->busy();
  controller_->begin_frame(now());
  previous_frame_submitted_ = !was_busy && controller_->busy();
  const bool zoomed = controller_->zooming();
  previous_frame_zoomed_ = zoomed;
  // 2. Cells: prepared, uploaded and rendered into their framebuffers.
  int win_w = 0, win_h = 0, fb_w = 0, fb_h = 0;
  glfwGetWindowSize(window_, &win_w, &win_h);
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  const float dpi = win_w > 0 ? static_cast<float>(fb_w) / static_cast<float>(win_w) : 1.0f;
  const auto t0 = Clock::now();
  view_->update_cells(*controller_, static_cast<float>(win_w), static_cast<float>(win_h), dpi);
  const auto t1 = Clock::now();
  if (request.orbit) view_->orbit(4.0f, 0.0f);
  view_->draw_cells(*controller_);
  // 3. The UI: reads state, queues intents for the next frame.
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  handle_keys();
  view_->build(*controller_, frame_);
  if (breakdown) glFinish();  // attribute GL time to the cells
  const auto t2 = Clock::now();
  if (zoomed && breakdown) observer_->phases(ms_between(t0, t1), ms_between(t1, t2));
  ImGui::Render();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb_w, fb_h);
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  glClearColor(bg.x, bg.y, bg.z, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (breakdown) glFinish();
  const auto t3 = Clock::now();
  ++frame_;
  after_render();
  glfwSwapBuffers(window_);
  if (observer_ != nullptr && observer_->waits_for_presented()) {
    glFinish();  // the click's frame is on screen
    observer_->frame_presented(Clock::now());
  }
  if (prefs_saver_) prefs_saver_->update(current_prefs(), now());
  if (zoomed && breakdown) {
    glFinish();
    observer_->presented_phases(ms_between(t2, Clock::now()), ms_between(t3, Clock::now()));
  }
}

// The first grid's launch time, and the screenshots asked for (F12, or after N frames).
void GalleryWindow::after_render() {
  if (!first_grid_shown_ && !controller_->displayed_cells().empty()) {
    first_grid_shown_ = true;
    glFinish();
    const double launch = seconds_since(options_.launch_time);
    if (observer_ != nullptr) observer_->first_grid(launch);
    std::cerr << "first grid shown " << static_cast<int>(launch * 1000.0) << " ms after launch\n";
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
}

}  // namespace

ControllerOptions controller_options(const GalleryOptions& o) {
  if (o.catalogue == nullptr) throw std::logic_error("the gallery needs a catalogue of spaces");
  const SpaceKind& kind = o.space.empty() ? o.catalogue->default_kind() : o.catalogue->get(o.space);
  ControllerOptions c;
  c.space.kind = kind.name;
  c.space.source = o.source.value_or("");
  // A space named on the command line (--space, --model, --image) is what the user asked for.
  c.space_chosen = o.space_given || o.source.has_value();
  c.space.dimensions = kind.dimensions_fixed || o.components <= 0 ? kind.dimensions : o.components;
  c.grid_size = o.grid_size;
  c.zoom_levels = o.zoom_levels;
  c.seed = o.seed;
  c.session_path = o.session_path;
  // A click never waits for the session file (tens of ms on a long session).
  c.background_autosave = true;
  c.resume = o.resume;
  c.zoom_seconds = o.zoom_seconds;
  c.optimizer_delay_ms = o.optimizer_delay_ms;
  c.targets = o.targets;
  c.holds = o.holds;
  c.report_messages = o.report_layout;
  c.catalogue = o.catalogue;
  return c;
}

ControllerOptions controller_options(const GalleryOptions& o, const UiPrefs& prefs) {
  ControllerOptions c = controller_options(o);
  const SpaceKind& kind = o.catalogue->get(c.space.kind);
  if (!o.source && kind.remembered_source) c.space.source = kind.remembered_source(prefs.sources);
  c.close_ups = prefs.close_ups;
  return c;
}

int run_gallery(const GalleryOptions& options) {
  GalleryWindow window(options);
  return window.run();
}

}  // namespace app
