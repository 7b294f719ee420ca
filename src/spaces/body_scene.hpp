// Glue between the body model and the renderer: evaluate a point of the search box into a
// grounded mesh and put it into a MeshGpu; render one body into an image (the `render`
// command and the GUI cells draw exactly the same way).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "body/body_model.hpp"
#include "render/body_renderer.hpp"
#include "render/camera.hpp"
#include "render/mesh_gpu.hpp"

namespace spaces {

// The mesh for x in [0,1]^K (beta = 6x - 3), feet on y = 0.
body::BodyMesh body_at(const body::Model& model, const Eigen::VectorXd& x);
body::BodyMesh body_from_betas(const body::Model& model, const Eigen::VectorXf& betas);

// The renderer's tint per vertex (body::EyePart as a float: the eyes' whites and irises), or
// empty for a model without eyes.
std::vector<float> eye_tints(const body::Model& model);

// Uploads (first time, with `tints` when they are one per vertex) or updates (same vertex
// count) the GPU mesh.
void show_mesh(render::MeshGpu& gpu, const body::Model& model, const body::BodyMesh& mesh,
               const std::vector<float>& tints = {});

// Cell appearance shared by the grid, previews and the headless renderer.
render::BodyStyle cell_style();

// Renders one body into a width x height RGBA8 image (bottom row first) with a
// multisampled offscreen framebuffer; needs a current GL context.
std::vector<std::uint8_t> render_body_image(const body::Model& model, const body::BodyMesh& mesh,
                                            const render::Camera& camera, int width, int height,
                                            int samples = 4);

}  // namespace spaces
