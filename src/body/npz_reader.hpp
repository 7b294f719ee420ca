// Reading .npz archives (a zip of .npy arrays, stored or deflated, zip64 or not) with libzip,
// from a file or from memory. Arrays are read one at a time, by name, when asked for.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "body/npy_reader.hpp"

namespace body {

struct NpzEntryInfo {
  std::string name;               // array name (the entry name without ".npy")
  std::uint64_t stored_size = 0;  // uncompressed bytes of the .npy
  bool compressed = false;
  std::optional<NpyHeader> header;  // empty if the header could not be parsed
  std::string problem;              // why the header could not be parsed
};

class NpzArchive {
 public:
  // Throw ModelError naming `label` for a missing file, not a zip, or a corrupt zip.
  static NpzArchive open_file(const std::filesystem::path& path);
  static NpzArchive open_memory(const void* data, std::size_t size, const std::string& label);

  NpzArchive(NpzArchive&&) noexcept;
  NpzArchive& operator=(NpzArchive&&) noexcept;
  ~NpzArchive();

  const std::string& label() const { return label_; }
  std::vector<std::string> names() const;  // array names in archive order
  bool contains(const std::string& name) const;

  // Lists every entry with its parsed header (reads only the start of each entry).
  std::vector<NpzEntryInfo> list() const;

  // Reads and parses one array. Throws ModelError "<label>: array '<name>': <problem>".
  NpyArray read(const std::string& name) const;

  // The header of one array, read from the start of its entry only. Throws ModelError like
  // read() for a missing array, a bad header, or an entry too short for the array's data (so
  // a caller may size buffers from the shape); object arrays carry no data and pass.
  NpyHeader header(const std::string& name) const;

  // Reads parts of one numeric array without holding all of it (a shape basis of 400 columns
  // when 10 are used). `next(offset, size)` gives the next wanted span of the array's data
  // (bytes from the start of the data, in increasing order, not overlapping, whole items) or
  // returns false when no more are wanted; `take(bytes, size)` gets each span's bytes in order,
  // in pieces of whole items. Bytes between spans are skipped (seeked over where the entry is
  // stored, inflated and dropped where it is deflated) and reading stops after the last span.
  // Checks as header() does first; throws ModelError like read(), and passes on what `take`
  // throws. Returns the header.
  using SpanSource = std::function<bool(std::uint64_t& offset, std::uint64_t& size)>;
  using SpanSink = std::function<void(const std::uint8_t* bytes, std::size_t size)>;
  NpyHeader read_spans(const std::string& name, const SpanSource& next, const SpanSink& take) const;

 private:
  NpzArchive() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string label_;
};

}  // namespace body
