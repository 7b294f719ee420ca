#include "spaces/body_scene.hpp"

#include <algorithm>

#include "body/eye_parts.hpp"
#include "render/cell_framebuffer.hpp"

namespace spaces {

body::BodyMesh body_at(const body::Model& model, const Eigen::VectorXd& x) {
  return body_from_betas(model, body::betas_from_unit(x));
}

body::BodyMesh body_from_betas(const body::Model& model, const Eigen::VectorXf& betas) {
  body::BodyMesh mesh = body::evaluate(model, betas);
  body::place_on_ground(mesh);
  return mesh;
}

std::vector<float> eye_tints(const body::Model& model) {
  const std::vector<body::EyePart> parts = body::eye_parts(model);
  if (std::none_of(parts.begin(), parts.end(),
                   [](body::EyePart p) { return p != body::EyePart::kSkin; }))
    return {};
  std::vector<float> tints(parts.size());
  for (std::size_t v = 0; v < parts.size(); ++v) tints[v] = static_cast<float>(parts[v]);
  return tints;
}

void show_mesh(render::MeshGpu& gpu, const body::Model& model, const body::BodyMesh& mesh,
               const std::vector<float>& tints) {
  const int vertices = static_cast<int>(mesh.vertices.rows());
  if (gpu.empty() || gpu.vertex_count() != vertices) {
    const bool tinted = tints.size() == static_cast<std::size_t>(vertices);
    gpu.upload(mesh.vertices.data(), mesh.normals.data(), vertices, model.faces.data(),
               static_cast<int>(model.faces.size()), tinted ? tints.data() : nullptr);
  } else {
    gpu.update(mesh.vertices.data(), mesh.normals.data(), vertices);
  }
}

render::BodyStyle cell_style() {
  return render::BodyStyle{};
}

std::vector<std::uint8_t> render_body_image(const body::Model& model, const body::BodyMesh& mesh,
                                            const render::Camera& camera, int width, int height,
                                            int samples) {
  render::BodyRenderer renderer;
  render::MeshGpu gpu;
  show_mesh(gpu, model, mesh, eye_tints(model));
  render::CellFramebuffer fbo(width, height, samples);
  fbo.begin();
  renderer.draw(gpu, camera, width, height, cell_style());
  fbo.end();
  render::check_gl("render_body_image");
  return fbo.read_pixels();
}

}  // namespace spaces
