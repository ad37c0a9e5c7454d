#include "sewer3d/report/html.hpp"

#include <fmt/core.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d::html {

std::string Escape(std::string_view text) { return EscapeMarkup(text); }

std::string Base64(std::string_view bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16U |
                       static_cast<unsigned char>(bytes[i + 1]) << 8U |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += kDigits[(v >> (6U * k)) & 63U];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16U;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8U;
    out += kDigits[(v >> 18U) & 63U];
    out += kDigits[(v >> 12U) & 63U];
    out += rest == 2 ? kDigits[(v >> 6U) & 63U] : '=';
    out += '=';
  }
  return out;
}

namespace {

std::string DataUri(const cv::Mat3b& image, const std::string& ext, const std::string& mime,
                    const std::vector<int>& params) {
  if (image.empty()) return "";
  std::vector<unsigned char> bytes;
  SEWER3D_CHECK(cv::imencode(ext, image, bytes, params), "image encoding failed");
  return "data:" + mime + ";base64," +
         Base64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

std::string JpegDataUri(const cv::Mat3b& image, int quality) {
  return DataUri(image, ".jpg", "image/jpeg", {cv::IMWRITE_JPEG_QUALITY, quality});
}

std::string PngDataUri(const cv::Mat3b& image) {
  return DataUri(image, ".png", "image/png", {cv::IMWRITE_PNG_COMPRESSION, 6});
}

std::string ScriptJson(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (std::size_t i = 0; i < json_text.size(); ++i) {
    if (json_text[i] == '<' && i + 1 < json_text.size() && json_text[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += json_text[i];
    }
  }
  return out;
}

std::string Fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "–";
  return fmt::format("{:.{}f}", value, decimals);
}

std::string Table(const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows, const std::string& css_class,
                  int markup_column) {
  std::string out = css_class.empty() ? "<table>" : "<table class=\"" + css_class + "\">";
  out += "<thead><tr>";
  for (const std::string& h : header) out += "<th>" + Escape(h) + "</th>";
  out += "</tr></thead><tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (size_t i = 0; i < row.size(); ++i) {
      const bool markup = static_cast<int>(i) == markup_column;
      out += "<td>" + (markup ? row[i] : Escape(row[i])) + "</td>";
    }
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string Note(const std::string& text) { return "<p class=\"note\">" + Escape(text) + "</p>\n"; }

}  // namespace sewer3d::html
