#pragma once
/// \file
/// Small HTML helpers for the report: escaping, base64 data: URIs of images, tables.

#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace sewer3d::html {

/// Text with &, <, >, " and ' escaped, for element content and attribute values.
std::string Escape(std::string_view text);

/// RFC 4648 base64 of `bytes`.
std::string Base64(std::string_view bytes);

/// A data: URI of `image` (BGR) encoded as JPEG (quality 0..100) or PNG (quality ignored).
/// An empty image gives "".
std::string JpegDataUri(const cv::Mat3b& image, int quality);
std::string PngDataUri(const cv::Mat3b& image);

/// A JSON string literal of `text` safe inside a <script> element ("</" written as "<\/").
std::string ScriptJson(const std::string& json_text);

/// `value` with `decimals` decimals; "–" for NaN or infinity.
std::string Fixed(double value, int decimals);

/// A <table> with a header row and body rows. Cells are escaped, except those of the column
/// `markup_column` (≥ 0), which hold markup made here (an <img>): text from files (an
/// observation's remark) never becomes markup.
std::string Table(const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows,
                  const std::string& css_class = "", int markup_column = -1);

/// A visible note: <p class="note">text</p>.
std::string Note(const std::string& text);

}  // namespace sewer3d::html
