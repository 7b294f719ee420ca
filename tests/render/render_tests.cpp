// Renderer tests on a headless EGL context with a stand-in mesh (no body model needed).
#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/cell_visibility.hpp"
#include "render/body_renderer.hpp"
#include "render/camera.hpp"
#include "render/cell_framebuffer.hpp"
#include "render/headless_context.hpp"
#include "render/mesh_gpu.hpp"
#include "render/png_writer.hpp"
#include "sphere_mesh.hpp"

namespace {

struct Rgb {
  int r, g, b;
};

Rgb pixel(const std::vector<std::uint8_t>& px, int width, int x, int y) {
  const size_t i =
      (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
  return {px[i], px[i + 1], px[i + 2]};
}

int distance(Rgb a, Rgb b) {
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

render::HeadlessContext& context() {
  static render::HeadlessContext ctx;
  return ctx;
}

}  // namespace

TEST_CASE("headless context is an OpenGL 3.3+ core context", "[render]") {
  auto& ctx = context();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  CHECK(major * 10 + minor >= 33);
  CHECK_FALSE(ctx.renderer().empty());
}

TEST_CASE("a body renders into a multisampled cell framebuffer", "[render]") {
  context();
  const auto mesh = render_test::make_ellipsoid(0.25f, 0.85f, 0.15f);
  render::MeshGpu gpu;
  gpu.upload(mesh.positions.data(), mesh.normals.data(), mesh.vertex_count(), mesh.indices.data(),
             static_cast<int>(mesh.indices.size()));
  CHECK(gpu.bounds_min().y == Approx(0.0f).margin(1e-5));
  CHECK(gpu.bounds_max().y == Approx(1.7f).margin(1e-4));

  render::BodyRenderer renderer;
  render::Camera camera;
  render::CellFramebuffer fbo(200, 200, 4);
  fbo.begin();
  renderer.draw(gpu, camera, fbo.width(), fbo.height());
  fbo.end();
  render::check_gl("draw");
  const auto px = fbo.read_pixels();

  // The body covers the centre of the image; the corners are backdrop.
  const Rgb centre = pixel(px, 200, 100, 100);
  const Rgb corner = pixel(px, 200, 5, 195);
  CHECK(distance(centre, corner) > 40);
  // The contact shadow darkens the floor just beside the feet compared with further out.
  const char* out = std::getenv("SG_RENDER_TEST_PNG");
  if (out != nullptr) render::write_png(out, 200, 200, px);

  SECTION("an empty mesh draws only the backdrop") {
    render::MeshGpu none;
    fbo.begin();
    renderer.draw(none, camera, fbo.width(), fbo.height());
    fbo.end();
    const auto bg = fbo.read_pixels();
    CHECK(distance(pixel(bg, 200, 100, 100), pixel(px, 200, 100, 100)) > 40);
  }

  SECTION("updating positions moves the body") {
    auto moved = mesh;
    for (size_t i = 0; i < moved.positions.size(); i += 3) moved.positions[i] += 0.6f;
    gpu.update(moved.positions.data(), moved.normals.data(), moved.vertex_count());
    CHECK(gpu.bounds_min().x == Approx(0.35f).margin(1e-4));
    fbo.begin();
    renderer.draw(gpu, camera, fbo.width(), fbo.height());
    fbo.end();
    const auto px2 = fbo.read_pixels();
    CHECK(distance(pixel(px2, 200, 100, 100), centre) > 20);
  }
}

TEST_CASE("vertex tints colour the eyes: white, a dark iris, skin where none are given",
          "[render]") {
  context();
  const auto mesh = render_test::make_ellipsoid(0.25f, 0.85f, 0.15f);
  render::BodyRenderer renderer;
  render::Camera camera;
  render::CellFramebuffer fbo(100, 100, 0);
  const auto centre_with = [&](const float* tints) {
    render::MeshGpu gpu;
    gpu.upload(mesh.positions.data(), mesh.normals.data(), mesh.vertex_count(), mesh.indices.data(),
               static_cast<int>(mesh.indices.size()), tints);
    fbo.begin();
    renderer.draw(gpu, camera, 100, 100);
    fbo.end();
    return pixel(fbo.read_pixels(), 100, 50, 50);
  };
  const std::vector<float> skin(static_cast<std::size_t>(mesh.vertex_count()), 0.0f);
  const std::vector<float> white(skin.size(), 1.0f), iris(skin.size(), 2.0f);
  const Rgb plain = centre_with(nullptr), as_skin = centre_with(skin.data());
  const Rgb as_white = centre_with(white.data()), as_iris = centre_with(iris.data());
  CHECK(distance(plain, as_skin) <= 3);  // no tints = skin
  // The white is lighter and greyer than skin (more blue), the iris far darker.
  CHECK(as_white.b > as_skin.b + 20);
  CHECK(as_iris.r + as_iris.g + as_iris.b < (as_skin.r + as_skin.g + as_skin.b) / 2);
}

TEST_CASE("back-face culling follows the mesh's winding", "[render]") {
  context();
  auto mesh = render_test::make_ellipsoid(0.25f, 0.85f, 0.15f);
  render::BodyRenderer renderer;
  render::Camera camera;
  render::CellFramebuffer fbo(100, 100, 0);
  std::vector<Rgb> centres;
  std::vector<bool> windings;
  for (int pass = 0; pass < 2; ++pass) {
    render::MeshGpu gpu;
    gpu.upload(mesh.positions.data(), mesh.normals.data(), mesh.vertex_count(), mesh.indices.data(),
               static_cast<int>(mesh.indices.size()));
    fbo.begin();
    renderer.draw(gpu, camera, 100, 100);
    fbo.end();
    centres.push_back(pixel(fbo.read_pixels(), 100, 50, 50));
    // Reverse every triangle for the second pass: it must look the same.
    windings.push_back(gpu.counter_clockwise());
    for (size_t t = 0; t < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
  CHECK(windings[0] != windings[1]);
  CHECK(distance(centres[0], centres[1]) <= 3);
}

TEST_CASE("the cached backdrop matches the drawn one", "[render]") {
  context();
  render::BodyRenderer renderer;
  render::Camera camera;
  render::MeshGpu none;
  render::CellFramebuffer single(64, 64, 0), multi(64, 64, 4);
  for (int pass = 0; pass < 2; ++pass) {  // the second single-sampled pass uses the cache
    single.begin();
    renderer.draw(none, camera, 64, 64);
    single.end();
  }
  multi.begin();
  renderer.draw(none, camera, 64, 64);
  multi.end();
  const auto a = single.read_pixels();
  const auto b = multi.read_pixels();
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{0, 0}, {32, 32}, {63, 63}, {5, 50}}) {
    CHECK(distance(pixel(a, 64, x, y), pixel(b, 64, x, y)) <= 3);
  }
}

TEST_CASE("framebuffers resize and work without multisampling", "[render]") {
  context();
  render::CellFramebuffer fbo(64, 48, 0);
  CHECK(fbo.samples() == 0);
  fbo.resize(80, 60, 4);
  CHECK(fbo.width() == 80);
  CHECK(fbo.height() == 60);
  CHECK(fbo.read_pixels().size() == 80u * 60u * 4u);
}

TEST_CASE("view presets and orbit", "[render]") {
  render::Camera cam;
  cam.set_preset(render::ViewPreset::kSide);
  CHECK(cam.eye().x > 3.5f);
  cam.set_preset(render::ViewPreset::kFront);
  CHECK(cam.eye().z > 3.5f);
  cam.orbit(0.0f, 1000.0f);
  CHECK(cam.pitch_degrees == Approx(60.0f));
  CHECK(render::parse_view_preset("3/4") == render::ViewPreset::kThreeQuarter);
  CHECK_FALSE(render::parse_view_preset("top").has_value());
}

TEST_CASE("png writer reports an unwritable path", "[render]") {
  std::vector<std::uint8_t> px(4 * 4 * 4, 128);
  const auto dir = std::filesystem::temp_directory_path() / "sg_render_png_test";
  std::filesystem::create_directories(dir);
  render::write_png(dir / "ok.png", 4, 4, px);
  CHECK(std::filesystem::file_size(dir / "ok.png") > 0);
  CHECK_THROWS_WITH(render::write_png(dir / "missing" / "x.png", 4, 4, px),
                    Catch::Contains("missing"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("the body cells' frame height the look-alike threshold assumes is the camera's",
          "[render][camera]") {
  const render::Camera camera;
  const double frame =
      2.0 * camera.distance * std::tan(0.5 * camera.fov_y_degrees * 3.14159265358979323846 / 180.0);
  CHECK(frame == Approx(app::kCellFrameHeightM).epsilon(1e-6));
}

namespace {

// Where a world point lands on a square cell of `camera`, in normalised device coordinates.
glm::vec3 on_cell(const render::Camera& camera, const glm::vec3& p) {
  const glm::vec4 clip = camera.projection(1.0f) * camera.view() * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}

}  // namespace

TEST_CASE(
    "a grid framed to its tallest body: the default top, and the camera scaled about the "
    "floor",
    "[render][camera]") {
  const render::Camera camera;
  // The highest point the default front view shows at the body is the top of the cell.
  CHECK(on_cell(camera, glm::vec3(0.0f, static_cast<float>(app::kCellFrameTopM), 0.0f)).y ==
        Approx(1.0).margin(2e-3));
  // Scaled by s about the floor, a body s times as tall lands where the full-size one did: a
  // grid of shorter bodies fills its cells as a 2 m grid does by default.
  const float s = 0.85f;
  const render::Camera framed = camera.scaled_about_floor(s);
  for (const glm::vec3 p :
       {glm::vec3(0.0f, 1.9f, 0.0f), glm::vec3(0.2f, 0.0f, 0.1f), glm::vec3(-0.3f, 1.2f, -0.1f)}) {
    const glm::vec3 a = on_cell(camera, p), b = on_cell(framed, s * p);
    CHECK(b.x == Approx(a.x).margin(1e-5));
    CHECK(b.y == Approx(a.y).margin(1e-5));
  }
  CHECK(framed.yaw_degrees == camera.yaw_degrees);
  CHECK(framed.pitch_degrees == camera.pitch_degrees);
  // Nonsense scales are clamped, never a camera inside the body or at infinity.
  CHECK(camera.scaled_about_floor(0.0f).distance == Approx(0.1f * camera.distance));
  CHECK(camera.scaled_about_floor(std::nanf("")).distance == Approx(camera.distance));
}
