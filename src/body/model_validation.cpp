#include "body/model_validation.hpp"

#include <cmath>

namespace body {

void fail_array(const NpzArchive& npz, const std::string& name, const std::string& problem) {
  throw ModelError(npz.label() + ": array '" + name + "': " + problem);
}

NpyArray read_required_array(const NpzArchive& npz, const std::string& name) {
  if (!npz.contains(name)) {
    throw ModelError(npz.label() + ": array '" + name +
                     "': missing (an SMPL-family model needs v_template, shapedirs, f, "
                     "J_regressor, weights and kintree_table)");
  }
  NpyArray a = npz.read(name);
  if (a.header.needs_pickle()) {
    fail_array(npz, name,
               "stored as a Python object array (needs pickle, e.g. a scipy sparse matrix or a "
               "chumpy object); convert the model with tools/smpl_pkl_to_npz.py");
  }
  return a;
}

void require_shape(const NpzArchive& npz, const std::string& name, const NpyHeader& h,
                   const std::vector<long long>& dims, const std::string& what) {
  if (h.shape.size() != dims.size()) {
    fail_array(npz, name,
               "wrong rank: expected " + std::to_string(dims.size()) + " dimensions " + what +
                   ", found shape " + h.shape_string());
  }
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (dims[i] >= 0 && static_cast<long long>(h.shape[i]) != dims[i]) {
      fail_array(npz, name,
                 "wrong shape: expected " + what + ", found " + h.shape_string() + " (dimension " +
                     std::to_string(i) + " should be " + std::to_string(dims[i]) + ")");
    }
  }
}

std::string index_string(const std::vector<std::size_t>& shape, std::size_t linear) {
  std::vector<std::size_t> idx(shape.size(), 0);
  for (std::size_t d = shape.size(); d-- > 0;) {
    if (shape[d] == 0) break;
    idx[d] = linear % shape[d];
    linear /= shape[d];
  }
  std::string s = "(";
  for (std::size_t d = 0; d < idx.size(); ++d) {
    if (d) s += ", ";
    s += std::to_string(idx[d]);
  }
  return s + ")";
}

std::vector<float> finite_floats(const NpzArchive& npz, const std::string& name,
                                 const NpyArray& a) {
  if (!a.header.is_numeric()) {
    fail_array(npz, name, "dtype " + a.header.dtype_name() + " is not numeric");
  }
  if (a.header.kind == 'f' && a.header.item_size == 8) {
    // Check in double precision first: finite doubles beyond float range become Inf.
    const auto d = a.to_double();
    std::vector<float> out(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      out[i] = static_cast<float>(d[i]);
      if (!std::isfinite(out[i])) {
        fail_array(npz, name,
                   std::string(std::isnan(d[i]) ? "contains NaN"
                                                : "contains Inf (or a value "
                                                  "beyond float range)") +
                       " at index " + index_string(a.header.shape, i));
      }
    }
    return out;
  }
  auto out = a.to_float();
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!std::isfinite(out[i])) {
      fail_array(npz, name,
                 std::string(std::isnan(out[i]) ? "contains NaN" : "contains Inf") + " at index " +
                     index_string(a.header.shape, i));
    }
  }
  return out;
}

std::vector<std::int64_t> integer_values(const NpzArchive& npz, const std::string& name,
                                         const NpyArray& a) {
  if (!a.header.is_numeric()) {
    fail_array(npz, name, "dtype " + a.header.dtype_name() + " is not an integer type");
  }
  try {
    return a.to_int64();
  } catch (const NpyError& e) {
    fail_array(npz, name, e.what());
  }
}

}  // namespace body
