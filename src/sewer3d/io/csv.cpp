#include "sewer3d/io/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

std::vector<CsvRow> ReadCsv(const std::filesystem::path& path, const std::string& header) {
  std::string text = ReadTextFile(path);
  // Spreadsheet exports: a UTF-8 byte-order mark first, CRLF line ends; both are read as plain.
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw FileError(path, fmt::format("a NUL byte at offset {}: not a text file", nul));
  std::istringstream in(text);
  std::string line;
  const auto next = [&] {
    if (!std::getline(in, line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  if (!next() || line != header)
    throw FileError(path,
                    "line 1: header must be '" + header + "', got '" + line.substr(0, 80) + "'");
  const size_t columns = std::count(header.begin(), header.end(), ',') + 1;
  std::vector<CsvRow> rows;
  for (int number = 2; next(); ++number) {
    if (line.empty()) continue;
    CsvRow row;
    row.line = number;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) row.fields.push_back(f);
    if (!line.empty() && line.back() == ',') row.fields.emplace_back();
    if (row.fields.size() != columns) {
      throw FileError(
          path, fmt::format("line {}: {} fields, expected {}", number, row.fields.size(), columns));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

double CsvNumber(const std::filesystem::path& path, const CsvRow& row, size_t column,
                 const char* name) {
  const std::string& text = row.fields.at(column);
  try {
    size_t used = 0;
    const double x = std::stod(text, &used);
    if (used == text.size() && std::isfinite(x)) return x;
  } catch (const std::exception&) {
  }
  throw FileError(path, fmt::format("line {}: {} '{}' is not a number", row.line, name, text));
}

int CsvInteger(const std::filesystem::path& path, const CsvRow& row, size_t column,
               const char* name) {
  const double x = CsvNumber(path, row, column, name);
  if (x != std::floor(x)) {
    throw FileError(path, fmt::format("line {}: {} '{}' is not an integer", row.line, name,
                                      row.fields[column]));
  }
  if (std::abs(x) > 1e9) {
    throw FileError(path, fmt::format("line {}: {} '{}' is out of range (at most 1e9)", row.line,
                                      name, row.fields[column]));
  }
  return static_cast<int>(x);
}

ImageKind CsvImageKind(const std::filesystem::path& path, const CsvRow& row, size_t column) {
  const auto kind = ParseImageKind(row.fields.at(column));
  if (!kind) {
    throw FileError(path, fmt::format("line {}: image '{}' must be texture_before, pattern or "
                                      "texture_after",
                                      row.line, row.fields[column]));
  }
  return *kind;
}

}  // namespace sewer3d
