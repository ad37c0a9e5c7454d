// CheckPng against PNG files assembled chunk by chunk: every broken one refused with its
// reason, every valid one (interlaced, palette, extra chunks) accepted and decoded alike.
#include "sewer3d/io/png_check.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace sewer3d {
namespace {

using Bytes = std::vector<std::uint8_t>;

void PutU32(Bytes& b, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
}

void PutChunk(Bytes& png, const std::string& type, const Bytes& data) {
  PutU32(png, static_cast<std::uint32_t>(data.size()));
  Bytes body(type.begin(), type.end());
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  PutU32(png, static_cast<std::uint32_t>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
}

Bytes Ihdr(std::uint32_t w, std::uint32_t h, int depth, int colour, int interlace) {
  Bytes d;
  PutU32(d, w);
  PutU32(d, h);
  for (const int v : {depth, colour, 0, 0, interlace}) d.push_back(static_cast<std::uint8_t>(v));
  return d;
}

Bytes Deflate(const Bytes& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  Bytes out(size);
  EXPECT_EQ(compress(out.data(), &size, raw.data(), static_cast<uLong>(raw.size())), Z_OK);
  out.resize(size);
  return out;
}

struct Chunks {
  std::vector<std::pair<std::string, Bytes>> list;
  Bytes File() const {
    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    for (const auto& [type, data] : list) PutChunk(png, type, data);
    return png;
  }
};

// An 8-bit grey image w x h, not interlaced: rows of filter 0 + pixels v * w + u.
Bytes GreyRows(int w, int h) {
  Bytes raw;
  for (int v = 0; v < h; ++v) {
    raw.push_back(0);
    for (int u = 0; u < w; ++u) raw.push_back(static_cast<std::uint8_t>(v * w + u));
  }
  return raw;
}

Chunks Grey(const Bytes& raw, int w = 5, int h = 4) {
  return {{{"IHDR", Ihdr(w, h, 8, 0, 0)}, {"IDAT", Deflate(raw)}, {"IEND", {}}}};
}

std::string Problem(const Chunks& c) { return CheckPng(c.File()).problem; }

TEST(PngCheck, AcceptsWhatOpenCvWrites) {
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_8UC4}) {
    cv::Mat image(37, 53, type);
    cv::randu(image, 0, type == CV_16UC1 ? 65535 : 255);
    Bytes png;
    ASSERT_TRUE(cv::imencode(".png", image, png));
    EXPECT_EQ(CheckPng(png).problem, "") << type;
  }
}

TEST(PngCheck, AcceptsHandMadeGrey) { EXPECT_EQ(Problem(Grey(GreyRows(5, 4))), ""); }

TEST(PngCheck, RefusesTooLittleOrTooMuchData) {
  Bytes raw = GreyRows(5, 4);
  raw.pop_back();
  EXPECT_NE(Problem(Grey(raw)).find("less image data"), std::string::npos);
  raw = GreyRows(5, 4);
  raw.push_back(0);
  EXPECT_NE(Problem(Grey(raw)).find("more image data"), std::string::npos);
}

TEST(PngCheck, RefusesABadFilterType) {
  Bytes raw = GreyRows(5, 4);
  raw[2 * 6] = 5;  // the third row's filter byte
  EXPECT_NE(Problem(Grey(raw)).find("row filter type 5"), std::string::npos);
}

TEST(PngCheck, RefusesDataThatIsNoZlibStream) {
  Chunks c = Grey(GreyRows(5, 4));
  c.list[1].second = Bytes(20, 0xAB);
  EXPECT_NE(Problem(c).find("image data"), std::string::npos);
  c = Grey(GreyRows(5, 4));
  c.list[1].second.resize(c.list[1].second.size() / 2);
  EXPECT_NE(Problem(c).find("truncated PNG"), std::string::npos);
}

TEST(PngCheck, RefusesBadHeadersAndChunkOrder) {
  Chunks c = Grey(GreyRows(5, 4));
  c.list[0].second = Ihdr(5, 4, 16, 3, 0);  // 16-bit palette does not exist
  EXPECT_NE(Problem(c).find("bit depth 16 with colour type 3"), std::string::npos);
  c.list[0].second = Ihdr(5, 4, 8, 0, 2);
  EXPECT_NE(Problem(c).find("interlace"), std::string::npos);
  c = Grey(GreyRows(5, 4));
  c.list.insert(c.list.begin() + 1, {"ABCD", Bytes(3, 1)});
  EXPECT_NE(Problem(c).find("unknown critical chunk ABCD"), std::string::npos);
  c = Grey(GreyRows(5, 4));
  const Bytes data = c.list[1].second;
  c.list[1].second.assign(data.begin(), data.begin() + 4);
  c.list.insert(c.list.begin() + 2, {"tEXt", Bytes{'a', 0, 'b'}});
  c.list.insert(c.list.begin() + 3, {"IDAT", Bytes(data.begin() + 4, data.end())});
  EXPECT_NE(Problem(c).find("IDAT chunks not in one run"), std::string::npos);
  c = Grey(GreyRows(5, 4));
  c.list[0].second = Ihdr(5, 4, 8, 3, 0);
  EXPECT_NE(Problem(c).find("without PLTE"), std::string::npos);
  c.list[0].second = Ihdr(5, 4, 8, 0, 0);
  c.list.insert(c.list.begin() + 1, {"tRNS", Bytes(6, 0)});  // grey takes 2 bytes
  EXPECT_NE(Problem(c).find("tRNS"), std::string::npos);
}

TEST(PngCheck, SplitDataAndAncillaryChunksDecodeAsTheImage) {
  Chunks c = Grey(GreyRows(5, 4));
  const Bytes data = c.list[1].second;
  c.list[1].second.assign(data.begin(), data.begin() + 3);
  c.list.insert(c.list.begin() + 2, {"IDAT", Bytes(data.begin() + 3, data.end())});
  c.list.insert(c.list.begin() + 1, {"gAMA", Bytes{0xFF, 0xFF, 0xFF, 0xFF}});  // nonsense
  const PngCheck check = CheckPng(c.File());
  ASSERT_EQ(check.problem, "");
  ASSERT_FALSE(check.essential.empty());  // gAMA is left out
  const cv::Mat image = cv::imdecode(check.essential, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(image.size(), cv::Size(5, 4));
  for (int v = 0; v < 4; ++v)
    for (int u = 0; u < 5; ++u) EXPECT_EQ(image.at<std::uint8_t>(v, u), v * 5 + u);
}

TEST(PngCheck, InterlacedSizesFollowAdam7) {
  // 2-bit palette, 11 x 7, Adam7: the passes' rows, each 1 filter byte + packed pixels.
  const int w = 11, h = 7;
  const int x0[7] = {0, 4, 0, 2, 0, 1, 0}, dx[7] = {8, 8, 4, 4, 2, 2, 1};
  const int y0[7] = {0, 0, 4, 0, 2, 0, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
  Bytes raw;
  for (int p = 0; p < 7; ++p) {
    const int pw = (w - x0[p] + dx[p] - 1) / dx[p], ph = (h - y0[p] + dy[p] - 1) / dy[p];
    if (pw <= 0 || ph <= 0) continue;
    for (int r = 0; r < ph; ++r) {
      raw.push_back(0);
      for (int k = 0; k < (pw * 2 + 7) / 8; ++k) raw.push_back(0x1B);  // indices 0 1 2 3
    }
  }
  const Bytes palette = {0, 0, 0, 80, 80, 80, 160, 160, 160, 240, 240, 240};
  Chunks c{
      {{"IHDR", Ihdr(w, h, 2, 3, 1)}, {"PLTE", palette}, {"IDAT", Deflate(raw)}, {"IEND", {}}}};
  EXPECT_EQ(Problem(c), "");
  const Bytes file = c.File();
  EXPECT_FALSE(cv::imdecode(file, cv::IMREAD_GRAYSCALE).empty());
  raw.push_back(0);
  c.list[2].second = Deflate(raw);
  EXPECT_NE(Problem(c).find("more image data"), std::string::npos);
}

}  // namespace
}  // namespace sewer3d
