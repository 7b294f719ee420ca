#include "npz_writer.hpp"

#include <stdexcept>

#include <zlib.h>

namespace default_model {

std::vector<std::uint8_t> npy_bytes(const NpyArray& array) {
  std::string shape = "(";
  for (std::size_t i = 0; i < array.shape.size(); ++i) {
    shape += std::to_string(array.shape[i]);
    if (array.shape.size() == 1 || i + 1 < array.shape.size()) shape += ",";
    if (i + 1 < array.shape.size()) shape += " ";
  }
  shape += ")";
  std::string header =
      "{'descr': '" + array.descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  // Magic (6) + version (2) + length (2) + header + '\n' padded to a multiple of 64.
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header += '\n';
  std::vector<std::uint8_t> out = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
  out.push_back(static_cast<std::uint8_t>(header.size() & 0xff));
  out.push_back(static_cast<std::uint8_t>(header.size() >> 8));
  out.insert(out.end(), header.begin(), header.end());
  out.insert(out.end(), array.data.begin(), array.data.end());
  return out;
}

namespace {

void put16(std::vector<std::uint8_t>& o, std::uint32_t v) {
  o.push_back(v & 0xff);
  o.push_back((v >> 8) & 0xff);
}
void put32(std::vector<std::uint8_t>& o, std::uint32_t v) {
  put16(o, v & 0xffff);
  put16(o, v >> 16);
}

// Raw deflate (zip method 8) at the highest level: the joint regressor and the skinning
// weights are mostly zeros and shrink to a few percent, so the files stay small enough to
// embed. zlib's output bytes may differ between its versions; the arrays never do.
std::vector<std::uint8_t> deflate_raw(const std::vector<std::uint8_t>& in) {
  z_stream zs{};
  if (deflateInit2(&zs, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("zlib: deflateInit2 failed");
  std::vector<std::uint8_t> out(deflateBound(&zs, static_cast<uLong>(in.size())));
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = static_cast<uInt>(in.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  const std::size_t written = zs.total_out;
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw std::runtime_error("zlib: deflate did not finish");
  out.resize(written);
  return out;
}

}  // namespace

std::vector<std::uint8_t> npz_bytes(const std::vector<NpyArray>& arrays) {
  // Fixed MS-DOS timestamp 1980-01-01 00:00:00 so the bytes never depend on the clock.
  const std::uint32_t dos_time = 0, dos_date = (0 << 9) | (1 << 5) | 1;
  std::vector<std::uint8_t> out, central;
  for (const NpyArray& a : arrays) {
    const std::vector<std::uint8_t> payload = npy_bytes(a);
    const std::string name = a.name + ".npy";
    const std::uint32_t crc = static_cast<std::uint32_t>(
        crc32(crc32(0L, Z_NULL, 0), payload.data(), static_cast<uInt>(payload.size())));
    const std::uint32_t offset = static_cast<std::uint32_t>(out.size());
    const std::uint32_t size = static_cast<std::uint32_t>(payload.size());
    const std::vector<std::uint8_t> packed = deflate_raw(payload);
    const std::uint32_t packed_size = static_cast<std::uint32_t>(packed.size());
    // Local file header.
    put32(out, 0x04034b50);
    put16(out, 20);  // version needed
    put16(out, 0);   // flags
    put16(out, 8);   // deflated
    put16(out, dos_time);
    put16(out, dos_date);
    put32(out, crc);
    put32(out, packed_size);
    put32(out, size);
    put16(out, static_cast<std::uint32_t>(name.size()));
    put16(out, 0);
    out.insert(out.end(), name.begin(), name.end());
    out.insert(out.end(), packed.begin(), packed.end());
    // Central directory record.
    put32(central, 0x02014b50);
    put16(central, 20);  // made by
    put16(central, 20);  // needed
    put16(central, 0);
    put16(central, 8);  // deflated
    put16(central, dos_time);
    put16(central, dos_date);
    put32(central, crc);
    put32(central, packed_size);
    put32(central, size);
    put16(central, static_cast<std::uint32_t>(name.size()));
    put16(central, 0);  // extra
    put16(central, 0);  // comment
    put16(central, 0);  // disk
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central.insert(central.end(), name.begin(), name.end());
  }
  const std::uint32_t cd_offset = static_cast<std::uint32_t>(out.size());
  out.insert(out.end(), central.begin(), central.end());
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(arrays.size()));
  put16(out, static_cast<std::uint32_t>(arrays.size()));
  put32(out, static_cast<std::uint32_t>(central.size()));
  put32(out, cd_offset);
  put16(out, 0);
  return out;
}

}  // namespace default_model
