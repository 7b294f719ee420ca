// The gallery in-process: the controller (intents, animation, undo/redo, resume, new search)
// and the view on the headless EGL context with a real ImGui context, asserting on state.
#include <epoxy/gl.h>
#include <imgui.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>

#include <catch2/catch.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "app/cell_visibility.hpp"
#include "app/gallery_app.hpp"
#include "app/gallery_controller.hpp"
#include "app/gallery_layout.hpp"
#include "app/gallery_view.hpp"
#include "app/session_perception.hpp"
#include "app/session_store.hpp"
#include "app/ui_prefs.hpp"
#include "body/grid_framing.hpp"
#include "body/shape_distance.hpp"
#include "body/standing_height.hpp"
#include "common/first_difference.hpp"
#include "render/camera.hpp"
#include "render/headless_context.hpp"
#include "render/photo_renderer.hpp"
#include "spaces/body_space.hpp"
#include "spaces/photo_enhancement.hpp"
#include "spaces/photo_image.hpp"
#include "spaces/photo_perception.hpp"
#include "spaces/source_panels.hpp"
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
  o.catalogue = &spaces::catalogue();
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

namespace {

// The least a space can be: dimensions, cells and an export, without perception or
// measurements (no facets).
class PlainSpace : public app::DesignSpace {
 public:
  app::SpaceSettings settings() const override { return {"plain", "", 4}; }
  std::string description() const override { return "plain: 4 numbers"; }
  std::string dimension_name(int i) const override { return "number " + std::to_string(i + 1); }
  bool uses_camera() const override { return false; }
  float preview_aspect() const override { return 1.0f; }
  std::shared_ptr<const app::PreparedCell> prepare(const Eigen::VectorXd& x,
                                                   bool details) const override {
    auto cell = std::make_shared<app::PreparedCell>();
    cell->x = x;
    cell->has_details = details;
    return cell;
  }
  std::unique_ptr<app::CellContent> make_content() override { return nullptr; }
  void draw_inspector(const app::PreparedCell&, const char*, const app::PreparedCell*,
                      const char*) const override {}
  std::string default_export_name() const override { return "plain.txt"; }
  std::string export_hint() const override { return ".txt"; }
  std::string export_point(const Eigen::VectorXd&, const fs::path& path) const override {
    return path.string();
  }
};

}  // namespace

TEST_CASE(
    "a space without perception or measurements: the kind's grid, fixed zoom, holds "
    "and targets refused by name",
    "[gallery][catalogue]") {
  app::SpaceCatalogue kinds;
  app::SpaceKind plain;
  plain.name = "plain";
  plain.label = "plain numbers";
  plain.source_noun = "Numbers";
  plain.source_option = "numbers";
  plain.dimensions = 4;
  plain.grid_size = 5;
  plain.open = [](const app::SpaceSettings&) { return std::make_unique<PlainSpace>(); };
  kinds.add(plain);
  TempDir dir;
  app::ControllerOptions o = options(dir.path / "s.json");
  o.catalogue = &kinds;
  o.space = {"plain", "", 4};
  GalleryController c(
      o, [&](const app::SpaceSettings& s) { return kinds.get(s.kind).open(s); }, 0.0);
  c.begin_frame(0.0);
  REQUIRE(c.space().perception() == nullptr);
  REQUIRE(c.space().measurements() == nullptr);
  CHECK(c.session().settings().grid_size == 5);  // the kind's, not the body's or photo's 3
  CHECK_FALSE(c.session().has_perceptual_distance());
  CHECK(c.session().search().options().perceptual_scale.size() == 0);
  c.queue(intent::SetHolds{{"height"}});
  c.begin_frame(0.1);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.message().text.find("no measurements to hold") != std::string::npos);
  CHECK(c.holds().empty());
  c.queue(intent::GoToTargets{{"height=1.8"}});
  c.begin_frame(0.2);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.message().text.find("no measurements to aim for") != std::string::npos);
  // Clicks still zoom (by the paper's fixed factor).
  c.queue(intent::ClickCell{2, 2});
  c.begin_frame(0.3);
  CHECK(c.session().clicks_on_plane() == 1);
}

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

TEST_CASE("Redo survives a relaunch: the session file keeps what Undo took back",
          "[gallery][redo]") {
  TempDir dir;
  const fs::path file = dir.path / "s.json";
  auto o = options(file);
  o.zoom_levels = 2;
  std::vector<std::string> searches;  // before each undo
  std::vector<Eigen::VectorXd> bests;
  {
    GalleryController c(o, &spaces::open_space, 0.0);
    c.begin_frame(0.0);
    double t = finish_plane(c, 0.0);
    t = finish_plane(c, t);
    c.queue(intent::ClickCell{2, 1});
    c.begin_frame(t);
    t += 5;
    c.begin_frame(t);
    REQUIRE(c.session().planes_done() == 2);
    REQUIRE(c.session().clicks_on_plane() == 1);
    for (int k = 0; k < 3; ++k) {
      searches.push_back(c.session().search().to_json());
      bests.push_back(c.session().current_best());
      if (k == 0) {
        c.queue(intent::UndoClick{});
      } else {
        c.queue(intent::UndoPlane{});
      }
      t += 5;
      c.begin_frame(t);
    }
    // The click, then the two planes: back at the start.
    REQUIRE(c.session().planes_done() == 0);
    REQUIRE(c.session().clicks_on_plane() == 0);
    REQUIRE(c.can_redo());
    CHECK(c.autosave_problem().empty());
  }
  auto resumed = o;
  resumed.resume = app::ResumePolicy::kYes;
  {
    GalleryController c(resumed, &spaces::open_space, 0.0);
    c.begin_frame(0.0);
    REQUIRE(c.session().planes_done() == 0);
    CHECK(c.message().kind != app::MessageKind::kError);
    double t = 1.0;
    for (int k = 2; k >= 0; --k) {
      REQUIRE(c.can_redo());
      c.queue(intent::Redo{});
      t += 5;
      c.begin_frame(t);
      const auto i = static_cast<std::size_t>(k);
      CHECK(test_support::first_difference(c.session().search().to_json(), searches[i]) == "");
      CHECK((c.session().current_best() - bests[i]).norm() < 1e-12);
      // Still the space's perceptual zoom (the distance is not saved with the file).
      CHECK(c.session().has_perceptual_distance());
    }
    CHECK(c.session().planes_done() == 2);
    CHECK(c.session().clicks_on_plane() == 1);
    CHECK_FALSE(c.can_redo());
    // Undone once more and closed: the next launch can redo it again.
    c.queue(intent::UndoClick{});
    c.begin_frame(t + 5);
  }
  {
    GalleryController c(resumed, &spaces::open_space, 0.0);
    c.begin_frame(0.0);
    CHECK(c.session().clicks_on_plane() == 0);
    REQUIRE(c.can_redo());
  }
  // A redo part that cannot be used is said by file and field; the session itself resumes.
  nlohmann::json j;
  std::ifstream(file) >> j;
  REQUIRE(j.contains("redo"));
  j["redo"][0]["path"] = "broken";
  std::ofstream(file) << j.dump();
  GalleryController c(resumed, &spaces::open_space, 0.0);
  c.begin_frame(0.0);
  CHECK(c.session().planes_done() == 2);
  CHECK_FALSE(c.can_redo());
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.message().text.find(file.string()) != std::string::npos);
  CHECK(c.message().text.find("redo[0]: path") != std::string::npos);
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

TEST_CASE("expert sliders keep the clicks already made on the plane", "[gallery]") {
  TempDir dir;
  // Use this on a fresh plane, and on one with two zoom clicks made: the clicks become
  // preference data too, and undo gives all of them back.
  const auto use_point_after = [&](int clicks, const char* file) {
    auto o = options(dir.path / file);
    o.perceptual_zoom = false;  // two clicks that never end the plane early
    auto c = std::make_unique<GalleryController>(o, &spaces::open_space, 0.0);
    double t = 0.0;
    c->begin_frame(t);
    for (int k = 0; k < clicks; ++k) {
      c->queue(intent::ClickCell{k, 1});
      c->begin_frame(t += 10.0);
      c->begin_frame(t += 10.0);  // past the zoom animation
    }
    REQUIRE(c->session().clicks_on_plane() == clicks);
    Eigen::VectorXd x = c->session().current_best();
    x[0] = x[0] > 0.5 ? 0.1 : 0.9;
    c->queue(intent::UsePoint{x});
    c->begin_frame(t += 1.0);
    c->wait_for_optimizer(t += 1.0);
    REQUIRE(c->session().planes_done() == 1);
    return c;
  };
  const auto fresh = use_point_after(0, "fresh.json");
  const auto clicked = use_point_after(2, "clicked.json");
  const auto count = [](const GalleryController& c) {
    return c.session().search().data().preferences().size();
  };
  CHECK(count(*clicked) >= count(*fresh) + 2);
  CHECK(clicked->session().history().back().set_by_sliders);
  CHECK(clicked->session().history().back().path.size() == 2);
  // The flag survives the session file.
  clicked->save_now();
  const auto reloaded = app::load_session(dir.path / "clicked.json");
  REQUIRE(reloaded.session);
  CHECK(reloaded.session->history().back().set_by_sliders);
  // Undo reopens the plane with both clicks, not one fewer as after a finished plane.
  clicked->queue(intent::UndoClick{});
  clicked->begin_frame(100.0);
  CHECK(clicked->session().planes_done() == 0);
  CHECK(clicked->session().clicks_on_plane() == 2);
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
  CHECK(c.resume_description().find("1 click on the current plane") != std::string::npos);
  CHECK(c.resume_description().find("dimensions") == std::string::npos);  // said twice before
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
  CHECK(c.session().settings().grid_size == 3);  // cells large enough to compare colours
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

namespace {

// The picture a photo cell shows, read back from the GPU (top row first), in CIELAB.
std::vector<spaces::Lab> rendered_cell_lab(const render::PhotoRenderer& renderer,
                                           const Eigen::VectorXd& x, int w, int h) {
  app::CellView view;
  view.fbo.resize(w, h, 0);
  view.fbo.begin();
  renderer.draw(spaces::photo_parameters(x), w, h);
  view.fbo.end();
  const auto rgba = view.fbo.read_pixels();
  std::vector<spaces::Lab> lab;
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) {
    lab.push_back(
        spaces::srgb_to_lab({rgba[i] / 255.0f, rgba[i + 1] / 255.0f, rgba[i + 2] / 255.0f}));
  }
  return lab;
}

}  // namespace

TEST_CASE("the photo space's colour differences are what its rendered cells show",
          "[gallery][photo][gl]") {
  // The look-alike measure works on a 40-pixel copy of the picture; a cell is the whole
  // picture drawn by the shader at the cell's size. Over random pairs of edits the two must
  // agree: the measure is a model of the renders, validated here against them.
  render::HeadlessContext context;
  const spaces::Image image = spaces::default_photo();
  render::PhotoRenderer renderer(image.width, image.height, image.rgba);
  const spaces::PhotoDistance distance(image);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.15, 0.85);
  double worst_ratio = 0.0;
  for (int pair = 0; pair < 8; ++pair) {
    Eigen::VectorXd a(12), b(12);
    for (int i = 0; i < 12; ++i) a[i] = unit(rng), b[i] = unit(rng);
    // Near pairs (about one JND) as well as far ones: the threshold matters where cells are
    // close.
    if (pair % 2 == 1) b = a + 0.2 * (b - a);
    const auto ra = rendered_cell_lab(renderer, a, 180, 120);
    const auto rb = rendered_cell_lab(renderer, b, 180, 120);
    const double rendered = spaces::PhotoDistance::visible_difference(ra, rb);
    const double rendered_mean = spaces::PhotoDistance::mean_difference(ra, rb);
    const double model = distance.pairwise({a, b})(0, 1);
    const double model_mean = distance.to_target({a}, b).front();
    INFO("pair " << pair << ": visible " << model << " (model) vs " << rendered
                 << " (rendered cell); mean " << model_mean << " vs " << rendered_mean);
    // The cells' 8-bit pixels add a rounding noise of a few tenths of a Delta E per pixel,
    // which the tenth of the pixels that differ most collects: an absolute margin for it.
    CHECK(model == Approx(rendered).epsilon(0.1).margin(0.4));
    CHECK(model_mean == Approx(rendered_mean).epsilon(0.1).margin(0.2));
    worst_ratio = std::max(worst_ratio, std::abs(std::log(model / rendered)));
  }
  INFO("worst |log(model / rendered)| " << worst_ratio);
  CHECK(worst_ratio < 0.25);
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
    app::GalleryView view(vo, app::UiPrefs{}, spaces::catalogue());
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
    CHECK(frame(6) >= 9);
    // The user's own picture, dropped: it opens, and the prefs offer it again next launch.
    spaces::Image small = spaces::default_photo();
    const fs::path own = dir.path / "own.png";
    { std::ofstream(own, std::ios::binary) << spaces::encode_image(small, own); }
    view.open_dropped(c, own.string());
    t += 5.0;
    frame(7);
    frame(8);
    CHECK(c.space().settings().kind == "photo");
    CHECK(fs::path(c.space().settings().source).filename() == "own.png");
    CHECK(fs::path(view.prefs().sources.at("photo_file")).filename() == "own.png");
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
  p.side_tab = "new-search";
  REQUIRE(app::save_ui_prefs(p, path));
  const app::UiPrefs q = app::load_ui_prefs(path);
  CHECK(q.window_width == 1280);
  CHECK(q.window_height == 720);
  CHECK(q.save_folder == "/tmp/designs");
  CHECK(q.save_name == "me.glb");
  CHECK(q.view_preset == 2);
  CHECK(q.side_tab == "new-search");
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
  float width = 1280, height = 720;

  explicit InProcessWindow(app::ControllerOptions o, app::UiPrefs prefs = {},
                           ImVec2 size = ImVec2(1280, 720),
                           const app::SpaceCatalogue& kinds = spaces::catalogue()) {
    create_test_imgui_context();
    width = size.x;
    height = size.y;
    ImGui::GetIO().DisplaySize = size;
    c = std::make_unique<GalleryController>(
        o, [&kinds](const app::SpaceSettings& s) { return kinds.open(s); }, t);
    app::ViewOptions vo;
    vo.file_dialog = "builtin";  // never a desktop dialog in a test
    view = std::make_unique<app::GalleryView>(vo, std::move(prefs), kinds);
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
    view->update_cells(*c, width, height, 1.0f);
    view->draw_cells(*c);
    ImGuiIO& io = ImGui::GetIO();
    io.DeltaTime = 1.0f / 60.0f;
    io.MousePos = mouse;
    io.MouseDown[0] = down;
    ImGui::NewFrame();
    view->build(*c, frames++);
    ImGui::Render();
  }
  // A real click (press, release) on a widget the view drew in the last frame.
  void click(const std::string& widget) {
    const auto r = view->widget(widget);
    REQUIRE(r);
    const ImVec2 p(r->x + r->w / 2, r->y + r->h / 2);
    frame(p, false);
    frame(p, true);
    frame(p, false);
    frame(ImVec2(-1, -1), false);  // the intent it queued is applied
  }
  ImVec2 cell_centre(int index) const {
    const auto& l = view->layout();
    const int n = c->session().settings().grid_size;
    return ImVec2(l.grid.x + static_cast<float>(index % n) * (l.cell + l.gap) + l.cell / 2,
                  l.grid.y + static_cast<float>(index / n) * (l.cell + l.gap) + l.cell / 2);
  }
};

}  // namespace

TEST_CASE("the toolbar's rows as drawn head the side column - Close-ups toggles the framing",
          "[gallery][gl]") {
  TempDir dir;
  for (const ImVec2 size : {ImVec2(1280, 720), ImVec2(800, 600), ImVec2(1920, 1080)}) {
    CAPTURE(size.x, size.y);
    // Each window in its own iteration: it owns the ImGui context.
    InProcessWindow w(options(dir.path / "s.json", "body"), {}, size);
    for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
    const app::GalleryLayout& l = w.view->layout();
    // Every toolbar widget lies in the toolbar's rect, above the message lines.
    for (const char* name : {"toolbar:close-ups", "toolbar:model"}) {
      CAPTURE(name);
      const auto r = w.view->widget(name);
      REQUIRE(r);
      CHECK(r->y >= l.toolbar.y - 1.0f);
      CHECK(r->y + r->h <= l.messages.y + 1.0f);
      CHECK(r->x >= l.toolbar.x - 1.0f);
    }
  }
  {
    InProcessWindow w(options(dir.path / "s.json", "body"));
    w.frame(ImVec2(-1, -1), false);
    w.frame(ImVec2(-1, -1), false);
    REQUIRE(w.c->space().close_ups());
    REQUIRE(w.view->prefs().close_ups);
    w.click("toolbar:close-ups");
    CHECK_FALSE(w.c->space().close_ups());
    CHECK_FALSE(w.view->prefs().close_ups);
    w.click("toolbar:close-ups");
    CHECK(w.c->space().close_ups());
  }
  // A window whose prefs say "whole" shows its first grid whole, and every new search (one
  // window at a time: each owns the ImGui context). The prefs reach the controller as the
  // window passes them.
  app::UiPrefs whole;
  whole.close_ups = false;
  app::GalleryOptions launch;
  launch.catalogue = &spaces::catalogue();
  launch.space = "body";
  launch.session_path = dir.path / "t.json";
  launch.resume = app::ResumePolicy::kNo;
  app::ControllerOptions o = app::controller_options(launch, whole);
  o.log = false;
  InProcessWindow v(o, whole);
  CHECK_FALSE(v.c->space().close_ups());  // before the first frame is drawn
  v.frame(ImVec2(-1, -1), false);
  CHECK_FALSE(v.c->space().close_ups());
  v.c->queue(intent::StartNew{});
  for (int i = 0; i < 2; ++i) v.frame(ImVec2(-1, -1), false);
  CHECK_FALSE(v.c->space().close_ups());
}

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
    // And how the components overlap (the built-in ones are turned to carry stature and
    // mass): the RMS vertex distance's Gram matrix, whose diagonal is the scale squared.
    const Eigen::MatrixXd metric = c.session().search().options().perceptual_metric;
    REQUIRE(metric.rows() == scale.size());
    CHECK((metric.diagonal().cwiseSqrt() - scale).cwiseAbs().maxCoeff() < 1e-4 * scale.maxCoeff());
    CHECK((metric - c.space().perception()->perceptual_metric()).norm() < 1e-9 * metric.norm());
    // No grid the window shows holds two look-alike cells.
    const auto cells = c.session().cells();
    std::vector<Eigen::VectorXd> xs;
    for (const auto& p : cells) xs.push_back(p.x);
    const Eigen::MatrixXd d = c.space().perception()->perceptual_distance()(xs);
    double closest = 1e300;
    for (Eigen::Index i = 0; i < d.rows(); ++i)
      for (Eigen::Index j = i + 1; j < d.cols(); ++j) closest = std::min(closest, d(i, j));
    CHECK(closest >= app::kCloneMm);
    // Its planes are centred on the estimate of the body in mind, with the body population.
    CHECK(c.session().search().options().population.mean.size() == scale.size());
    c.queue(intent::ClickCell{1, 1});
    c.begin_frame(0.0);
  }
  {
    // A file saved before the target estimate existed has no population, and one saved before
    // the full metric none of that: take them out.
    nlohmann::json saved;
    std::ifstream(session) >> saved;
    int removed = 0;
    const auto strip = [&removed](nlohmann::json& node, const auto& self) -> void {
      if (!node.is_object() && !node.is_array()) return;
      if (node.is_object()) {
        removed += static_cast<int>(node.erase("population_mean") + node.erase("population_sd") +
                                    node.erase("perceptual_metric"));
      }
      for (auto& child : node) self(child, self);
    };
    strip(saved, strip);
    REQUIRE(removed == 3);
    std::ofstream(session) << saved.dump();
  }
  app::ControllerOptions resumed = options(session, "body");
  resumed.resume = app::ResumePolicy::kYes;
  GalleryController c(resumed, &spaces::open_space, 0.0);
  CHECK(c.session().clicks_on_plane() == 1);
  CHECK(c.session().has_perceptual_distance());
  // Resumed, it is centred on the estimate too from its next plane on, in the full metric.
  CHECK(c.session().search().options().population.mean.size() == c.session().settings().components);
  CHECK(c.session().search().options().perceptual_metric.rows() ==
        c.session().settings().components);
  // The photo space has its own, in colour differences: no two cells within one JND.
  c.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
  c.begin_frame(0.1);
  CHECK(c.session().has_perceptual_distance());
  CHECK(c.session().zoom_policy().look_alike_mm == Approx(spaces::kPhotoDistinctDeltaE));
  CHECK(c.session().search().options().perceptual_scale.size() == 12);
  CHECK(c.session().search().options().perceptual_metric.size() == 0);  // seen independently
  CHECK(c.session().search().options().min_plane_length == Approx(spaces::kPhotoMinPlaneDeltaE));
}

TEST_CASE("what a space's perception gives a session follows the cells' size, as render-grid's",
          "[gallery][zoom][metric]") {
  // One function serves the window and `render-grid`: a new session takes everything, sized
  // for its cells; a restored one keeps its scale and gains only what it was saved without.
  const auto space = spaces::open_space({"body", "neutral", 10});
  const app::SpacePerception* perception = space->perception();
  REQUIRE(perception != nullptr);
  app::SessionSettings settings;
  settings.space = "body";
  settings.components = space->dimensions();
  const auto installed = [&](int cell_px) {
    app::Session session(settings);
    app::install_perception(session, *perception, cell_px, true);
    return session;
  };
  const app::Session small = installed(120);
  const app::Session large = installed(400);
  const sps::SearchOptions& o = small.search().options();
  REQUIRE(o.perceptual_scale.size() == 10);
  CHECK(o.perceptual_metric.rows() == 10);
  CHECK(o.population.mean.size() == 10);
  CHECK(o.plane_axes == perception->plane_axes());
  CHECK(o.choice_region_slack == Approx(spaces::kBodyChoiceRegionSlack));  // the body's regions
  CHECK(o.min_plane_length == Approx(perception->min_plane_length(120)));
  CHECK(o.choice_temperature_mm == Approx(perception->choice_temperature(120)));
  CHECK(o.uncertainty_min_side == Approx(perception->uncertainty_min_side(120)));
  CHECK(small.has_perceptual_distance());
  // Larger cells show finer differences: shorter planes, finer look-alike threshold (at 230
  // px and above a close-up's planes are at the optimizer's own floor).
  CHECK(large.search().options().min_plane_length < o.min_plane_length);
  CHECK(large.zoom_policy().look_alike_mm < small.zoom_policy().look_alike_mm);
  // Resized cells: the zoom at once, the plane length from the next plane on.
  app::Session resized = installed(120);
  app::follow_cell_size(resized, *perception, 400);
  CHECK(resized.zoom_policy().look_alike_mm == Approx(large.zoom_policy().look_alike_mm));
  CHECK(resized.search().options().min_plane_length ==
        Approx(large.search().options().min_plane_length));
  // A person who sees coarser differences in smaller cells needs longer planes to tell a deep
  // zoom level's cells apart.
  CHECK(o.uncertainty_min_side > large.search().options().uncertainty_min_side);
  CHECK(resized.search().options().uncertainty_min_side ==
        Approx(large.search().options().uncertainty_min_side));
  // A session saved on another model (its scale not this metric's diagonal) keeps its scale
  // alone; one saved on this model without the metric gains it.
  const Eigen::VectorXd scale = perception->perceptual_scale();
  CHECK(app::usable_metric(*perception, 1.01 * scale).size() == 0);
  CHECK(app::usable_metric(*perception, scale.head(9)).size() == 0);
  app::Session other(settings);
  other.set_perceptual_scale(1.01 * scale);
  app::install_perception(other, *perception, 230, true);
  CHECK((other.search().options().perceptual_scale - 1.01 * scale).norm() < 1e-12);
  CHECK(other.search().options().perceptual_metric.size() == 0);
  app::Session same(settings);
  same.set_perceptual_scale(scale);
  app::install_perception(same, *perception, 230, true);
  CHECK(same.search().options().perceptual_metric.rows() == 10);
}

namespace {

double number(const app::DesignSpace& space, const Eigen::VectorXd& x, const std::string& name) {
  for (const auto& [key, value] : space.numbers(*space.prepare(x, true))) {
    if (key == name) return value;
  }
  return std::nan("");
}

// Height (m) of the body at x in a space, as the inspector measures it.
double height_at(const app::DesignSpace& space, const Eigen::VectorXd& x) {
  for (const auto& [name, value] : space.numbers(*space.prepare(x, true))) {
    if (name == "height_m") return value;
  }
  return -1.0;
}

// Prefs that show the New-search tab.
app::UiPrefs prefs_with_open_panel() {
  app::UiPrefs p;
  p.side_tab = "new-search";
  return p;
}

}  // namespace

TEST_CASE("holds through the controller: every cell held, choices learnt, release keeps data",
          "[gallery][holds]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
  double t = finish_plane(c, 0.0);
  REQUIRE(c.session().planes_done() == 1);
  const int preferences = c.session().search().data().preference_count();

  c.queue(intent::SetHolds{{"height=1.80"}});
  CHECK(c.holds().empty());  // nothing until the next frame
  c.begin_frame(t += 1.0);
  REQUIRE(c.holds().size() == 1);
  CHECK_THAT(c.holds_description(), Catch::Contains("height 180.0 cm"));
  for (const auto& cell : c.displayed_cells()) {
    CHECK(std::abs(number(c.space(), cell.x, "height_m") - 1.80) <= 0.01);
    CHECK(cell.x.minCoeff() >= 0.0);
    CHECK(cell.x.maxCoeff() <= 1.0);
  }
  // A held plane: the choice the optimizer learns is a held body.
  t = finish_plane(c, t);
  REQUIRE(c.session().planes_done() == 2);
  CHECK(std::abs(number(c.space(), c.session().history().back().chosen, "height_m") - 1.80) <=
        0.01);
  CHECK(c.session().search().data().preference_count() > preferences);
  const int held_preferences = c.session().search().data().preference_count();

  // Asked while the optimizer runs: applied once its result is in, never discarding it.
  const int levels = c.session().settings().zoom_levels;
  for (int i = 0; i < levels; ++i) {
    c.queue(intent::ClickCell{i % 3, 2});
    c.begin_frame(t += 0.1);
    if (i + 1 < levels) c.begin_frame(t += 5.0);  // let the zoom finish
  }
  REQUIRE(c.busy());
  c.queue(intent::SetHolds{{"height=1.80", "mass=85"}});
  c.begin_frame(t += 0.1);
  c.wait_for_optimizer(t += 0.1);
  c.begin_frame(t += 0.1);
  CHECK(c.session().planes_done() == 3);
  REQUIRE(c.holds().size() == 2);
  for (const auto& cell : c.session().cells()) {
    CHECK(std::abs(number(c.space(), cell.x, "height_m") - 1.80) <= 0.01);
    CHECK(std::abs(number(c.space(), cell.x, "mass_kg") - 85.0) <= 1.5);
  }
  // Still nine bodies to choose from: a centre moved onto the new holds once sat on four
  // faces of the box and the plane there came out as one point, nine identical cells.
  {
    const auto& cells = c.session().cells();
    double spread = 0.0;
    for (const auto& cell : cells) spread = std::max(spread, (cell.x - cells[4].x).norm());
    CHECK(spread > 0.05);
  }

  // Releasing the holds keeps every choice.
  const int before_release = c.session().search().data().preference_count();
  CHECK(before_release > held_preferences);
  c.queue(intent::SetHolds{{}});
  c.begin_frame(t += 1.0);
  CHECK(c.holds().empty());
  CHECK(c.session().constraint_projector() == nullptr);
  CHECK(c.session().planes_done() == 3);
  CHECK(c.session().search().data().preference_count() == before_release);
  CHECK_THAT(c.message().text, Catch::Contains("all your choices are kept"));

  // Bad holds: a message, nothing changed.
  c.queue(intent::SetHolds{{"weight=80"}});
  c.begin_frame(t += 1.0);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.holds().empty());

  // "Go": the nearest body with the typed mass becomes the current best.
  c.queue(intent::GoToTargets{{"mass=80"}});
  c.begin_frame(t += 1.0);
  c.wait_for_optimizer(t += 0.1);
  CHECK(c.session().planes_done() == 4);
  CHECK(std::abs(number(c.space(), c.session().current_best(), "mass_kg") - 80.0) <= 0.75);
  // Out of reach: the message names the nearest reachable value; nothing submitted.
  c.queue(intent::GoToTargets{{"height=2.6"}});
  c.begin_frame(t += 1.0);
  CHECK_FALSE(c.busy());
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK_THAT(c.message().text, Catch::Contains("nearest reachable"));

  // A photo has nothing to hold.
  c.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
  c.begin_frame(t += 1.0);
  c.queue(intent::SetHolds{{"height"}});
  c.begin_frame(t += 1.0);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK_THAT(c.message().text, Catch::Contains("no measurements to hold"));
}

TEST_CASE("holds survive a restart: saved with the session, held again on resume",
          "[gallery][holds]") {
  TempDir dir;
  const fs::path file = dir.path / "s.json";
  std::vector<Eigen::VectorXd> held_cells;
  {
    GalleryController c(options(file, "body"), &spaces::open_space, 0.0);
    double t = finish_plane(c, 0.0);
    c.queue(intent::SetHolds{{"height=1.75", "mass"}});
    c.begin_frame(t += 1.0);
    REQUIRE(c.holds().size() == 2);
    for (const auto& cell : c.session().cells()) held_cells.push_back(cell.x);
    c.save_now();
  }
  auto resumed_options = options(file, "body");
  resumed_options.resume = app::ResumePolicy::kYes;
  GalleryController c(resumed_options, &spaces::open_space, 0.0);
  c.begin_frame(1.0);
  REQUIRE(c.holds().size() == 2);
  CHECK_THAT(c.holds_description(), Catch::Contains("height 175.0 cm"));
  CHECK_THAT(c.holds_description(), Catch::Contains("mass"));
  const auto cells = c.session().cells();
  REQUIRE(cells.size() == held_cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    CHECK(std::abs(number(c.space(), cells[i].x, "height_m") - 1.75) <= 0.01);
    CHECK((cells[i].x - held_cells[i]).norm() < 1e-6);
  }
  // A name the space does not know: a message, the session still opens.
  {
    std::ifstream in(file);
    nlohmann::json j = nlohmann::json::parse(in);
    j["holds"][0]["name"] = "weight";
    std::ofstream(file) << j.dump();
  }
  GalleryController d(resumed_options, &spaces::open_space, 0.0);
  d.begin_frame(1.0);
  CHECK(d.holds().empty());
  CHECK(d.message().kind == app::MessageKind::kError);
  CHECK_THAT(d.message().text, Catch::Contains("weight"));
}

TEST_CASE("the New-search panel starts a search on the chosen body model and remembers it",
          "[gallery][gl][model-picker]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  app::UiPrefs remembered;
  {
    InProcessWindow w(options(session, "body"), prefs_with_open_panel(), ImVec2(1280, 900));
    for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
    // First launch: neutral preselected, and the search is on the neutral model.
    CHECK(w.view->model_choice() == "neutral");
    CHECK(w.c->space().source_label() == "neutral (built-in)");
    REQUIRE(w.view->widget("model:female"));
    REQUIRE(w.view->widget("toolbar:model"));
    const int generation = w.c->space_generation();

    w.click("model:female");
    CHECK(w.view->model_choice() == "female");
    CHECK(w.c->space_generation() == generation);  // choosing alone starts nothing
    w.click("new-search");
    w.frame(ImVec2(-1, -1), false);
    CHECK(w.c->space_generation() != generation);
    CHECK(w.c->message().kind == app::MessageKind::kSuccess);
    CHECK(w.c->space().settings().source == "female");
    CHECK(w.c->space().source_label() == "female (built-in)");
    CHECK(w.c->session().settings().model_path == "female");
    CHECK(w.c->session().settings().components == 10);
    // It is the female model: its mean body is the female model's, not the neutral one's.
    const Eigen::VectorXd mean = Eigen::VectorXd::Constant(10, 0.5);
    const auto female = spaces::open_space({"body", "female", 10});
    const auto neutral = spaces::open_space({"body", "neutral", 10});
    const double h = height_at(w.c->space(), mean);
    CHECK(std::abs(h - height_at(*female, mean)) < 1e-9);
    CHECK(std::abs(h - height_at(*neutral, mean)) > 0.01);
    // The autosaved session records it.
    const auto saved = app::load_session(session);
    REQUIRE(saved.session);
    CHECK(saved.session->settings().model_path == "female");
    // The choice is in the prefs, and survives the file.
    CHECK(w.view->prefs().sources.at("body_model") == "female");
    REQUIRE(app::save_ui_prefs(w.view->prefs(), app::ui_prefs_path(session)));
    remembered = app::load_ui_prefs(app::ui_prefs_path(session));
  }
  CHECK(remembered.sources.at("body_model") == "female");

  // The next launch (a fresh session file, so no resume question) starts on the female model
  // with Female preselected...
  app::GalleryOptions launch;
  launch.catalogue = &spaces::catalogue();
  launch.session_path = dir.path / "next.json";
  launch.resume = app::ResumePolicy::kNo;
  {
    app::ControllerOptions o = app::controller_options(launch, remembered);
    o.log = false;
    InProcessWindow w(o, remembered, ImVec2(1280, 900));
    w.frame(ImVec2(-1, -1), false);
    CHECK(w.c->space().settings().source == "female");
    CHECK(w.view->model_choice() == "female");
  }
  // ...unless --model says otherwise for that launch, which is not remembered.
  launch.source = "male";
  {
    app::ControllerOptions o = app::controller_options(launch, remembered);
    o.log = false;
    InProcessWindow w(o, remembered, ImVec2(1280, 900));
    w.frame(ImVec2(-1, -1), false);
    CHECK(w.c->space().settings().source == "male");
    CHECK(w.view->model_choice() == "male");  // the panel shows the search's model
    CHECK(w.view->prefs().sources.at("body_model") == "female");
  }
}

TEST_CASE("a broken model file is refused by name and the current search goes on untouched",
          "[gallery][gl][model-picker]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  const fs::path broken = dir.path / "broken.npz";
  std::ofstream(broken) << "this is not a zip archive";
  InProcessWindow w(options(session, "body"), prefs_with_open_panel(), ImVec2(1280, 900));
  w.frame(ImVec2(-1, -1), false);
  w.frame(ImVec2(-1, -1), false);  // the remembered tab shows from the second frame
  w.click("model:male");
  w.c->queue(intent::ClickCell{1, 1});  // progress: a new search asks first
  w.frame(ImVec2(-1, -1), false, 5.0);
  REQUIRE(w.c->session().clicks_on_plane() == 1);
  const Eigen::VectorXd best = w.c->session().current_best();
  const int generation = w.c->space_generation();

  w.view->set_model_file(broken.string());
  w.frame(ImVec2(-1, -1), false);
  CHECK(w.view->model_choice() == "file");
  w.click("new-search");
  REQUIRE(w.view->widget("confirm:start"));  // asked before discarding
  CHECK(w.c->space().settings().source.empty());
  w.click("confirm:start");
  w.frame(ImVec2(-1, -1), false);
  // Refused, naming the file and the problem.
  CHECK(w.c->message().kind == app::MessageKind::kError);
  INFO(w.c->message().text);
  CHECK(w.c->message().text.find(broken.string()) != std::string::npos);
  CHECK(w.c->message().text.find("zip") != std::string::npos);
  // The search, its space and its file are as they were; nothing was set aside.
  CHECK(w.c->space_generation() == generation);
  CHECK(w.c->space().settings().source.empty());
  CHECK(w.c->session().clicks_on_plane() == 1);
  CHECK((w.c->session().current_best() - best).norm() < 1e-12);
  CHECK_FALSE(fs::exists(session.string() + ".previous"));
  const auto saved = app::load_session(session);
  REQUIRE(saved.session);
  CHECK(saved.session->clicks_on_plane() == 1);
  // A file that failed is not remembered.
  CHECK(spaces::remembered_body_model(w.view->prefs().sources) == "neutral");

  // An SMPL .pkl gets told how to convert it.
  const fs::path pkl = dir.path / "basicmodel_f.pkl";
  std::ofstream(pkl) << "\x80\x02}q\x00.";
  w.c->queue(intent::Open{{"body", pkl.string(), 10}, 0, 4});
  w.frame(ImVec2(-1, -1), false);
  CHECK(w.c->message().kind == app::MessageKind::kError);
  CHECK(w.c->message().text.find("basicmodel_f.pkl") != std::string::npos);
  CHECK(w.c->message().text.find("smpl_pkl_to_npz") != std::string::npos);
  CHECK(w.c->session().clicks_on_plane() == 1);
}

TEST_CASE("a session on another model than the remembered one resumes on its own model",
          "[gallery][model-picker]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    auto o = options(session, "body");
    o.space.source = "female";
    GalleryController first(o, &spaces::open_space, 0.0);
    first.queue(intent::ClickCell{2, 0});
    first.begin_frame(0.0);
    first.save_now();
  }
  app::UiPrefs prefs;
  prefs.sources["body_model"] = "male";
  app::GalleryOptions launch;
  launch.catalogue = &spaces::catalogue();
  launch.session_path = session;
  launch.resume = app::ResumePolicy::kYes;
  {
    app::ControllerOptions o = app::controller_options(launch, prefs);
    o.log = false;
    GalleryController c(o, &spaces::open_space, 0.0);
    CHECK(c.space().settings().source == "female");
    CHECK(c.session().clicks_on_plane() == 1);
    CHECK(c.session().path()[0].col == 2);
  }
  // Asked: the question names the session's model; "Start new" starts on the remembered one.
  launch.resume = app::ResumePolicy::kAsk;
  app::ControllerOptions o = app::controller_options(launch, prefs);
  o.log = false;
  GalleryController c(o, &spaces::open_space, 0.0);
  REQUIRE(c.resume_candidate() != nullptr);
  CHECK(c.resume_description().find("female") != std::string::npos);
  c.queue(intent::StartNew{});
  c.begin_frame(0.1);
  CHECK(c.space().settings().source == "male");
  CHECK(c.session().settings().model_path == "male");
  CHECK(c.session().clicks_on_plane() == 0);
  CHECK(fs::exists(session.string() + ".previous"));  // the female session is kept
}

TEST_CASE("ui prefs are written when they change, once they settle, atomically",
          "[gallery][ui-prefs]") {
  TempDir dir;
  const fs::path path = app::ui_prefs_path(dir.path / "session.json");
  app::UiPrefsSaver saver(path, app::load_ui_prefs(path), 1.0);
  app::UiPrefs p = app::load_ui_prefs(path);
  CHECK_FALSE(saver.update(p, 0.0));  // unchanged: nothing to write
  CHECK_FALSE(fs::exists(path));
  p.sources["body_model"] = "female";
  CHECK_FALSE(saver.update(p, 0.1));  // changed: wait for it to settle
  CHECK_FALSE(saver.update(p, 0.6));
  // A window being resized changes the prefs every frame: each change restarts the wait.
  p.window_width = 1300;
  p.window_height = 800;
  CHECK_FALSE(saver.update(p, 0.9));
  p.window_width = 1320;
  CHECK_FALSE(saver.update(p, 1.0));
  CHECK_FALSE(saver.update(p, 1.9));
  CHECK_FALSE(fs::exists(path));
  CHECK(saver.update(p, 2.05));  // settled for a second: written
  CHECK(saver.writes() == 1);
  const app::UiPrefs read = app::load_ui_prefs(path);
  CHECK(read.sources.at("body_model") == "female");
  CHECK(read.window_width == 1320);
  CHECK(read == p);
  // Nothing but the file itself in the folder (the atomic write's temporary is gone).
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir.path)) {
    INFO(e.path());
    CHECK(e.path() == path);
    ++files;
  }
  CHECK(files == 1);
  CHECK_FALSE(saver.update(p, 5.0));  // written once, not every frame
  CHECK(saver.writes() == 1);
  // A change undone before it settles writes nothing.
  app::UiPrefs q = p;
  q.view_preset = 1;
  CHECK_FALSE(saver.update(q, 6.0));
  CHECK_FALSE(saver.update(p, 6.5));
  CHECK_FALSE(saver.update(p, 9.0));
  CHECK(saver.writes() == 1);
  // At exit, a change that has not settled yet is written at once.
  q.side_tab = "history";
  CHECK_FALSE(saver.update(q, 10.0));
  CHECK(saver.flush(q));
  CHECK(saver.writes() == 2);
  CHECK(app::load_ui_prefs(path) == q);

  // A folder that cannot hold the file: no crash, tried again later, flush says it failed.
  std::ofstream(dir.path / "a-file") << "x";
  app::UiPrefsSaver stuck(dir.path / "a-file" / "ui.json", app::UiPrefs{}, 1.0);
  CHECK_FALSE(stuck.update(q, 0.0));
  CHECK_FALSE(stuck.update(q, 1.5));
  CHECK_FALSE(stuck.update(q, 3.0));
  CHECK(stuck.writes() == 0);
  CHECK_FALSE(stuck.flush(q));
}

TEST_CASE("asking for more components than the body model has says so", "[gallery]") {
  TempDir dir;
  auto o = options(dir.path / "s.json", "body");
  o.space.source = "female";
  o.space.dimensions = 40;
  GalleryController c(o, &spaces::open_space, 0.0);
  const int has = c.space().dimensions();
  REQUIRE(has < 40);  // the built-in models keep 16
  CHECK(c.session().settings().components == has);
  CHECK(c.message().kind == app::MessageKind::kError);
  INFO(c.message().text);
  CHECK(c.message().text.find("only " + std::to_string(has) + " components") != std::string::npos);
  CHECK(c.message().text.find("40") != std::string::npos);
  // A new search asking for too many says so too; one within the model's count does not.
  c.queue(intent::Open{{"body", "male", 50}, 0, 4});
  c.begin_frame(0.1);
  CHECK(c.space().settings().source == "male");
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK(c.message().text.find("new search started") != std::string::npos);
  CHECK(c.message().text.find("50") != std::string::npos);
  c.queue(intent::Open{{"body", "male", 8}, 0, 4});
  c.begin_frame(0.2);
  CHECK(c.message().kind == app::MessageKind::kSuccess);
  CHECK(c.space().dimensions() == 8);
}

// A click, then a frame long after it so that its zoom animation has ended.
double click_and_settle(GalleryController& c, int col, int row, double t) {
  c.queue(intent::ClickCell{col, row});
  c.begin_frame(t);
  c.begin_frame(t + 5.0);
  return t + 10.0;
}

TEST_CASE("a second window on the same session views it read-only and never saves over it",
          "[gallery][session-lock]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  auto o = options(session);
  o.resume = app::ResumePolicy::kYes;
  o.perceptual_zoom = false;  // three clicks on one plane
  GalleryController a(o, &spaces::open_space, 0.0);
  CHECK_FALSE(a.open_elsewhere());
  (void)click_and_settle(a, 0, 0, 0.0);
  (void)click_and_settle(a, 1, 1, 5.0);
  REQUIRE(app::read_session_file(session).clicks_on_plane() == 2);
  {
    auto ask = o;
    ask.resume = app::ResumePolicy::kAsk;
    GalleryController b(ask, &spaces::open_space, 0.0);
    CHECK(b.open_elsewhere());
    CHECK_FALSE(b.autosave_enabled());
    CHECK_THAT(b.autosave_problem(), Catch::Contains("open in another window"));
    REQUIRE(b.resume_candidate() != nullptr);  // offered read-only
    b.queue(intent::Resume{});
    b.begin_frame(0.1);
    CHECK(b.session().clicks_on_plane() == 2);
    (void)click_and_settle(b, 2, 2, 5.0);
    b.save_now();  // as at exit
    CHECK(b.session().clicks_on_plane() == 3);
  }
  // B's click and exit changed nothing on disk; A continues and saves.
  CHECK(app::read_session_file(session).clicks_on_plane() == 2);
  CHECK_FALSE(fs::exists(fs::path(session.string() + ".previous")));
  (void)click_and_settle(a, 2, 0, 10.0);
  CHECK(app::read_session_file(session).clicks_on_plane() == 3);
}

TEST_CASE("a new search in a read-only window moves nothing aside", "[gallery][session-lock]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  auto o = options(session);
  o.resume = app::ResumePolicy::kYes;
  GalleryController a(o, &spaces::open_space, 0.0);
  (void)click_and_settle(a, 0, 0, 0.0);
  auto ask = o;
  ask.resume = app::ResumePolicy::kAsk;
  GalleryController b(ask, &spaces::open_space, 0.0);
  REQUIRE(b.open_elsewhere());
  b.queue(intent::StartNew{});
  b.begin_frame(0.1);
  (void)click_and_settle(b, 1, 1, 5.0);
  b.queue(intent::Open{spaces::default_settings("photo"), 0, 4});
  b.begin_frame(10.0);
  CHECK_FALSE(fs::exists(fs::path(session.string() + ".previous")));
  CHECK(app::read_session_file(session).clicks_on_plane() == 1);
}

TEST_CASE("the lock goes with the window: a later window owns the session again",
          "[gallery][session-lock]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  auto o = options(session);
  o.resume = app::ResumePolicy::kYes;
  {
    GalleryController a(o, &spaces::open_space, 0.0);
    (void)click_and_settle(a, 0, 0, 0.0);
  }
  GalleryController b(o, &spaces::open_space, 0.0);
  CHECK_FALSE(b.open_elsewhere());
  CHECK(b.session().clicks_on_plane() == 1);
  (void)click_and_settle(b, 1, 1, 5.0);
  CHECK(app::read_session_file(session).clicks_on_plane() == 2);
}

TEST_CASE("a window never saves over a session file another program replaced",
          "[gallery][session-lock]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  auto o = options(session);
  o.resume = app::ResumePolicy::kYes;
  GalleryController a(o, &spaces::open_space, 0.0);
  (void)click_and_settle(a, 0, 0, 0.0);
  // Another writer (an older build without the lock, a copy from a backup) replaces the file.
  {
    app::Session other = app::read_session_file(session);
    other.click({2, 2});
    other.click({2, 2});
    app::save_session(other, session);
  }
  const std::string replaced = [&] {
    std::ifstream in(session);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  (void)click_and_settle(a, 1, 1, 5.0);
  a.save_now();
  const std::string after = [&] {
    std::ifstream in(session);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const bool unchanged = after == replaced;  // not CHECK(a == b): Catch would print both files
  CHECK(unchanged);
  CHECK(app::read_session_file(session).clicks_on_plane() == 3);
  CHECK_FALSE(a.autosave_enabled());
  CHECK_THAT(a.autosave_problem(), Catch::Contains("changed by another window"));
  // This window's own state is kept beside it.
  int conflicts = 0;
  for (const auto& e : fs::directory_iterator(dir.path)) {
    if (e.path().filename().string().rfind("s.json.conflict-", 0) == 0) {
      ++conflicts;
      CHECK(app::read_session_file(e.path()).clicks_on_plane() == 2);
    }
  }
  CHECK(conflicts == 1);
}

TEST_CASE("a ui.json that cannot be used is reported, set aside and replaced by defaults",
          "[gallery][ui-prefs]") {
  TempDir dir;
  const fs::path path = dir.path / "ui.json";
  const auto set_aside_count = [&] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir.path)) {
      if (e.path().filename().string().rfind("ui.json.corrupt-", 0) == 0) ++n;
    }
    return n;
  };
  SECTION("not JSON") {
    std::ofstream(path) << "{\"window_width\": 1200,";
  }
  SECTION("nested 100,000 deep") {
    std::ofstream(path) << "{\"save_folder\": " << std::string(100000, '[')
                        << std::string(100000, ']') << "}";
  }
  SECTION("larger than 1 MB") {
    std::ofstream(path) << "{\"save_name\": \"" << std::string(2u << 20, 'a') << "\"}";
  }
  SECTION("a pipe (opening it used to wait forever)") {
    REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
  }
  SECTION("a link to an endless device") {
    fs::create_symlink("/dev/zero", path);
  }
  std::string problem;
  const app::UiPrefs p = app::load_ui_prefs(path, &problem);
  CHECK(p == app::UiPrefs{});
  CHECK_THAT(problem, Catch::Contains("ui.json"));
  CHECK_THAT(problem, Catch::Contains("using defaults"));
  CHECK(problem.size() < 400);
  CHECK(set_aside_count() == 1);
  CHECK_FALSE(fs::exists(fs::symlink_status(path)));
  // A good file next time reads without a problem.
  REQUIRE(app::save_ui_prefs(app::UiPrefs{}, path));
  std::string again;
  (void)app::load_ui_prefs(path, &again);
  CHECK(again.empty());
}

TEST_CASE("the grid takes the window's height, the toolbar heads the side column",
          "[gallery][layout]") {
  const auto inside = [](const app::LayoutRect& r, float w, float h) {
    return r.x >= 0 && r.y >= 0 && r.w > 0 && r.h > 0 && r.x + r.w <= w && r.y + r.h <= h;
  };
  const auto left_of = [](const app::LayoutRect& a, const app::LayoutRect& b) {
    return a.x + a.w <= b.x;
  };
  const auto above = [](const app::LayoutRect& a, const app::LayoutRect& b) {
    return a.y + a.h <= b.y;
  };
  // The default window: the cell size the benchmarks' pixel person assumes.
  const app::GalleryLayout d = app::compute_layout(1280, 720, 3);
  CHECK(static_cast<int>(d.cell) == app::kDefaultCellPx);
  CHECK(d.toolbar_rows == 2);
  const std::vector<std::pair<float, float>> sizes{
      {1280, 720}, {1920, 1080}, {800, 600}, {2560, 1000}, {640, 900}};
  for (const auto& [w, h] : sizes) {
    const app::GalleryLayout l = app::compute_layout(w, h, 3);
    INFO(w << "x" << h << ": cell " << l.cell << ", toolbar rows " << l.toolbar_rows);
    for (const auto* r : {&l.grid, &l.toolbar, &l.messages, &l.side}) CHECK(inside(*r, w, h));
    CHECK(l.grid.h == Approx(3 * l.cell + 2 * l.gap));
    CHECK(left_of(l.grid, l.toolbar));
    CHECK(left_of(l.grid, l.side));
    CHECK(above(l.toolbar, l.messages));
    CHECK(above(l.messages, l.side));
    // Nothing above the grid: it starts at the margin and grows until the window's height
    // or the side column's smallest width stops it (less what whole pixels per cell lose).
    CHECK(l.grid.y == Approx(app::kLayoutMargin));
    const bool height_bound = h - 2 * app::kLayoutMargin - l.grid.h < 3.5f;
    const bool width_bound =
        l.side.w < std::max(app::kSidePanelMinWidth, app::kSidePanelShare * w) + 3.5f;
    CHECK((height_bound || width_bound));
  }
  // A side column wide enough keeps the toolbar on one row; a narrow one wraps it.
  CHECK(app::compute_layout(2560, 1000, 3).toolbar_rows == 1);
  CHECK(app::toolbar_rows_for(300) == 3);
  // The rows the view really drew take precedence over the estimate.
  const app::GalleryLayout three = app::compute_layout(1280, 720, 3, 0, 3);
  CHECK(three.toolbar_rows == 3);
  CHECK(three.messages.y == Approx(three.toolbar.y + 3 * app::kToolbarRowHeight));
  CHECK(three.cell == d.cell);
  CHECK(app::compute_layout(1280, 720, 3, 0, 40).toolbar_rows == 6);
  // bench-gui's window for a given cell shows cells of that size.
  const auto [bw, bh] = app::window_size_for_cells(3, 300);
  CHECK(app::compute_layout(static_cast<float>(bw), static_cast<float>(bh), 3).cell >= 300);
}

TEST_CASE("a remembered window size is fitted to the screen's work area", "[gallery][layout]") {
  const app::WorkArea laptop{1280, 800};
  CHECK(app::fit_window_to(1600, 1000, laptop) == std::pair<int, int>{1216, 760});
  CHECK(app::fit_window_to(8192, 8192, laptop) == std::pair<int, int>{1216, 760});
  CHECK(app::fit_window_to(1200, 700, laptop) == std::pair<int, int>{1200, 700});
  CHECK(app::fit_window_to(1600, 1000, app::WorkArea{}) == std::pair<int, int>{1600, 1000});
  CHECK(app::fit_window_to(1600, 1000, app::WorkArea{200, 100}) == std::pair<int, int>{320, 240});
}

TEST_CASE("starting anew says where the previous session was kept, in words that read",
          "[gallery]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    GalleryController first(options(session), &spaces::open_space, 0.0);
    (void)click_and_settle(first, 1, 1, 0.0);
  }
  auto o = options(session);
  o.resume = app::ResumePolicy::kAsk;
  GalleryController c(o, &spaces::open_space, 0.0);
  c.queue(intent::StartNew{});
  c.begin_frame(0.1);
  // Was "new session; the previous one is it as ...".
  CHECK_THAT(c.message().text, Catch::Equals("new session; the previous one is kept as " +
                                             session.string() + ".previous"));
}

TEST_CASE("holds no body meets are refused in the window with the nearest reachable values",
          "[gallery][holds]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
  double t = 0.0;
  for (const std::vector<std::string>& holds :
       {std::vector<std::string>{"height=0.5"}, {"bmi=90"}, {"height=1.9", "mass=40", "bmi=40"}}) {
    c.queue(intent::SetHolds{holds});
    c.begin_frame(t += 1.0);
    CHECK(c.holds().empty());
    CHECK(c.message().kind == app::MessageKind::kError);
    CHECK_THAT(c.message().text, Catch::Contains("cannot hold that"));
  }
  CHECK_THAT(c.message().text, Catch::Contains("no body has all three"));
  // Typed targets are solved with the holds in force; one against a hold is refused.
  c.queue(intent::SetHolds{{"height=1.80"}});
  c.begin_frame(t += 1.0);
  REQUIRE(c.holds().size() == 1);
  c.queue(intent::GoToTargets{{"height=1.70"}});
  c.begin_frame(t += 1.0);
  CHECK(c.message().kind == app::MessageKind::kError);
  CHECK_THAT(c.message().text, Catch::Contains("contradicts the hold on height"));
}

TEST_CASE("Undo plane takes back one plane, not two, with several planes done", "[gallery]") {
  TempDir dir;
  auto o = options(dir.path / "s.json");
  o.zoom_levels = 2;
  GalleryController c(o, &spaces::open_space, 0.0);
  double t = 0.0;
  for (int plane = 0; plane < 3; ++plane) t = finish_plane(c, t);
  REQUIRE(c.session().planes_done() == 3);
  t = click_and_settle(c, 1, 0, t);  // on plane 4
  REQUIRE(c.session().clicks_on_plane() == 1);
  c.queue(intent::UndoPlane{});
  c.begin_frame(t);
  // Was: planes_done() == 1 ("undid plane 2" from plane 4).
  CHECK(c.session().planes_done() == 2);
  CHECK(c.session().clicks_on_plane() == 0);
  CHECK_THAT(c.message().text, Catch::Contains("undid plane 3"));
  c.queue(intent::UndoPlane{});
  c.begin_frame(t + 1.0);
  CHECK(c.session().planes_done() == 1);
}

TEST_CASE("Save never replaces a file the current search did not write without asking",
          "[gallery][gl][save]") {
  TempDir dir;
  app::UiPrefs prefs;
  prefs.save_folder = dir.path.string();
  prefs.save_name = "body.glb";
  prefs.side_tab = "save";
  InProcessWindow w(options(dir.path / "s.json", "body"), prefs);
  for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
  const fs::path file = dir.path / "body.glb";
  w.view->quick_save(*w.c);
  w.frame(ImVec2(-1, -1), false);
  REQUIRE(fs::exists(file));
  CHECK_FALSE(w.view->overwrite_question());
  // Saving again in the same search replaces its own file without a question.
  w.view->quick_save(*w.c);
  CHECK_FALSE(w.view->overwrite_question());
  w.frame(ImVec2(-1, -1), false);
  const auto size_before = fs::file_size(file);
  const auto time_before = fs::last_write_time(file);
  // A new search on another model: the same name now asks first (it replaced a finished
  // neutral body with a male one in the same file).
  w.c->queue(intent::Open{app::SpaceSettings{"body", "male", 10}, 0, 4});
  w.frame(ImVec2(-1, -1), false);
  REQUIRE(w.c->space().settings().source == "male");
  CHECK(w.c->last_export().empty());
  w.view->quick_save(*w.c);
  REQUIRE(w.view->overwrite_question());
  CHECK(*w.view->overwrite_question() == file);
  w.frame(ImVec2(-1, -1), false);
  CHECK(fs::file_size(file) == size_before);
  CHECK(fs::last_write_time(file) == time_before);
}

TEST_CASE("the default save folder is the documents folder, else home", "[gallery][save]") {
  TempDir dir;
  const char* old_home = std::getenv("HOME");
  const std::string saved = old_home != nullptr ? old_home : "";
  ::setenv("HOME", dir.path.c_str(), 1);
  CHECK(app::default_save_folder() == dir.path);
  fs::create_directories(dir.path / "Documents");
  CHECK(app::default_save_folder() == dir.path / "Documents");
  ::setenv("HOME", saved.c_str(), 1);
}

TEST_CASE("expert sliders say what they change, and a slider point keeps the holds",
          "[gallery][holds][sliders]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
  // Labels from the measured effect, not "shape 1 (66% var.)".
  const std::string first = c.space().dimension_name(0);
  INFO("component 1: " << first);
  CHECK(first.rfind("1: ", 0) == 0);
  CHECK(first.find("var.") == std::string::npos);
  // The first component of the neutral model is size and sex together; whichever measures it
  // changes most are named ("taller", "broader shoulders", "longer legs", ...).
  CHECK(first.find("shape") == std::string::npos);
  CHECK((first.find("taller") != std::string::npos || first.find("heavier") != std::string::npos ||
         first.find("broader") != std::string::npos || first.find("longer") != std::string::npos));
  CHECK_THAT(c.space().dimension_details(0),
             Catch::Contains("Height") && Catch::Contains("of the shape variance"));
  for (int i = 0; i < c.space().dimensions(); ++i) {
    CHECK(c.space().dimension_name(i).size() < 48);
  }
  // Hold the height, move a slider that changes it, use the point: the height stays held.
  double t = 0.0;
  c.queue(intent::SetHolds{{"height=1.70"}});
  c.begin_frame(t += 1.0);
  REQUIRE(c.holds().size() == 1);
  Eigen::VectorXd x = c.session().current_best();
  x[0] = 0.9;  // the first component changes height most
  c.queue(intent::UsePoint{x});
  c.begin_frame(t += 1.0);
  c.wait_for_optimizer(t += 1.0);
  c.begin_frame(t += 1.0);
  CHECK_THAT(c.message().text, Catch::Contains("the slider values, moved onto the holds") &&
                                   Catch::Contains("now the current best"));
  CHECK(std::abs(number(c.space(), c.session().current_best(), "height_m") - 1.70) <= 0.01);
  CHECK(c.holds().size() == 1);
}

TEST_CASE("why a plane ended early stays in the message that shows the next plane", "[gallery]") {
  TempDir dir;
  auto o = options(dir.path / "s.json", "body");
  o.zoom_levels = 8;  // deeper than the cells stay visibly different
  GalleryController c(o, &spaces::open_space, 0.0);
  // Shown whole (close-ups keep the centre's cells apart for all 8 levels).
  c.queue(intent::SetCloseUps{false});
  c.begin_frame(0.0);
  double t = 0.0;
  int clicks = 0;
  while (c.session().planes_done() == 0 && !c.session().submission_pending() && clicks < 8) {
    t = click_and_settle(c, 1, 1, t);
    ++clicks;
  }
  REQUIRE(c.session().submission_pending());
  REQUIRE(clicks < 8);  // it ended before the last level
  c.wait_for_optimizer(t);
  c.begin_frame(t + 1.0);
  REQUIRE(c.session().planes_done() == 1);
  // Was replaced within a second by "plane 1 done ...; here is the next one".
  CHECK_THAT(c.message().text,
             Catch::Contains("No visible change left") && Catch::Contains("plane 1 done"));
}

TEST_CASE("history thumbnails are drawn once: orbiting the grid redraws none of them",
          "[gallery][gl][history]") {
  TempDir dir;
  auto o = options(dir.path / "s.json", "body");
  o.zoom_levels = 2;
  InProcessWindow w(o);
  for (int plane = 0; plane < 3; ++plane) w.t = finish_plane(*w.c, w.t);
  REQUIRE(w.c->session().planes_done() == 3);
  for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
  CHECK(w.view->thumbnail_draws() == 3);
  // Every view preset (a camera change re-renders the grid and the previews).
  for (int preset : {1, 2, 0, 1}) {
    w.view->choose_view(preset);
    w.frame(ImVec2(-1, -1), false);
  }
  CHECK(w.view->thumbnail_draws() == 3);
  w.t = finish_plane(*w.c, w.t + 1.0);
  for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
  CHECK(w.view->thumbnail_draws() == 4);  // only the new entry
}

TEST_CASE("asking for a photo search while a body session waits offers that search by name",
          "[gallery]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    GalleryController body(options(session, "body"), &spaces::open_space, 0.0);
    (void)click_and_settle(body, 1, 1, 0.0);
  }
  auto o = options(session, "photo");
  o.resume = app::ResumePolicy::kAsk;
  o.space_chosen = true;  // --space photo
  GalleryController c(o, &spaces::open_space, 0.0);
  REQUIRE(c.resume_candidate() != nullptr);
  CHECK(c.asked_kind_instead() == "photo");
  c.queue(intent::StartNew{});
  c.begin_frame(0.1);
  CHECK(c.space().settings().kind == "photo");
  CHECK(fs::exists(fs::path(session.string() + ".previous")));  // the body search is kept
  // Without a space on the command line, a resumable session is just offered.
  auto plain = options(session, "body");
  plain.resume = app::ResumePolicy::kAsk;
  GalleryController d(plain, &spaces::open_space, 0.0);
  CHECK(d.asked_kind_instead().empty());
}

TEST_CASE("a session that names no kind is one of the catalogue's default kind", "[gallery]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  {
    app::SessionSettings s;  // no kind: the default one
    s.components = 10;
    REQUIRE(s.space.empty());
    app::save_session(app::Session(s), session);
  }
  auto o = options(session, "body");
  o.resume = app::ResumePolicy::kAsk;
  o.space_chosen = true;  // --space body, the default kind
  GalleryController c(o, &spaces::open_space, 0.0);
  REQUIRE(c.resume_candidate() != nullptr);
  CHECK(c.resume_kind() == spaces::catalogue().default_kind().name);
  CHECK(c.asked_kind_instead().empty());  // the same kind: a plain Resume
  c.queue(intent::Resume{});
  c.begin_frame(0.1);
  CHECK(c.space().settings().kind == spaces::catalogue().default_kind().name);
}

TEST_CASE("autosave on its own thread: nothing lost, nothing written over",
          "[gallery][background-save]") {
  TempDir dir;
  const fs::path session = dir.path / "s.json";
  auto o = options(session, "body");
  o.resume = app::ResumePolicy::kYes;
  o.background_autosave = true;
  {
    GalleryController c(o, &spaces::open_space, 0.0);
    double t = click_and_settle(c, 0, 0, 0.0);
    t = click_and_settle(c, 1, 1, t);
  }  // closing writes what is queued
  CHECK(app::read_session_file(session).clicks_on_plane() == 2);
  {
    GalleryController c(o, &spaces::open_space, 0.0);
    REQUIRE(c.session().clicks_on_plane() == 2);
    double t = click_and_settle(c, 2, 2, 0.0);
    c.save_now();
    CHECK(app::read_session_file(session).clicks_on_plane() == 3);
    CHECK(c.autosave_problem().empty());
    // A new search at once: the old search, with its last click, is set aside first.
    c.queue(intent::Open{app::SpaceSettings{"body", "male", 10}, 0, 4});
    c.begin_frame(t += 1.0);
    c.save_now();
    CHECK(app::read_session_file(fs::path(session.string() + ".previous")).clicks_on_plane() == 3);
    CHECK(app::read_session_file(session).settings().model_path == "male");
    // Another program replaces the file: this window keeps it and saves beside it.
    app::Session other = app::read_session_file(session);
    other.click({0, 0});
    app::save_session(other, session);
    const auto stamp = app::stamp_of(session);
    t = click_and_settle(c, 1, 0, t + 1.0);
    t = click_and_settle(c, 0, 1, t);
    c.save_now();
    CHECK(app::stamp_of(session) == stamp);
    CHECK_FALSE(c.autosave_enabled());
    CHECK_THAT(c.autosave_problem(), Catch::Contains("changed by another window"));
    int conflicts = 0;
    for (const auto& e : fs::directory_iterator(dir.path)) {
      conflicts += e.path().filename().string().rfind("s.json.conflict-", 0) == 0 ? 1 : 0;
    }
    CHECK(conflicts == 1);
  }
  CHECK(app::read_session_file(session).clicks_on_plane() == 1);  // the other program's
}

TEST_CASE("typed targets and the panel's units survive a relaunch", "[gallery][gl][ui-prefs]") {
  TempDir dir;
  const fs::path path = dir.path / "ui.json";
  app::UiPrefs p;
  p.typed_targets = {{"height", "180cm"}, {"mass", "85kg"}};
  p.imperial = true;
  REQUIRE(app::save_ui_prefs(p, path));
  const app::UiPrefs read = app::load_ui_prefs(path);
  CHECK(read.typed_targets.size() == 2);
  CHECK(read.typed_targets.at("height") == "180cm");
  CHECK(read.imperial);
  // The panel starts with them (it would have written back empty fields otherwise).
  InProcessWindow w(options(dir.path / "s.json", "body"), read);
  for (int i = 0; i < 3; ++i) w.frame(ImVec2(-1, -1), false);
  CHECK(w.view->prefs().typed_targets == read.typed_targets);
  CHECK(w.view->prefs().imperial);
  // Junk in the file is dropped, not trusted.
  std::ofstream(path) << R"({"typed_targets": {"height": 5, "waist": ")" << std::string(100, 'x')
                      << R"(", "hips": "100cm"}})";
  const app::UiPrefs junk = app::load_ui_prefs(path);
  CHECK(junk.typed_targets.size() == 1);
  CHECK(junk.typed_targets.count("hips") == 1);
}

TEST_CASE(
    "a body grid shown whole is framed to its tallest body, and its cells compare as they look",
    "[gallery][zoom]") {
  // The rule: headroom above the tallest body, never wider than the default.
  CHECK(app::cell_frame_scale(1.70) == Approx((1.70 + app::kCellHeadroomM) / app::kCellFrameTopM));
  CHECK(app::cell_frame_scale(2.2) == 1.0);
  CHECK(app::cell_frame_scale(0.3) == 0.5);
  CHECK(app::cell_frame_scale(std::nan("")) == 1.0);
  CHECK(app::cell_frame_scale(-1.0) == 1.0);
  const auto space = spaces::open_space({"body", "neutral", 10});
  CHECK(space->close_ups());  // the window's default
  CHECK_FALSE(space->set_close_ups(false));
  CHECK_FALSE(space->close_ups());
  const app::SpacePerception* perception = space->perception();
  REQUIRE(perception != nullptr);
  const body::Model& model = dynamic_cast<const spaces::BodySpace&>(*space).model();
  const body::StandingHeights heights(model);
  const body::ShapeDistance raw(model);
  // The mean body and two that differ in the most visible component.
  std::vector<Eigen::VectorXd> xs(3, Eigen::VectorXd::Constant(10, 0.5));
  xs[1][0] = 0.4;
  xs[2][0] = 0.6;
  CHECK(perception->grid_frame(xs).pivot_m == 0.0);  // the floor stays put
  const double scale = perception->grid_frame(xs).scale;
  CHECK(scale == Approx(app::cell_frame_scale(heights.tallest_m(xs))));
  // A grid of people about 1.7 m tall is shown about 15 % larger than a 2 m one.
  CHECK(scale > 0.75);
  CHECK(scale < 0.97);
  // The distance the zoom and the look-alike test use is what the framed grid shows: each
  // pair's largest vertex distance enlarged by the framing.
  const Eigen::MatrixXd seen = perception->perceptual_distance()(xs);
  const Eigen::MatrixXd body_mm = raw.pairwise_max_mm(xs);
  REQUIRE(seen.rows() == 3);
  for (Eigen::Index i = 0; i < 3; ++i) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      CHECK(seen(i, j) == Approx(body_mm(i, j) / scale).epsilon(1e-9).margin(1e-9));
    }
  }
  // A grid with a tall body in it keeps (nearly) the default framing; never wider.
  std::vector<Eigen::VectorXd> tall = xs;
  tall.emplace_back(Eigen::VectorXd::Constant(10, 0.5));
  tall.back()[0] = 1.0;
  CHECK(perception->grid_frame(tall).scale > scale);
  CHECK(perception->grid_frame(tall).scale <= 1.0);
}

TEST_CASE(
    "a band of heights framed fills the cell: the camera shows it where the default "
    "frame shows the whole body",
    "[gallery][zoom]") {
  // Project a point at height y on the body's plane with the framed camera, as the cells do.
  const auto screen_y = [](const render::Camera& camera, double y) {
    const glm::vec4 clip = camera.projection(1.0f) * camera.view() *
                           glm::vec4(0.0f, static_cast<float>(y), 0.0f, 1.0f);
    return static_cast<double>(clip.y / clip.w);
  };
  const render::Camera camera;
  // The default frame's ends are the constants' (render_tests hold the top).
  CHECK(screen_y(camera, app::kCellFrameTopM) == Approx(1.0).margin(0.01));
  CHECK(screen_y(camera, app::kCellFrameBottomM) == Approx(-1.0).margin(0.01));
  for (const auto& [bottom, top] :
       {std::pair{0.55, 1.85}, std::pair{0.2, 1.3}, std::pair{-0.05, 1.0}}) {
    CAPTURE(bottom, top);
    const app::GridFrame frame = app::cell_frame_for_band(bottom, top);
    CHECK(frame.scale == Approx((top - bottom) / (app::kCellFrameTopM - app::kCellFrameBottomM)));
    const render::Camera framed = camera.scaled_about_height(static_cast<float>(frame.scale),
                                                             static_cast<float>(frame.pivot_m));
    CHECK(screen_y(framed, bottom) == Approx(-1.0).margin(0.02));
    CHECK(screen_y(framed, top) == Approx(1.0).margin(0.02));
  }
  // The whole frame or more, nothing or junk: the default framing.
  CHECK(app::cell_frame_for_band(-0.2, 2.1).scale == 1.0);
  CHECK(app::cell_frame_for_band(1.0, 1.0).scale == 1.0);
  CHECK(app::cell_frame_for_band(std::nan(""), 1.0).scale == 1.0);
  CHECK(app::cell_frame_for_band(0.0, std::numeric_limits<double>::infinity()).scale == 1.0);
  // Never closer than a quarter of the default frame.
  CHECK(app::cell_frame_for_band(1.0, 1.01).scale == 0.25);
}

TEST_CASE("close-ups frame a grid on the band where its bodies differ and compare what is in view",
          "[gallery][zoom]") {
  const auto space = spaces::open_space({"body", "neutral", 10});
  REQUIRE(space->close_ups());
  const app::SpacePerception* perception = space->perception();
  REQUIRE(perception != nullptr);
  const body::Model& model = dynamic_cast<const spaces::BodySpace&>(*space).model();
  const body::GridFraming bands(model);
  const body::ShapeDistance raw(model);
  const body::StandingHeights heights(model);
  int close_ups = 0, whole = 0;
  for (int k = 0; k < 10; ++k) {
    CAPTURE(k);
    // A zoomed-in grid along one component: the mean body and two 0.3 SD either side.
    std::vector<Eigen::VectorXd> xs(3, Eigen::VectorXd::Constant(10, 0.5));
    xs[1][k] = 0.45;
    xs[2][k] = 0.55;
    const body::FramedBand framed = bands.frame(xs);
    const body::HeightBand& band = framed.band;
    const app::GridFrame frame = perception->grid_frame(xs);
    const double whole_scale = app::cell_frame_scale(heights.tallest_m(xs));
    CHECK(frame.scale <= whole_scale + 1e-12);
    // Every vertex that moves most across the grid is in the band (what the grid is about).
    const Eigen::VectorXf a = body::vertex_norms(raw.displacement_mm(xs[1], xs[0]));
    const Eigen::VectorXf b = body::vertex_norms(raw.displacement_mm(xs[2], xs[0]));
    const Eigen::VectorXf moves = a.cwiseMax(b);
    const std::vector<int>& in_view = framed.vertices;
    std::vector<bool> shown(static_cast<std::size_t>(model.vertex_count()), false);
    for (const int v : in_view) shown[static_cast<std::size_t>(v)] = true;
    int missed = 0;
    for (Eigen::Index v = 0; v < moves.size(); ++v) {
      if (moves[v] >= 0.8f * moves.maxCoeff() && !shown[static_cast<std::size_t>(v)]) ++missed;
    }
    CHECK(missed == 0);
    CHECK(band.height_m() >= body::BandRule{}.min_height_m - 1e-9);
    CHECK(band.top_m >= framed.tallest_m);
    if (frame.scale < 0.95 * whole_scale) {
      ++close_ups;
      // A close-up shows every head whole or none, and at least a trunk.
      CHECK(frame.scale >= 0.3);
      // Its look-alike distance is the largest distance in view, enlarged by the framing.
      const Eigen::MatrixXd seen = perception->perceptual_distance()(xs);
      const Eigen::MatrixXd in_band = raw.pairwise_max_mm(xs, in_view);
      for (Eigen::Index i = 0; i < 3; ++i) {
        for (Eigen::Index j = 0; j < 3; ++j) {
          CHECK(seen(i, j) == Approx(in_band(i, j) / frame.scale).margin(1e-6));
        }
      }
      CHECK(seen(1, 2) > raw.pairwise_max_mm(xs)(1, 2) / whole_scale);
    } else {
      ++whole;
      CHECK(frame.pivot_m == 0.0);
    }
  }
  // The trunk's components are shown close up. Component 1 of the built-in models is stature
  // alone (tools/default_model/pca.hpp): its most moving vertices are the heads, so it is shown
  // from the heads down at least a metre, the heads whole (checked above for every close-up by
  // the band's top: the tallest head).
  CHECK(close_ups >= 3);
  std::printf("close-ups on %d of 10 components, whole bodies on %d\n", close_ups, whole);
  // The same grid of one body, nothing to frame on: the whole body.
  const std::vector<Eigen::VectorXd> same(3, Eigen::VectorXd::Constant(10, 0.5));
  CHECK(perception->grid_frame(same).scale ==
        Approx(app::cell_frame_scale(heights.tallest_m(same))));
  // Shown whole again, the same grids compare over the whole body.
  space->set_close_ups(false);
  std::vector<Eigen::VectorXd> xs(3, Eigen::VectorXd::Constant(10, 0.5));
  xs[1][3] = 0.45;
  xs[2][3] = 0.55;
  CHECK(space->perception()->grid_frame(xs).scale ==
        Approx(app::cell_frame_scale(heights.tallest_m(xs))));
}

TEST_CASE("the Close-ups choice reaches the session's look-alike test and is remembered",
          "[gallery][zoom]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
  c.queue(intent::SetCellPixels{app::kDefaultCellPx});
  c.begin_frame(1.0);
  REQUIRE(c.space().close_ups());
  // A zoomed-in grid along a trunk component looks more different in a close-up.
  std::vector<Eigen::VectorXd> xs(3, Eigen::VectorXd::Constant(10, 0.5));
  int k = 0;
  for (; k < 10; ++k) {
    xs = std::vector<Eigen::VectorXd>(3, Eigen::VectorXd::Constant(10, 0.5));
    xs[1][k] = 0.45;
    xs[2][k] = 0.55;
    if (c.space().perception()->grid_frame(xs).scale < 0.8) break;
  }
  REQUIRE(k < 10);
  const double close = c.session().perceptual_distance()(xs)(1, 2);
  c.queue(intent::SetCloseUps{false});
  c.begin_frame(2.0);
  CHECK_FALSE(c.space().close_ups());
  const double whole = c.session().perceptual_distance()(xs)(1, 2);
  CHECK(whole < close);
  // The planes' smallest side follows what the framing shows.
  const double whole_plane = c.session().search().options().min_plane_length;
  const double whole_side = c.session().search().options().uncertainty_min_side;
  c.queue(intent::SetCloseUps{true});
  c.begin_frame(3.0);
  CHECK(c.session().perceptual_distance()(xs)(1, 2) == Approx(close));
  CHECK(c.session().search().options().min_plane_length <= whole_plane);
  CHECK(c.session().search().options().uncertainty_min_side < whole_side);
  // ui.json keeps the choice.
  app::UiPrefs prefs;
  prefs.close_ups = false;
  const auto path = dir.path / "ui.json";
  REQUIRE(app::save_ui_prefs(prefs, path));
  CHECK_FALSE(app::load_ui_prefs(path).close_ups);
  prefs.close_ups = true;
  REQUIRE(app::save_ui_prefs(prefs, path));
  CHECK(app::load_ui_prefs(path).close_ups);
}

TEST_CASE("the look-alike threshold follows the cells' size on screen", "[gallery][zoom]") {
  TempDir dir;
  GalleryController c(options(dir.path / "s.json", "body"), &spaces::open_space, 0.0);
  // No view has said how big its cells are: the session's default.
  CHECK(c.session().zoom_policy().distinct_mm == Approx(app::ZoomPolicy{}.distinct_mm));
  // The default window's cells: 2 px of a 2.14 m frame over 230 px are about 19 mm.
  c.queue(intent::SetCellPixels{app::kDefaultCellPx});
  c.begin_frame(1.0);
  const double at_default = c.session().zoom_policy().distinct_mm;
  CHECK(at_default == Approx(app::look_alike_mm(app::kDefaultCellPx)));
  CHECK(at_default == Approx(18.6).margin(0.2));
  // The planes to come are at least that long as a typical close-up shows them, as the
  // benchmark's pixel person has them (and never shorter than the optimizer's default).
  CHECK(c.session().search().options().min_plane_length ==
        Approx(std::max(sps::SearchOptions{}.min_plane_length,
                        at_default * spaces::typical_frame_scale(spaces::BodyFraming::kCloseUps))));
  // The uncertainty planes to come are at least 8 of those thresholds long, in RMS mm (a third
  // of it, as a close-up shows it): about 30 mm, beyond twice the smallest length (24 mm).
  const double side = c.session().search().options().uncertainty_min_side;
  CHECK(side == Approx(spaces::kBodyUncertaintySideThresholds * at_default *
                       spaces::typical_frame_scale(spaces::BodyFraming::kCloseUps) / 3.0));
  CHECK(side > 2.0 * c.session().search().options().min_plane_length);
  // And the estimate of the body in mind takes the choices as about as noisy as a third of it.
  CHECK(c.session().search().options().choice_temperature_mm ==
        Approx(app::choice_temperature_for_cells(app::kDefaultCellPx)));
  CHECK(app::choice_temperature_for_cells(app::kDefaultCellPx) == Approx(at_default / 3.0));
  CHECK(app::choice_temperature_for_cells(2000) == Approx(app::kChoiceTemperatureMm));
  // The benchmark's mm person: their threshold, never below the precise chooser's 3 mm.
  CHECK(app::choice_temperature_for_jnd_mm(10.0) == Approx(10.0));
  CHECK(app::choice_temperature_for_jnd_mm(0.0) == Approx(app::kChoiceTemperatureMm));
  CHECK(app::choice_temperature_for_jnd_mm(std::nan("")) == Approx(app::kChoiceTemperatureMm));
  // For a person at the window the planes run where that estimate is least certain.
  CHECK(c.session().search().options().plane_axes == sps::PlaneAxes::kTargetUncertainty);
  // Every grid of a plane clicked through at that size shows nine cells that differ by at
  // least that much, pairwise (or the plane ends early, the click being the choice).
  const auto distance = c.space().perception()->perceptual_distance();
  REQUIRE(distance);
  double t = 2.0;
  int zoomed_grids = 0;
  double first_closest = 0.0;
  for (int click = 0; click < 2 * c.session().settings().zoom_levels; ++click) {
    if (c.session().planes_done() > 0) break;  // the first plane was submitted
    {
      // Every grid of the first plane, its first (widened where the box has room) included.
      std::vector<Eigen::VectorXd> xs;
      for (const auto& p : c.session().cells()) xs.push_back(p.x);
      const Eigen::MatrixXd d = distance(xs);
      double closest = 1e9;
      for (Eigen::Index i = 0; i < d.rows(); ++i)
        for (Eigen::Index j = i + 1; j < d.cols(); ++j) closest = std::min(closest, d(i, j));
      INFO("zoom level " << c.session().path().size() << ": closest pair " << closest << " mm");
      // The first grid can only be widened as far as the box allows.
      if (!c.session().path().empty()) CHECK(closest >= at_default - 1e-6);
      if (c.session().path().empty()) first_closest = closest;
      ++zoomed_grids;
    }
    c.queue(intent::ClickCell{1, 1});
    c.begin_frame(t);
    t += 5.0;
    c.begin_frame(t);
    c.wait_for_optimizer(t);
  }
  std::printf(
      "at %d px cells: threshold %.1f mm, %d grids checked, the first's closest pair "
      "%.1f mm\n",
      app::kDefaultCellPx, at_default, zoomed_grids, first_closest);
  CHECK(c.session().zoom_policy().look_alike_mm == Approx(at_default));
  // Big cells show more: a 1000 px cell resolves 4.3 mm, never below the look-alike floor.
  c.queue(intent::SetCellPixels{1000});
  c.begin_frame(t += 1.0);
  CHECK(c.session().zoom_policy().distinct_mm == Approx(app::kCloneMm));
  // A new search keeps the cells' size.
  c.queue(intent::StartOver{});
  c.begin_frame(t += 1.0);
  CHECK(c.session().zoom_policy().distinct_mm == Approx(app::kCloneMm));
}

TEST_CASE("a kind added to the catalogue is offered in New search and opens its own files",
          "[gallery][gl][catalogue]") {
  // A third kind, registered beside the two the program has: the window is not edited for it.
  app::SpaceCatalogue kinds;
  for (const app::SpaceKind& k : spaces::catalogue().kinds()) kinds.add(k);
  int opened = 0;
  app::SpaceKind sketch;
  sketch.name = "sketch";
  sketch.label = "sketch lines";
  sketch.source_noun = "Sketch";
  sketch.source_option = "sketch";
  sketch.file_extensions = {".sketch"};
  sketch.open = [&opened](const app::SpaceSettings& s) -> std::unique_ptr<app::DesignSpace> {
    ++opened;
    throw std::runtime_error(s.source + ": sketches cannot be read yet");
  };
  kinds.add(sketch);
  TempDir dir;
  InProcessWindow w(options(dir.path / "s.json", "body"), prefs_with_open_panel(),
                    ImVec2(1280, 900), kinds);
  w.frame(ImVec2(-1, -1), false);
  w.frame(ImVec2(-1, -1), false);
  REQUIRE(w.view->widget("kind:sketch"));  // the New-search tab offers it
  REQUIRE(w.view->widget("kind:photo"));
  const fs::path file = dir.path / "Plan.SKETCH";
  w.view->open_dropped(*w.c, file.string());
  w.frame(ImVec2(-1, -1), false);
  // The dropped file went to the kind that takes its extension; its error is the message and
  // the body search goes on.
  CHECK(opened == 1);
  CHECK(w.c->message().kind == app::MessageKind::kError);
  CHECK_THAT(w.c->message().text, Catch::Contains("sketches cannot be read yet"));
  CHECK(w.c->space().settings().kind == "body");
}
