#include "sewer3d/io/pattern_io.hpp"

#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

std::filesystem::path PatternSidecarPath(const std::filesystem::path& matrix_path) {
  std::filesystem::path sidecar = matrix_path;
  sidecar.replace_extension(".json");
  return sidecar;
}

void WritePatternSidecar(const std::filesystem::path& path, const PatternProvenance& provenance,
                         const PatternReport& report) {
  SEWER3D_CHECK(provenance.options != nullptr);
  const SubmapSearchOptions& o = *provenance.options;
  nlohmann::json doc;
  doc["source"] = provenance.source;
  doc["parameters"] = {{"rows", o.rows},
                       {"cols", o.cols},
                       {"window", o.constraints.window},
                       {"min_hamming", o.constraints.min_hamming},
                       {"min_weight", o.constraints.min_weight},
                       {"isolated", o.constraints.isolated},
                       {"torus", o.constraints.torus},
                       {"seed", o.seed}};
  if (provenance.result != nullptr) {
    const SubmapSearchResult& r = *provenance.result;
    doc["search"] = {{"reached", r.reached},
                     {"termination", r.termination},
                     {"final_cost", r.final_cost},
                     {"moves", r.moves},
                     {"seconds", r.elapsed_s}};
  }
  doc["verified"] = {
      {"valid", report.valid},
      {"rows", report.rows},
      {"cols", report.cols},
      {"windows", report.windows},
      {"unique", report.duplicate_pairs == 0},
      {"min_hamming", report.windows >= 2 ? nlohmann::json(report.min_hamming_found)
                                          : nlohmann::json(nullptr)},  // no pair to measure
      {"pairs_below_min_hamming", report.close_pairs},
      {"min_weight", report.min_weight_found},
      {"max_weight", report.max_weight_found},
      {"adjacent_spot_pairs", report.adjacent_spot_pairs},
      {"density", report.density}};
  WriteTextFile(path, doc.dump(2) + "\n");
}

}  // namespace sewer3d
