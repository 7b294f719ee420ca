#include "body/model_validation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace body {

void fail_array(const NpzArchive& npz, const std::string& name, const std::string& problem) {
  throw ModelError(npz.label() + ": array '" + name + "': " + problem);
}

namespace {

// Throws the errors read_required_array gives for a missing array or an object array.
void require_present(const NpzArchive& npz, const std::string& name) {
  if (!npz.contains(name)) {
    throw ModelError(npz.label() + ": array '" + name +
                     "': missing (an SMPL-family model needs v_template, shapedirs, f, "
                     "J_regressor, weights and kintree_table)");
  }
}
void require_no_pickle(const NpzArchive& npz, const std::string& name, const NpyHeader& h) {
  if (h.needs_pickle()) {
    fail_array(npz, name,
               "stored as a Python object array (needs pickle, e.g. a scipy sparse matrix or a "
               "chumpy object); convert the model with tools/smpl_pkl_to_npz.py");
  }
}

// The message for a value that is not finite as float: float64 values are checked after the
// conversion, so a finite double beyond float's range counts as Inf, as finite_floats has it.
std::string not_finite_text(bool float64, bool nan) {
  if (nan) return "contains NaN";
  return float64 ? "contains Inf (or a value beyond float range)" : "contains Inf";
}

// The span list and the destination of every value for read_finite_columns. Spans: in C order
// one per row and slice (the slice's columns are next to each other in a row); in Fortran order
// one per slice (a column is a block of `rows` values, the first axis fastest).
class ColumnReader {
 public:
  ColumnReader(const NpyHeader& h, const std::vector<ColumnSlice>& slices)
      : h_(h),
        slices_(slices),
        columns_(h.shape.back()),
        fortran_(h.fortran_order && h.shape.size() >= 2) {
    const std::size_t lead = h.shape.size() - 1;
    for (std::size_t d = 0; d < lead; ++d) rows_ *= h.shape[d];
    // C-order strides (in rows) of the leading axes, to follow a Fortran walk in C rows.
    c_stride_.assign(lead, 1);
    for (std::size_t d = lead; d-- > 1;) c_stride_[d - 1] = c_stride_[d] * h.shape[d];
    index_.assign(lead, 0);
  }

  bool next(std::uint64_t& offset, std::uint64_t& size) {
    const std::uint64_t item = h_.item_size;
    for (;;) {
      if (next_slice_ == slices_.size()) {
        if (fortran_) return false;
        next_slice_ = 0;
        ++next_row_;
      }
      if (next_row_ >= rows_) return false;
      current_ = next_slice_++;
      const ColumnSlice& s = slices_[current_];
      if (s.count == 0) continue;
      column_ = 0;
      if (fortran_) {
        offset = s.first * rows_ * item;
        size = s.count * rows_ * item;
        row_ = 0, walked_ = 0;
        std::fill(index_.begin(), index_.end(), std::size_t{0});
      } else {
        offset = (next_row_ * columns_ + s.first) * item;
        size = s.count * item;
        row_ = next_row_;
      }
      return true;
    }
  }

  // The next n values of the current span, in storage order, decoded.
  template <typename T>
  void take(const T* values, std::size_t n) {
    const ColumnSlice& s = slices_[current_];
    float* out = s.out ? s.out->data() : nullptr;
    for (std::size_t i = 0; i < n; ++i) {
      const auto f = static_cast<float>(values[i]);
      if (out) out[column_ * rows_ + row_] = f;  // column-major rows x count
      if (!std::isfinite(f)) note_bad(row_ * columns_ + s.first + column_, std::isnan(values[i]));
      if (!fortran_) {
        ++column_;
      } else if (++walked_ == rows_) {  // the end of a column block
        walked_ = 0, row_ = 0, ++column_;
        std::fill(index_.begin(), index_.end(), std::size_t{0});
      } else {  // the next row of the Fortran walk: the first axis fastest
        for (std::size_t d = 0; d < index_.size(); ++d) {
          row_ += c_stride_[d];
          if (++index_[d] < h_.shape[d]) break;
          row_ -= c_stride_[d] * index_[d];
          index_[d] = 0;
        }
      }
    }
  }

  bool bad() const { return bad_ != kNone; }
  std::size_t bad_index() const { return bad_; }
  bool bad_is_nan() const { return bad_nan_; }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  // Keeps the first bad value in C order (a Fortran walk meets them in another order).
  void note_bad(std::size_t linear, bool nan) {
    if (linear < bad_) bad_ = linear, bad_nan_ = nan;
  }

  const NpyHeader& h_;
  const std::vector<ColumnSlice>& slices_;
  std::size_t rows_ = 1;
  std::size_t columns_;
  bool fortran_;
  std::vector<std::size_t> c_stride_, index_;
  std::size_t next_slice_ = 0, next_row_ = 0;  // the span after the current one
  std::size_t current_ = 0;                    // slice of the current span
  std::size_t row_ = 0, column_ = 0;           // C row and slice column of the next value
  std::size_t walked_ = 0;                     // values of the current Fortran column taken
  std::size_t bad_ = kNone;
  bool bad_nan_ = false;
};

}  // namespace

NpyHeader read_required_header(const NpzArchive& npz, const std::string& name) {
  require_present(npz, name);
  NpyHeader h = npz.header(name);
  require_no_pickle(npz, name, h);
  return h;
}

void read_finite_columns(const NpzArchive& npz, const std::string& name, const NpyHeader& h,
                         const std::vector<ColumnSlice>& slices) {
  if (!h.is_numeric()) fail_array(npz, name, "dtype " + h.dtype_name() + " is not numeric");
  if (h.shape.empty()) throw std::logic_error("read_finite_columns: a scalar has no columns");
  const std::size_t columns = h.shape.back();
  std::size_t rows = 1;
  for (std::size_t d = 0; d + 1 < h.shape.size(); ++d) rows *= h.shape[d];
  std::size_t end = 0;
  for (const auto& s : slices) {
    if (s.first < end || s.count > columns || s.first > columns - s.count) {
      throw std::logic_error("read_finite_columns: slices out of order or out of range");
    }
    end = s.first + s.count;
  }
  // The caller's header comes from NpzArchive::header, which checked that the entry holds the
  // whole array, so these sizes are bounded by the file.
  for (const auto& s : slices) {
    if (s.out) s.out->resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(s.count));
  }
  ColumnReader reader(h, slices);
  const bool float64 = h.kind == 'f' && h.item_size == 8;
  // Decoded in small batches: float64 to double first (its range check needs the double).
  constexpr std::size_t kBatch = 4096;
  std::vector<double> as_double(float64 ? kBatch : 0);
  std::vector<float> as_float(float64 ? 0 : kBatch);
  npz.read_spans(
      name, [&](std::uint64_t& offset, std::uint64_t& size) { return reader.next(offset, size); },
      [&](const std::uint8_t* bytes, std::size_t size) {
        const std::size_t n = size / h.item_size;
        for (std::size_t i = 0; i < n; i += kBatch) {
          const std::size_t m = std::min(kBatch, n - i);
          const std::uint8_t* p = bytes + i * h.item_size;
          if (float64) {
            decode_numbers(h, p, m, as_double.data());
            reader.take(as_double.data(), m);
          } else {
            decode_numbers(h, p, m, as_float.data());
            reader.take(as_float.data(), m);
          }
        }
      });
  if (reader.bad()) {
    fail_array(npz, name,
               not_finite_text(float64, reader.bad_is_nan()) + " at index " +
                   index_string(h.shape, reader.bad_index()));
  }
}

NpyArray read_required_array(const NpzArchive& npz, const std::string& name) {
  require_present(npz, name);
  NpyArray a = npz.read(name);
  require_no_pickle(npz, name, a.header);
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
