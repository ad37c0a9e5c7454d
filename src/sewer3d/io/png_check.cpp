#include "sewer3d/io/png_check.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>

namespace sewer3d {
namespace {

std::uint32_t U32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

struct Chunk {
  std::string type;
  const std::uint8_t* data = nullptr;
  std::uint32_t length = 0;
  size_t start = 0;  ///< offset of the chunk's length field in the file
};

struct Header {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0, channels = 0;
  bool interlaced = false;
};

bool Critical(const std::string& type) { return (type[0] & 0x20) == 0; }

// The chunks in file order, or the structural problem.
std::string ReadChunks(const std::vector<std::uint8_t>& b, std::vector<Chunk>& chunks) {
  size_t at = 8;
  while (at + 12 <= b.size()) {
    Chunk c{std::string(b.begin() + static_cast<std::ptrdiff_t>(at) + 4,
                        b.begin() + static_cast<std::ptrdiff_t>(at) + 8),
            b.data() + at + 8, U32(b.data() + at), at};
    if (c.length > b.size() - at - 12)
      return "truncated PNG (the " + c.type + " chunk runs past the end)";
    if (chunks.empty() && c.type != "IHDR") return "not a PNG (no IHDR chunk first)";
    const auto crc = crc32(0, b.data() + at + 4, static_cast<uInt>(4 + c.length));
    if (crc != U32(b.data() + at + 8 + c.length))
      return "corrupt PNG (CRC error in the " + c.type + " chunk)";
    chunks.push_back(c);
    if (c.type == "IEND") return "";
    at += 12 + c.length;
  }
  return "truncated PNG (no IEND chunk)";
}

std::string ReadHeader(const Chunk& ihdr, Header& h) {
  if (ihdr.length != 13) return "corrupt PNG (IHDR is not 13 bytes)";
  const std::uint8_t* d = ihdr.data;
  h.width = U32(d);
  h.height = U32(d + 4);
  h.bit_depth = d[8];
  h.colour_type = d[9];
  h.interlaced = d[12] == 1;
  const int depth = h.bit_depth;
  constexpr std::array<int, 7> kChannels = {1, 0, 3, 1, 2, 0, 4};
  const bool colour_ok = h.colour_type <= 6 && kChannels[h.colour_type] > 0;
  if (!colour_ok) return "corrupt PNG (colour type " + std::to_string(h.colour_type) + ")";
  h.channels = kChannels[h.colour_type];
  const bool low = depth == 1 || depth == 2 || depth == 4;
  const bool depth_ok = depth == 8 || (depth == 16 && h.colour_type != 3) ||
                        (low && (h.colour_type == 0 || h.colour_type == 3));
  if (!depth_ok) {
    return "corrupt PNG (bit depth " + std::to_string(depth) + " with colour type " +
           std::to_string(h.colour_type) + ")";
  }
  if (d[10] != 0 || d[11] != 0 || d[12] > 1)
    return "corrupt PNG (unknown compression, filter or interlace method)";
  if (h.width == 0 || h.height == 0 || h.width > 0x7fffffffu || h.height > 0x7fffffffu)
    return "corrupt PNG (image size out of range)";
  return "";
}

// The byte count of each row of the filtered image data, in order (Adam7: pass by pass).
struct RowRun {
  std::uint64_t bytes = 0, rows = 0;
};
std::vector<RowRun> Rows(const Header& h) {
  const auto row_bytes = [&](std::uint64_t width) {
    return 1 + (width * static_cast<std::uint64_t>(h.channels * h.bit_depth) + 7) / 8;
  };
  if (!h.interlaced) return {{row_bytes(h.width), h.height}};
  constexpr int kX0[7] = {0, 4, 0, 2, 0, 1, 0}, kDx[7] = {8, 8, 4, 4, 2, 2, 1};
  constexpr int kY0[7] = {0, 0, 4, 0, 2, 0, 1}, kDy[7] = {8, 8, 8, 4, 4, 2, 2};
  std::vector<RowRun> runs;
  for (int p = 0; p < 7; ++p) {
    const std::uint64_t w = (h.width + kDx[p] - 1 - kX0[p]) / kDx[p];
    const std::uint64_t n = (h.height + kDy[p] - 1 - kY0[p]) / kDy[p];
    if (h.width > static_cast<std::uint32_t>(kX0[p]) &&
        h.height > static_cast<std::uint32_t>(kY0[p]) && w > 0 && n > 0)
      runs.push_back({row_bytes(w), n});
  }
  return runs;
}

std::string CheckPalette(const std::vector<Chunk>& chunks, const Header& h) {
  int palette = -1;
  for (const Chunk& c : chunks) {
    if (c.type == "PLTE") {
      if (palette >= 0) return "corrupt PNG (two PLTE chunks)";
      if (c.length == 0 || c.length % 3 != 0 || c.length > 768 || h.colour_type == 0 ||
          h.colour_type == 4)
        return "corrupt PNG (PLTE chunk invalid for this image)";
      palette = static_cast<int>(c.length / 3);
      if (h.colour_type == 3 && palette > (1 << h.bit_depth))
        return "corrupt PNG (PLTE has more entries than the bit depth can index)";
    } else if (c.type == "tRNS") {
      const bool ok = (h.colour_type == 0 && c.length == 2) ||
                      (h.colour_type == 2 && c.length == 6) ||
                      (h.colour_type == 3 && palette > 0 && static_cast<int>(c.length) <= palette);
      if (!ok) return "corrupt PNG (tRNS chunk invalid for this image)";
    } else if (c.type == "IDAT") {
      break;
    }
  }
  if (h.colour_type == 3 && palette < 0) return "corrupt PNG (palette image without PLTE)";
  return "";
}

// Inflates the IDAT stream without keeping it: its length and every row's filter byte.
std::string CheckImageData(const std::vector<Chunk>& chunks, const Header& h) {
  const std::vector<RowRun> runs = Rows(h);
  size_t run = 0;
  std::uint64_t row = 0, at_in_row = 0;  // position in the expected rows
  z_stream z{};
  if (inflateInit(&z) != Z_OK) return "cannot check the image data (zlib)";
  std::array<std::uint8_t, 1 << 16> out{};
  int status = Z_OK;
  std::string problem;
  for (const Chunk& c : chunks) {
    if (c.type != "IDAT" || !problem.empty()) continue;
    if (status == Z_STREAM_END) {
      if (c.length > 0) problem = "corrupt PNG (data after the end of the image data)";
      continue;
    }
    z.next_in = const_cast<Bytef*>(c.data);
    z.avail_in = c.length;
    do {  // until this chunk is used up and zlib holds no more output
      z.next_out = out.data();
      z.avail_out = static_cast<uInt>(out.size());
      status = inflate(&z, Z_NO_FLUSH);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) {
        problem = std::string("corrupt PNG (image data: ") + (z.msg ? z.msg : "zlib error") + ")";
        break;
      }
      const size_t produced = out.size() - z.avail_out;
      for (size_t i = 0; i < produced && problem.empty();) {
        if (run == runs.size()) {
          problem = "corrupt PNG (more image data than the header's size)";
        } else if (at_in_row == 0 && out[i] > 4) {
          problem = "corrupt PNG (row filter type " + std::to_string(out[i]) + ")";
        } else {
          const std::uint64_t take =
              std::min<std::uint64_t>(produced - i, runs[run].bytes - at_in_row);
          i += take;
          at_in_row += take;
          if (at_in_row == runs[run].bytes) {
            at_in_row = 0;
            if (++row == runs[run].rows) row = 0, ++run;
          }
        }
      }
      if (status == Z_BUF_ERROR && z.avail_in > 0 && produced == 0) {
        problem = "corrupt PNG (image data: zlib made no progress)";
      }
    } while (problem.empty() && status != Z_STREAM_END && (z.avail_in > 0 || z.avail_out == 0));
    if (problem.empty() && status == Z_STREAM_END && z.avail_in > 0)
      problem = "corrupt PNG (data after the end of the image data)";
  }
  inflateEnd(&z);
  if (!problem.empty()) return problem;
  if (status != Z_STREAM_END) return "truncated PNG (the image data stream does not end)";
  if (run != runs.size()) return "truncated PNG (less image data than the header's size)";
  return "";
}

std::string CheckChunkOrder(const std::vector<Chunk>& chunks) {
  bool in_idat = false, idat_done = false;
  for (const Chunk& c : chunks) {
    for (const char ch : c.type) {
      if (!((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z')))
        return "corrupt PNG (a chunk type is not 4 letters)";
    }
    const bool known = c.type == "IHDR" || c.type == "PLTE" || c.type == "IDAT" || c.type == "IEND";
    if (Critical(c.type) && !known)
      return "unsupported PNG (unknown critical chunk " + c.type + ")";
    if (c.type == "IHDR" && &c != &chunks.front()) return "corrupt PNG (two IHDR chunks)";
    if (c.type == "IDAT") {
      if (idat_done) return "corrupt PNG (IDAT chunks not in one run)";
      in_idat = true;
    } else if (in_idat) {
      idat_done = true;
      in_idat = false;
    }
    if (c.type == "PLTE" && idat_done) return "corrupt PNG (PLTE after the image data)";
  }
  if (!idat_done) return "corrupt PNG (no image data)";
  return "";
}

std::vector<std::uint8_t> EssentialChunks(const std::vector<std::uint8_t>& b,
                                          const std::vector<Chunk>& chunks) {
  bool other = false;
  for (const Chunk& c : chunks) other |= !(Critical(c.type) || c.type == "tRNS");
  if (!other) return {};
  std::vector<std::uint8_t> out(b.begin(), b.begin() + 8);
  for (const Chunk& c : chunks) {
    if (!(Critical(c.type) || c.type == "tRNS")) continue;
    const auto from = b.begin() + static_cast<std::ptrdiff_t>(c.start);
    out.insert(out.end(), from, from + 12 + c.length);
  }
  return out;
}

}  // namespace

PngCheck CheckPng(const std::vector<std::uint8_t>& bytes) {
  PngCheck check;
  std::vector<Chunk> chunks;
  Header header;
  check.problem = ReadChunks(bytes, chunks);
  if (check.problem.empty()) check.problem = CheckChunkOrder(chunks);
  if (check.problem.empty()) check.problem = ReadHeader(chunks.front(), header);
  if (check.problem.empty()) check.problem = CheckPalette(chunks, header);
  if (check.problem.empty()) check.problem = CheckImageData(chunks, header);
  if (!check.problem.empty()) return check;
  check.essential = EssentialChunks(bytes, chunks);
  return check;
}

}  // namespace sewer3d
