// The gallery in-process: the controller (intents, animation, undo/redo, resume, new search)
// and the view on the headless EGL context with a real ImGui context, asserting on state.
#include <epoxy/gl.h>
#include <imgui.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "app/gallery_controller.hpp"
#include "app/gallery_view.hpp"
#include "app/session_store.hpp"
#include "render/headless_context.hpp"
#include "render/photo_renderer.hpp"
#include "spaces/photo_enhancement.hpp"
#include "spaces/photo_image.hpp"
#include "spaces/space_factory.hpp"

namespace fs = std::filesystem;
using app::GalleryController;
namespace intent = app::intent;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("sg-gallery-test-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

app::ControllerOptions options(const fs::path& session, const std::string& kind = "photo") {
  app::ControllerOptions o;
  o.space = spaces::default_settings(kind);
  o.session_path = session;
  o.resume = app::ResumePolicy::kNo;
  o.zoom_seconds = 1.0;
  o.morph_seconds = 0.5;
  o.log = false;
  return o;
}

// Clicks through a whole plane, letting each zoom finish, and waits for the optimizer.
double finish_plane(GalleryController& c, double t) {
  const int levels = c.session().settings().zoom_levels;
  for (int i = 0; i < levels; ++i) {
    c.queue(intent::ClickCell{i % 3, (i + 1) % 3});
    c.begin_frame(t);
    t += 5.0;
    c.begin_frame(t);
  }
  c.wait_for_optimizer(t);
  t += 5.0;
  c.begin_frame(t);
  return t;
}

// A headless ImGui context the size of a 1280x720 window, its font atlas built, no ini file.
void create_test_imgui_context() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(1280, 720);
  unsigned char* font = nullptr;
  int fw = 0, fh = 0;
  io.Fonts->GetTexDataAsRGBA32(&font, &fw, &fh);
}

}  // namespace

TEST_CASE("intents change nothing until the next frame starts", "[gallery]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json"), &spaces::open_space, 0.0);
  c.begin_frame(0.0);
  c.queue(intent::ClickCell{1, 1});
  CHECK(c.session().clicks_on_plane() == 0);  // queued only
  c.begin_frame(0.1);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK(c.zooming());
}

TEST_CASE("clicks during the zoom animation are not extra zoom steps", "[gallery]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json"), &spaces::open_space, 0.0);
  c.begin_frame(0.0);
  c.queue(intent::ClickCell{0, 0});
  c.begin_frame(0.0);
  REQUIRE(c.session().clicks_on_plane() == 1);
  // The second click of a double-click and an impatient click, both mid-zoom.
  c.queue(intent::ClickCell{0, 0});
  c.begin_frame(0.2);
  c.queue(intent::ClickCell{2, 2});
  c.begin_frame(0.9);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK(c.ignored_clicks() == 2);
  // Once the grid has settled a click counts again.
  c.begin_frame(1.1);
  CHECK_FALSE(c.animating());
  c.queue(intent::ClickCell{2, 2});
  c.begin_frame(1.2);
  CHECK(c.session().clicks_on_plane() == 2);
}

TEST_CASE("Undo plane has one meaning and Redo brings it back", "[gallery]") {
  TempDir dir;
  auto o = options(dir.path / "s.json");
  o.zoom_levels = 2;
  GalleryController c(o, &spaces::open_space, 0.0);
  c.begin_frame(0.0);
  CHECK_FALSE(c.can_undo_plane());  // no finished plane yet
  double t = finish_plane(c, 0.0);
  REQUIRE(c.session().planes_done() == 1);
  c.queue(intent::ClickCell{1, 0});
  c.begin_frame(t);
  t += 5;
  c.begin_frame(t);
  REQUIRE(c.session().clicks_on_plane() == 1);
  const Eigen::VectorXd best_before = c.session().current_best();

  c.queue(intent::UndoPlane{});
  c.begin_frame(t);
  CHECK(c.session().planes_done() == 0);      // the finished plane is undone...
  CHECK(c.session().clicks_on_plane() == 0);  // ...and it starts without clicks
  CHECK(c.can_redo());

  c.queue(intent::Redo{});
  c.begin_frame(t + 1);
  CHECK(c.session().planes_done() == 1);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK((c.session().current_best() - best_before).norm() < 1e-12);

  // A new click makes the redo history obsolete.
  c.queue(intent::UndoClick{});
  c.begin_frame(t + 10);
  c.begin_frame(t + 20);
  c.queue(intent::ClickCell{0, 0});
  c.begin_frame(t + 21);
  CHECK_FALSE(c.can_redo());
}

TEST_CASE("expert sliders: Use this makes the point the current best, preferred over the last",
          "[gallery]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json"), &spaces::open_space, 0.0);
  c.begin_frame(0.0);
  const Eigen::VectorXd before = c.session().current_best();
  Eigen::VectorXd x = before;
  x[0] = 0.9;
  x[5] = 0.1;
  c.queue(intent::UsePoint{x});
  c.begin_frame(0.1);
  CHECK(c.busy());
  c.wait_for_optimizer(0.2);
  CHECK_FALSE(c.busy());
  REQUIRE(c.session().planes_done() == 1);
  CHECK((c.session().history().back().chosen - x).norm() < 1e-12);
  // It was autosaved, and the file reads back (a slider entry has no clicks).
  CHECK(c.autosave_problem().empty());
  const auto reloaded = app::load_session(dir.path / "s.json");
  CHECK(reloaded.problem.empty());
  REQUIRE(reloaded.session);
  CHECK(reloaded.session->planes_done() == 1);
  // The data says x beat the previous best: the model ranks it higher.
  const auto& search = c.session().search();
  CHECK(search.posterior_mean(x) > search.posterior_mean(before));
  // Points outside the box are refused with a message, nothing submitted.
  Eigen::VectorXd bad = x;
  bad[1] = 1.5;
  c.queue(intent::UsePoint{bad});
  c.begin_frame(1.0);
  CHECK_FALSE(c.busy());
  CHECK(c.message().kind == app::MessageKind::kError);
  // Undo takes it back like a finished plane (no clicks to restore).
  c.begin_frame(10.0);
  c.queue(intent::UndoClick{});
  c.begin_frame(10.1);
  CHECK(c.session().planes_done() == 0);
  CHECK(c.session().clicks_on_plane() == 0);
}

TEST_CASE("a resumable session waits for the answer, other intents are ignored", "[gallery]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    GalleryController first(options(session), &spaces::open_space, 0.0);
    first.queue(intent::ClickCell{2, 1});
    first.begin_frame(0.0);
    first.save_now();
  }
  auto o = options(session);
  o.resume = app::ResumePolicy::kAsk;
  GalleryController c(o, &spaces::open_space, 0.0);
  REQUIRE(c.resume_candidate() != nullptr);
  CHECK(c.resume_description().find("1 click(s)") != std::string::npos);
  c.queue(intent::ClickCell{0, 0});
  c.begin_frame(0.0);
  CHECK(c.session().clicks_on_plane() == 0);
  c.queue(intent::Resume{});
  c.begin_frame(0.1);
  CHECK(c.resume_candidate() == nullptr);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK(c.session().path()[0].col == 2);
}

TEST_CASE("a new search keeps the old session file and switches the space", "[gallery]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  GalleryController c(options(session, "body"), &spaces::open_space, 0.0);
  CHECK(c.space().settings().kind == "body");
  CHECK(c.session().settings().grid_size == 3);
  c.queue(intent::ClickCell{1, 1});
  c.begin_frame(0.0);
  const int space_generation = c.space_generation();
  c.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
  c.begin_frame(0.1);
  CHECK(c.space().settings().kind == "photo");
  CHECK(c.space().dimensions() == 12);
  CHECK(c.session().settings().grid_size == 5);  // the paper's grid for photos
  CHECK(c.space_generation() != space_generation);
  CHECK(fs::exists(fs::path(session.string() + ".previous")));
  const auto reloaded = app::load_session(session);
  REQUIRE(reloaded.session);
  CHECK(reloaded.session->settings().space == "photo");
}

TEST_CASE("a failing autosave is reported until a save works again", "[gallery]") {
  TempDir dir;
  std::ofstream(dir.path / "a-file") << "x";
  // The session's folder would have to be inside a plain file: every save fails.
  GalleryController c(options(dir.path / "a-file" / "s.json"), &spaces::open_space, 0.0);
  c.queue(intent::ClickCell{0, 0});
  c.begin_frame(0.0);
  CHECK_FALSE(c.autosave_problem().empty());
  c.queue(intent::UndoClick{});
  c.begin_frame(5.0);
  CHECK_FALSE(c.autosave_problem().empty());  // still failing, still shown
}

TEST_CASE("photo export writes the enhanced full-size image and its parameters",
          "[gallery][photo]") {
  TempDir dir;
  GalleryController c(options(""), &spaces::open_space, 0.0);
  c.queue(intent::ClickCell{4, 0});
  c.begin_frame(0.0);
  const fs::path out = dir.path / "edit.jpg";
  c.queue(intent::Export{out});
  c.begin_frame(0.1);
  REQUIRE(c.message().kind == app::MessageKind::kSuccess);
  const spaces::Image saved = spaces::load_image(out);
  CHECK(saved.width == 960);
  CHECK(saved.height == 640);
  std::ifstream json_file(dir.path / "edit.json");
  REQUIRE(json_file);
  const auto j = nlohmann::json::parse(json_file);
  CHECK(j.at("parameters").size() == 12);
  CHECK(j.at("x").size() == 12);
  CHECK(std::abs(j.at("x")[0].get<double>() - c.session().current_best()[0]) < 1e-9);
  // A wrong extension is an error naming the file, not a crash.
  c.queue(intent::Export{dir.path / "edit.bmp"});
  c.begin_frame(0.2);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.message().text.find("edit.bmp") != std::string::npos);
}

TEST_CASE("the photo shader and the CPU export agree", "[gallery][photo][gl]") {
  render::HeadlessContext context;
  const spaces::Image image = spaces::default_photo();
  render::PhotoRenderer renderer(image.width, image.height, image.rgba);
  Eigen::VectorXd x(12);
  x << 0.7, 0.3, 0.8, 0.2, 0.6, 0.9, 0.4, 0.1, 0.5, 0.75, 0.35, 0.65;
  const auto p = spaces::photo_parameters(x);
  app::CellView view;  // only its framebuffer
  view.fbo.resize(image.width, image.height, 0);
  view.fbo.begin();
  renderer.draw(p, image.width, image.height);
  view.fbo.end();
  const auto gpu = view.fbo.read_pixels();  // bottom row first
  std::vector<std::uint8_t> cpu = image.rgba;
  spaces::enhance_image(cpu, p);
  double total = 0.0;
  int worst = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int xx = 0; xx < image.width; ++xx) {
      for (int k = 0; k < 3; ++k) {
        const int a =
            gpu[(static_cast<std::size_t>(image.height - 1 - y) * image.width + xx) * 4 + k];
        const int b = cpu[(static_cast<std::size_t>(y) * image.width + xx) * 4 + k];
        total += std::abs(a - b);
        worst = std::max(worst, std::abs(a - b));
      }
    }
  }
  const double mean = total / (3.0 * image.width * image.height);
  INFO("mean difference " << mean << ", worst " << worst);
  CHECK(mean < 1.0);
  CHECK(worst <= 4);
  // And the edit is visible at all.
  double changed = 0.0;
  for (std::size_t i = 0; i < cpu.size(); ++i) changed += std::abs(cpu[i] - image.rgba[i]);
  CHECK(changed / static_cast<double>(cpu.size()) > 5.0);
}

TEST_CASE("view and controller in-process: textures the UI drew stay alive across intents",
          "[gallery][gl]") {
  TempDir dir;
  render::HeadlessContext context;
  create_test_imgui_context();
  {
    GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
    app::ViewOptions vo;
    vo.file_dialog = "builtin";
    app::GalleryView view(vo, app::UiPrefs{});
    double t = 0.0;
    auto frame = [&](long n) {
      c.begin_frame(t);
      view.update_cells(c, 1280, 720, 1.0f);
      view.draw_cells(c);
      ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
      ImGui::NewFrame();
      view.build(c, n);
      ImGui::Render();
      // Every texture the UI queued this frame must still exist when it is drawn.
      int images = 0;
      const ImDrawData* data = ImGui::GetDrawData();
      for (int l = 0; l < data->CmdListsCount; ++l) {
        for (const ImDrawCmd& cmd : data->CmdLists[l]->CmdBuffer) {
          const auto id = static_cast<GLuint>(reinterpret_cast<std::intptr_t>(cmd.TextureId));
          if (id == 0 || cmd.UserCallback != nullptr) continue;
          ++images;
          CHECK(glIsTexture(id) == GL_TRUE);
        }
      }
      return images;
    };
    CHECK(frame(0) >= 9);  // nine cells (and previews) drawn as images
    CHECK(view.layout().grid.w > view.layout().side.w);  // at 1280x720 the grid rules
    CHECK(view.layout().messages.y + app::kMessageHeight <= 720);
    // A key press on the view: queued, applied at the next frame's start.
    view.press_cell(c, 4);
    CHECK(c.session().clicks_on_plane() == 0);
    frame(1);
    CHECK(c.session().clicks_on_plane() == 1);
    // Switching the space mid-session (a dropped image with progress asks first).
    view.open_dropped(c, "");
    t += 5.0;
    frame(2);
    CHECK(c.space().settings().kind == "body");  // the question is open, nothing changed
    // No progress: a drop opens at once, and the next frames draw the new space's cells.
    c.queue(intent::StartOver{});
    t += 5.0;
    frame(3);
    view.open_dropped(c, (dir.path / "missing.png").string());
    frame(4);
    CHECK(c.message().kind == app::MessageKind::kError);  // a missing image is reported
    c.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
    frame(5);
    CHECK(c.space().settings().kind == "photo");
    CHECK(frame(6) >= 25);
    view.release_gl();
  }
  ImGui::DestroyContext();
}

TEST_CASE("the window's remembered settings round-trip, a broken file means defaults",
          "[gallery]") {
  TempDir dir;
  const fs::path path = app::ui_prefs_path(dir.path / "session.json");
  CHECK(path == dir.path / "ui.json");
  app::UiPrefs p;
  p.window_width = 1280;
  p.window_height = 720;
  p.save_folder = "/tmp/designs";
  p.save_name = "me.glb";
  p.view_preset = 2;
  p.open_panel = true;
  REQUIRE(app::save_ui_prefs(p, path));
  const app::UiPrefs q = app::load_ui_prefs(path);
  CHECK(q.window_width == 1280);
  CHECK(q.window_height == 720);
  CHECK(q.save_folder == "/tmp/designs");
  CHECK(q.save_name == "me.glb");
  CHECK(q.view_preset == 2);
  CHECK(q.open_panel);
  std::ofstream(path) << "{\"window_width\": -5, \"window_height\": \"big\", \"view_preset\": 9";
  const app::UiPrefs broken = app::load_ui_prefs(path);
  CHECK(broken.window_width == 0);
  CHECK(broken.view_preset == 0);
  std::ofstream(path) << "{\"window_width\": 99999, \"window_height\": 100, \"view_preset\": 9}";
  const app::UiPrefs clamped = app::load_ui_prefs(path);
  CHECK(clamped.window_width == 16384);
  CHECK(clamped.window_height == 240);
  CHECK(clamped.view_preset == 2);
}

namespace {

// A view and a controller driven frame by frame as the window does, with ImGui fed synthetic
// mouse input (no window, no backend; cells render on the headless EGL context).
struct InProcessWindow {
  render::HeadlessContext context;
  std::unique_ptr<GalleryController> c;
  std::unique_ptr<app::GalleryView> view;
  double t = 0.0;
  long frames = 0;

  explicit InProcessWindow(app::ControllerOptions o) {
    create_test_imgui_context();
    c = std::make_unique<GalleryController>(o, &spaces::open_space, t);
    view = std::make_unique<app::GalleryView>(app::ViewOptions{}, app::UiPrefs{});
  }
  ~InProcessWindow() {
    view->release_gl();
    view.reset();
    c.reset();
    ImGui::DestroyContext();
  }
  void frame(ImVec2 mouse, bool down, double seconds = 1.0 / 60.0) {
    t += seconds;
    c->begin_frame(t);
    view->update_cells(*c, 1280, 720, 1.0f);
    view->draw_cells(*c);
    ImGuiIO& io = ImGui::GetIO();
    io.DeltaTime = 1.0f / 60.0f;
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ImGui::NewFrame();
    view->build(*c, frames++);
    ImGui::Render();
  }
  ImVec2 cell_centre(int index) const {
    const auto& l = view->layout();
    const int n = c->session().settings().grid_size;
    return ImVec2(l.grid.x + static_cast<float>(index % n) * (l.cell + l.gap) + l.cell / 2,
                  l.grid.y + static_cast<float>(index / n) * (l.cell + l.gap) + l.cell / 2);
  }
};

}  // namespace

TEST_CASE("a double-click on a cell is one zoom step, hovering shows the cell", "[gallery][gl]") {
  TempDir dir;
  auto o = options(dir.path / "s.json", "body");
  o.zoom_seconds = 0.01;  // the zoom is over long before the second click
  InProcessWindow w(o);
  w.frame(ImVec2(-1, -1), false);  // lays the window out
  const ImVec2 p = w.cell_centre(4);
  w.frame(p, false);
  w.frame(p, false);
  CHECK(w.view->hovered_cell() == 4);
  // Press, release, press, release within ImGui's double-click time (4 frames at 60 Hz).
  w.frame(p, true);
  w.frame(p, false);
  w.frame(p, true);
  w.frame(p, false);
  for (int i = 0; i < 3; ++i) w.frame(p, false);
  CHECK(w.c->session().clicks_on_plane() == 1);
  // A later single click counts.
  w.frame(p, true, 1.0);
  w.frame(p, false);
  w.frame(p, false);
  CHECK(w.c->session().clicks_on_plane() == 2);
}

TEST_CASE("the window's body sessions see what the benchmark's simulated person sees",
          "[gallery]") {
  // The body space hands its perceptual distance and scale to every session the controller
  // holds (new, resumed, after a new search), exactly as `simulate --function body` does, so
  // the benchmark measures the window's behaviour.
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    GalleryController c(options(session, "body"), &spaces::open_space, 0.0);
    CHECK(c.session().has_perceptual_distance());
    const Eigen::VectorXd scale = c.session().search().options().perceptual_scale;
    REQUIRE(scale.size() == c.session().settings().components);
    CHECK(scale.minCoeff() > 1.0);  // mm over the range: every component visibly moves
    // No grid the window shows holds two look-alike cells.
    const auto cells = c.session().cells();
    std::vector<Eigen::VectorXd> xs;
    for (const auto& p : cells) xs.push_back(p.x);
    const Eigen::MatrixXd d = c.space().perceptual_distance()(xs);
    double closest = 1e300;
    for (Eigen::Index i = 0; i < d.rows(); ++i)
      for (Eigen::Index j = i + 1; j < d.cols(); ++j) closest = std::min(closest, d(i, j));
    CHECK(closest >= app::kCloneMm);
    c.queue(intent::ClickCell{1, 1});
    c.begin_frame(0.0);
  }
  app::ControllerOptions resumed = options(session, "body");
  resumed.resume = app::ResumePolicy::kYes;
  GalleryController c(resumed, &spaces::open_space, 0.0);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK(c.session().has_perceptual_distance());
  // The photo space has no such measure: the paper's fixed zoom.
  c.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
  c.begin_frame(0.1);
  CHECK_FALSE(c.session().has_perceptual_distance());
}
