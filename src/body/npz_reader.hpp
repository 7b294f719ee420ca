// Reading .npz archives (a zip of .npy arrays, stored or deflated, zip64 or not) with libzip,
// from a file or from memory. Arrays are read one at a time, by name, when asked for.
#pragma once

#include <cstddef>
#include <filesystem>
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

 private:
  NpzArchive() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string label_;
};

}  // namespace body
