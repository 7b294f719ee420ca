// Validation helpers for model arrays: each check throws ModelError naming the file, the array
// and the problem ("model.npz: array 'shapedirs': has 6890 vertices but v_template has 6891").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/npz_reader.hpp"

namespace body {

// Reads a required array; missing arrays and arrays that need Python pickle are errors.
NpyArray read_required_array(const NpzArchive& npz, const std::string& name);

// The header of a required array, without its data (the same errors as read_required_array,
// and an entry too short for the data is an error too).
NpyHeader read_required_header(const NpzArchive& npz, const std::string& name);

// Requires the given rank; dims[i] < 0 means "any size". `what` describes the expected shape
// for the message, e.g. "(V, 3)".
void require_shape(const NpzArchive& npz, const std::string& name, const NpyHeader& h,
                   const std::vector<long long>& dims, const std::string& what);

// Requires a numeric dtype and returns the values (C order) as float, rejecting NaN and Inf
// with the multi-index of the first bad value.
std::vector<float> finite_floats(const NpzArchive& npz, const std::string& name, const NpyArray& a);

// Columns [first, first + count) of an array's last axis, read into `out` (resized to rows x
// count, rows = the product of the other dimensions with the last but one fastest, as C order
// has them: row 3 v + axis of a (V, 3, K) shape basis), or only checked when `out` is null.
struct ColumnSlice {
  std::size_t first = 0;
  std::size_t count = 0;
  Eigen::MatrixXf* out = nullptr;
};

// finite_floats for some columns of a numeric array (rank >= 1) with header `h`, read straight
// from the archive into their matrices: only the bytes of those columns are read where the
// entry is stored (all of it is inflated where it is deflated) and only they are converted, and
// no copy of the whole array is made. Slices in increasing order, not overlapping. NaN and Inf
// are reported with their index in the whole array, the first in C order.
void read_finite_columns(const NpzArchive& npz, const std::string& name, const NpyHeader& h,
                         const std::vector<ColumnSlice>& slices);

// Requires an integer dtype (or integral floats) and returns the values in C order.
std::vector<std::int64_t> integer_values(const NpzArchive& npz, const std::string& name,
                                         const NpyArray& a);

// "(i, j)" for linear C-order index `linear` in an array of shape `shape`.
std::string index_string(const std::vector<std::size_t>& shape, std::size_t linear);

[[noreturn]] void fail_array(const NpzArchive& npz, const std::string& name,
                             const std::string& problem);

}  // namespace body
