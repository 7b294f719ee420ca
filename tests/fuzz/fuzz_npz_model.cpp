// libFuzzer target: an .npz in memory through the model loader (npz reader, npy parser,
// validation), then evaluation, measurements and glTF export of what it accepts.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "body/body_model.hpp"
#include "body/gltf_export.hpp"
#include "body/measurements.hpp"
#include "body/model_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  body::Model model;
  try {
    model = body::load_model_from_memory(data, size, "fuzz.npz", 0);
  } catch (const body::ModelError&) {
    return 0;  // refused with a message: fine
  }
  // Fewer components read other bytes (only some columns of shapedirs): a file that loads whole
  // loads in part too, with the same numbers.
  const body::Model part = body::load_model_from_memory(data, size, "fuzz.npz", 1, 0);
  if (!(part.shapedirs.array() == model.shapedirs.leftCols(1).array()).all()) std::abort();
  // SMPL-X's expression columns are read (and checked) only when asked for.
  try {
    const body::Model expr =
        body::load_model_from_memory(data, size, "fuzz.npz", 1, model.total_expressions);
    if (expr.expression_dirs.cols() != model.total_expressions) std::abort();
  } catch (const body::ModelError&) {
  }
  // Accepted models must evaluate, measure and export without any exception but ExportError.
  Eigen::VectorXf betas = Eigen::VectorXf::Zero(model.component_count());
  for (Eigen::Index i = 0; i < betas.size(); ++i) betas[i] = (i % 2 == 0) ? 1.5f : -2.0f;
  body::BodyMesh mesh = body::evaluate(model, betas);
  (void)body::measure(model, mesh);
  try {
    (void)body::export_gltf_bytes(model, betas, true);
    (void)body::export_gltf_bytes(model, betas, false);
  } catch (const body::ExportError&) {
  }
  return 0;
}
