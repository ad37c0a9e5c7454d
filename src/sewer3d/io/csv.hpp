#pragma once
/// \file
/// Internal to the file readers (io/, simio/): the CSV files of a capture run (comma-separated,
/// one header line, no quoting) with errors that name the file and the line.

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// One data line of a CSV file: its fields and its line number in the file (1 = header).
struct CsvRow {
  std::vector<std::string> fields;
  int line = 0;
};

/// The data lines of a CSV file whose first line must be `header`; blank lines are skipped.
/// Throws FileError naming the line when a line has the wrong number of fields.
std::vector<CsvRow> ReadCsv(const std::filesystem::path& path, const std::string& header);

/// Parsers of one field; throw FileError "PATH: line N: column: 'text' is not …".
double CsvNumber(const std::filesystem::path& path, const CsvRow& row, size_t column,
                 const char* name);
int CsvInteger(const std::filesystem::path& path, const CsvRow& row, size_t column,
               const char* name);
ImageKind CsvImageKind(const std::filesystem::path& path, const CsvRow& row, size_t column);

/// The columns every per-image file starts with: module, counter, image, time_s.
template <typename Row>
void ReadImageKey(const std::filesystem::path& path, const CsvRow& row, Row& out) {
  out.module = CsvInteger(path, row, 0, "module");
  out.counter = CsvInteger(path, row, 1, "counter");
  out.kind = CsvImageKind(path, row, 2);
  out.time_s = CsvNumber(path, row, 3, "time_s");
}

}  // namespace sewer3d
