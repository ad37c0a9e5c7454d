#include "sewer3d/io/inclinometer_io.hpp"

#include <fmt/format.h>

#include <string>

#include "sewer3d/io/csv.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

constexpr const char* kHeader = "time_s,down_x,down_y,down_z";

}  // namespace

void WriteInclinometer(const std::filesystem::path& path,
                       const std::vector<InclinometerReading>& readings) {
  std::string text = std::string(kHeader) + "\n";
  for (const InclinometerReading& r : readings) {
    const Eigen::Vector3d& d = r.down_in_carrier;
    text += fmt::format("{:.6f},{:.9f},{:.9f},{:.9f}\n", r.time_s, d.x(), d.y(), d.z());
  }
  WriteTextFile(path, text);
}

std::vector<InclinometerReading> ReadInclinometer(const std::filesystem::path& path) {
  std::vector<InclinometerReading> out;
  for (const CsvRow& row : ReadCsv(path, kHeader)) {
    InclinometerReading r;
    r.line = row.line;
    r.time_s = CsvNumber(path, row, 0, "time_s");
    r.down_in_carrier = {CsvNumber(path, row, 1, "down_x"), CsvNumber(path, row, 2, "down_y"),
                         CsvNumber(path, row, 3, "down_z")};
    if (!(r.down_in_carrier.norm() > 1e-6)) {
      throw FileError(
          path, fmt::format("line {}: the direction ({}, {}, {}) has no length", row.line,
                            r.down_in_carrier.x(), r.down_in_carrier.y(), r.down_in_carrier.z()));
    }
    if (!out.empty() && r.time_s <= out.back().time_s) {
      throw FileError(path,
                      fmt::format("line {}: time_s {} does not increase", row.line, r.time_s));
    }
    r.down_in_carrier.normalize();
    out.push_back(r);
  }
  return out;
}

}  // namespace sewer3d
