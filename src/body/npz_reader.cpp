#include "body/npz_reader.hpp"

#include <zip.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace body {

namespace {

std::string zip_error_text(int code) {
  switch (code) {
    case ZIP_ER_NOZIP:
      return "not a zip archive (.npz files are zip archives of .npy arrays)";
    case ZIP_ER_NOENT:
    case ZIP_ER_OPEN:
      return std::string("cannot open the file: ") + std::strerror(errno ? errno : ENOENT);
    case ZIP_ER_INCONS:
      return "corrupt or truncated zip archive (inconsistent directory)";
    case ZIP_ER_CRC:
      return "corrupt zip entry (CRC mismatch)";
    case ZIP_ER_EOF:
      return "truncated zip archive (unexpected end of file)";
    case ZIP_ER_READ:
      return "read error (truncated or unreadable file)";
    case ZIP_ER_COMPNOTSUPP:
      return "zip entry uses an unsupported compression method";
    case ZIP_ER_ENCRNOTSUPP:
    case ZIP_ER_NOPASSWD:
      return "zip entry is encrypted";
    case ZIP_ER_MEMORY:
      return "out of memory";
    default: {
      zip_error_t e;
      zip_error_init_with_code(&e, code);
      std::string s = zip_error_strerror(&e);
      zip_error_fini(&e);
      return "corrupt zip archive (" + s + ")";
    }
  }
}

// libzip reports a zip whose end (the central directory) is cut off as "not a zip"; a file
// that starts with a zip local header is almost always such a truncated download.
bool starts_like_zip(const unsigned char* head, std::size_t size) {
  return size >= 4 && head[0] == 'P' && head[1] == 'K' && head[2] == 3 && head[3] == 4;
}

std::string open_error_text(int code, bool zip_header) {
  if (code == ZIP_ER_NOZIP && zip_header) {
    return "truncated or damaged zip archive (it starts like a zip, but the directory at its "
           "end is missing; download or copy the file again)";
  }
  return zip_error_text(code);
}

std::string strip_npy(const std::string& entry) {
  if (entry.size() > 4 && entry.compare(entry.size() - 4, 4, ".npy") == 0) {
    return entry.substr(0, entry.size() - 4);
  }
  return entry;
}

// Bytes read at a time when an array is read in parts, and the smallest gap between wanted
// parts of a stored entry that is seeked over rather than read (smaller gaps share disk pages
// with the wanted bytes, so reading through them costs no more than a seek).
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;
constexpr std::uint64_t kSeekGap = std::uint64_t{1} << 16;

// One zip entry read front to back, with forward skips. Checks the entry's sizes on opening,
// as a whole read does. Errors are thrown as std::string (the caller adds file and array).
class EntryStream {
 public:
  EntryStream(zip_t* zip, zip_uint64_t index) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip, index, 0, &st) != 0) throw std::string(zip_strerror(zip));
    size_ = (st.valid & ZIP_STAT_SIZE) ? st.size : std::numeric_limits<std::uint64_t>::max();
    stored_ = (st.valid & ZIP_STAT_COMP_METHOD) && st.comp_method == ZIP_CM_STORE;
    if (size_ > std::numeric_limits<std::size_t>::max() / 2) throw std::string("entry too large");
    // A directory claiming far more data than deflate can expand to is corrupt.
    if ((st.valid & ZIP_STAT_COMP_SIZE) && size_ > st.comp_size * 1100 + 4096) {
      throw std::string("corrupt zip entry (claims " + std::to_string(st.size) + " bytes from " +
                        std::to_string(st.comp_size) + " compressed)");
    }
    // A stored entry's "compressed" data is its data: reading it raw skips libzip's CRC layer,
    // which only computes (a whole read never reaches the end-of-entry check) and costs a pass
    // over every byte. Encrypted entries are still decrypted, or refused without a password.
    file_ = zip_fopen_index(zip, index, stored_ ? ZIP_FL_COMPRESSED : 0);
    if (!file_) throw zip_error_text(zip_error_code_zip(zip_get_error(zip)));
  }
  EntryStream(const EntryStream&) = delete;
  EntryStream& operator=(const EntryStream&) = delete;
  ~EntryStream() {
    if (file_) zip_fclose(file_);
  }

  std::uint64_t size() const { return size_; }
  std::uint64_t position() const { return pos_; }

  // Reads exactly n bytes.
  void read(std::uint8_t* dst, std::size_t n) {
    std::size_t got = 0;
    while (got < n) {
      const zip_int64_t r = zip_fread(file_, dst + got, n - got);
      if (r < 0) throw zip_error_text(zip_error_code_zip(zip_file_get_error(file_)));
      if (r == 0) break;
      got += static_cast<std::size_t>(r);
    }
    pos_ += got;
    if (got < n) {
      throw std::string("truncated zip entry (read " + std::to_string(pos_) + " of " +
                        std::to_string(size_) + " bytes)");
    }
  }

  // Skips n bytes: a seek in a stored entry (libzip seeks in uncompressed data only), else
  // they are read (inflated) into `scratch` and dropped.
  void skip(std::uint64_t n, std::vector<std::uint8_t>& scratch) {
    if (stored_ && n >= kSeekGap && n <= size_ - pos_) {
      if (zip_fseek(file_, static_cast<zip_int64_t>(pos_ + n), SEEK_SET) != 0) {
        throw zip_error_text(zip_error_code_zip(zip_file_get_error(file_)));
      }
      pos_ += n;
      return;
    }
    while (n > 0) {
      const auto k = static_cast<std::size_t>(std::min<std::uint64_t>(n, scratch.size()));
      read(scratch.data(), k);
      n -= k;
    }
  }

  // Closes the entry; an error libzip reports then counts only if all of it was read.
  void finish() {
    const int rc = zip_fclose(file_);
    file_ = nullptr;
    if (rc != 0 && pos_ == size_) throw zip_error_text(rc);
  }

 private:
  zip_file_t* file_ = nullptr;
  std::uint64_t size_ = 0;
  std::uint64_t pos_ = 0;
  bool stored_ = false;
};

// Reads the .npy header at the start of an entry, leaving the stream at the data.
NpyHeader read_npy_header(EntryStream& s) {
  std::vector<std::uint8_t> head(static_cast<std::size_t>(std::min<std::uint64_t>(s.size(), 12)));
  s.read(head.data(), head.size());
  if (head.size() >= 10) {
    const std::size_t need = npy_header_size(head.data(), head.size());
    if (need > head.size() && need <= s.size()) {
      const std::size_t had = head.size();
      head.resize(need);
      s.read(head.data() + had, need - had);
    }
  }
  NpyHeader h = parse_npy_header(head.data(), head.size());
  // A valid header is longer than the 12 bytes read first, so the stream is at the data.
  if (h.data_offset != s.position()) throw NpyError("malformed .npy header (too short)");
  return h;
}

}  // namespace

struct NpzArchive::Impl {
  zip_t* zip = nullptr;
  std::vector<std::string> entries;  // entry names as stored (with .npy)
  ~Impl() {
    if (zip) zip_discard(zip);
  }

  void fill_entries(const std::string& label) {
    const zip_int64_t n = zip_get_num_entries(zip, 0);
    if (n < 0) throw ModelError(label + ": corrupt zip archive (no entry count)");
    for (zip_int64_t i = 0; i < n; ++i) {
      const char* name = zip_get_name(zip, static_cast<zip_uint64_t>(i), 0);
      entries.push_back(name ? name : "");
    }
  }

  zip_int64_t index_of(const std::string& name) const {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (strip_npy(entries[i]) == name) return static_cast<zip_int64_t>(i);
    }
    return -1;
  }

  // Opens array `name`, parses its header and checks that the entry holds its data, then
  // returns fn(stream, header); every error becomes "<label>: array '<name>': <problem>".
  template <typename Fn>
  auto with_array(const std::string& label, const std::string& name, Fn fn) const {
    const zip_int64_t i = index_of(name);
    const std::string where = label + ": array '" + name + "': ";
    if (i < 0) throw ModelError(where + "missing (the file has no " + name + ".npy)");
    try {
      EntryStream s(zip, static_cast<zip_uint64_t>(i));
      const NpyHeader h = read_npy_header(s);
      check_npy_data_size(h, static_cast<std::size_t>(s.size() - h.data_offset));
      return fn(s, h);
    } catch (const std::string& e) {
      throw ModelError(where + e);
    } catch (const NpyError& e) {
      throw ModelError(where + e.what());
    } catch (const std::bad_alloc&) {
      throw ModelError(where + "out of memory");
    }
  }

  // Reads up to `limit` bytes of entry i (all if limit is max). Throws std::string on error.
  std::vector<std::uint8_t> read_entry(zip_uint64_t i, std::uint64_t limit,
                                       std::uint64_t* full_size, bool* compressed) const {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip, i, 0, &st) != 0) throw std::string(zip_strerror(zip));
    if (full_size) *full_size = (st.valid & ZIP_STAT_SIZE) ? st.size : 0;
    if (compressed)
      *compressed = (st.valid & ZIP_STAT_COMP_METHOD) && st.comp_method != ZIP_CM_STORE;
    std::uint64_t want =
        (st.valid & ZIP_STAT_SIZE) ? std::min<std::uint64_t>(st.size, limit) : limit;
    if (want > std::numeric_limits<std::size_t>::max() / 2) throw std::string("entry too large");
    // A directory claiming far more data than deflate can expand to is corrupt.
    if ((st.valid & ZIP_STAT_COMP_SIZE) && want > st.comp_size * 1100 + 4096) {
      throw std::string("corrupt zip entry (claims " + std::to_string(st.size) + " bytes from " +
                        std::to_string(st.comp_size) + " compressed)");
    }
    zip_file_t* f = zip_fopen_index(zip, i, 0);
    if (!f) throw zip_error_text(zip_error_code_zip(zip_get_error(zip)));
    std::vector<std::uint8_t> buf(static_cast<std::size_t>(want));
    std::size_t got = 0;
    while (got < buf.size()) {
      const zip_int64_t n = zip_fread(f, buf.data() + got, buf.size() - got);
      if (n < 0) {
        const std::string err = zip_error_text(zip_error_code_zip(zip_file_get_error(f)));
        zip_fclose(f);
        throw err;
      }
      if (n == 0) break;
      got += static_cast<std::size_t>(n);
    }
    const int rc = zip_fclose(f);
    if (got < buf.size()) {
      throw std::string("truncated zip entry (read " + std::to_string(got) + " of " +
                        std::to_string(buf.size()) + " bytes)");
    }
    if (rc != 0 && want == st.size) throw zip_error_text(rc);
    return buf;
  }
};

NpzArchive::NpzArchive(NpzArchive&&) noexcept = default;
NpzArchive& NpzArchive::operator=(NpzArchive&&) noexcept = default;
NpzArchive::~NpzArchive() = default;

NpzArchive NpzArchive::open_file(const std::filesystem::path& path) {
  NpzArchive a;
  a.label_ = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ModelError(a.label_ + ": file not found");
  if (std::filesystem::is_directory(path, ec)) throw ModelError(a.label_ + ": is a directory");
  // Devices and pipes (/dev/zero, /dev/stdin) cannot be zip archives: libzip needs to seek.
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ModelError(a.label_ +
                     ": not a regular file (a device, pipe or socket); give an .npz file");
  }
  a.impl_ = std::make_unique<Impl>();
  int err = 0;
  errno = 0;
  a.impl_->zip = zip_open(a.label_.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &err);
  if (!a.impl_->zip) {
    unsigned char head[4] = {0, 0, 0, 0};
    std::size_t got = 0;
    if (std::FILE* f = std::fopen(a.label_.c_str(), "rb")) {
      got = std::fread(head, 1, sizeof head, f);
      std::fclose(f);
    }
    throw ModelError(a.label_ + ": " + open_error_text(err, starts_like_zip(head, got)));
  }
  a.impl_->fill_entries(a.label_);
  return a;
}

NpzArchive NpzArchive::open_memory(const void* data, std::size_t size, const std::string& label) {
  NpzArchive a;
  a.label_ = label;
  if (data == nullptr || size == 0) throw ModelError(label + ": empty data (not a zip archive)");
  a.impl_ = std::make_unique<Impl>();
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* src = zip_source_buffer_create(data, size, 0, &error);
  if (!src) {
    const std::string msg = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw ModelError(label + ": " + msg);
  }
  a.impl_->zip = zip_open_from_source(src, ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (!a.impl_->zip) {
    const int code = zip_error_code_zip(&error);
    zip_source_free(src);
    zip_error_fini(&error);
    throw ModelError(
        label + ": " +
        open_error_text(code, starts_like_zip(static_cast<const unsigned char*>(data), size)));
  }
  zip_error_fini(&error);
  a.impl_->fill_entries(label);
  return a;
}

std::vector<std::string> NpzArchive::names() const {
  std::vector<std::string> out;
  for (const auto& e : impl_->entries) out.push_back(strip_npy(e));
  return out;
}

bool NpzArchive::contains(const std::string& name) const {
  return impl_->index_of(name) >= 0;
}

std::vector<NpzEntryInfo> NpzArchive::list() const {
  std::vector<NpzEntryInfo> out;
  for (std::size_t i = 0; i < impl_->entries.size(); ++i) {
    NpzEntryInfo info;
    info.name = strip_npy(impl_->entries[i]);
    try {
      auto head = impl_->read_entry(i, 4096, &info.stored_size, &info.compressed);
      std::size_t need = npy_header_size(head.data(), head.size());
      if (need > head.size()) head = impl_->read_entry(i, need, nullptr, nullptr);
      info.header = parse_npy_header(head.data(), head.size());
    } catch (const std::string& e) {
      info.problem = e;
    } catch (const NpyError& e) {
      info.problem = e.what();
    }
    out.push_back(std::move(info));
  }
  return out;
}

NpyArray NpzArchive::read(const std::string& name) const {
  // Straight into the array's buffer, sized from the checked header: one copy of the data.
  return impl_->with_array(label_, name, [](EntryStream& s, const NpyHeader& h) {
    NpyArray a;
    a.header = h;
    if (h.needs_pickle()) return a;  // no data: object arrays are pickled Python objects
    a.data.resize(h.element_count() * h.item_size);
    s.read(a.data.data(), a.data.size());
    s.finish();
    return a;
  });
}

NpyHeader NpzArchive::header(const std::string& name) const {
  return impl_->with_array(label_, name, [](EntryStream&, const NpyHeader& h) { return h; });
}

NpyHeader NpzArchive::read_spans(const std::string& name, const SpanSource& next,
                                 const SpanSink& take) const {
  return impl_->with_array(label_, name, [&](EntryStream& s, const NpyHeader& h) {
    const std::uint64_t data_size = h.needs_pickle() ? 0 : h.element_count() * h.item_size;
    const std::size_t item = std::max<std::size_t>(h.item_size, 1);
    // Whole items per block, so that every piece handed on holds whole items.
    std::vector<std::uint8_t> block(std::max(item, kBlockBytes / item * item));
    std::uint64_t block_start = 0, block_end = 0;  // data offsets that `block` holds
    std::uint64_t offset = 0, size = 0, last_end = 0;
    while (next(offset, size)) {
      if (offset < last_end || size > data_size || offset > data_size - size || offset % item ||
          size % item) {
        throw std::logic_error("NpzArchive::read_spans: spans out of order or not whole items");
      }
      last_end = offset + size;
      while (size > 0) {
        if (offset >= block_end) {
          const std::uint64_t at = s.position() - h.data_offset;
          s.skip(offset - at, block);
          const auto n =
              static_cast<std::size_t>(std::min<std::uint64_t>(block.size(), data_size - offset));
          s.read(block.data(), n);
          block_start = offset;
          block_end = offset + n;
        }
        const auto piece = static_cast<std::size_t>(std::min(size, block_end - offset));
        take(block.data() + (offset - block_start), piece);
        offset += piece;
        size -= piece;
      }
    }
    s.finish();
    return h;
  });
}

}  // namespace body
