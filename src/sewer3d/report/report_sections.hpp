#pragma once
/// \file
/// The report's sections as HTML fragments (report.cpp puts them together).

#include <optional>
#include <string>
#include <vector>

#include "sewer3d/io/model_io.hpp"
#include "sewer3d/report/map_downsample.hpp"
#include "sewer3d/report/report.hpp"

namespace sewer3d::report {

/// What the model pass produced (all empty when the model could not be read).
struct ModelPictures {
  std::optional<PipeModelInfo> info;
  std::optional<CoarseMaps> preview;             ///< the map pictures' cells
  std::optional<CoarseMaps> relief;              ///< the viewer's vertices
  std::vector<std::optional<CoarseMaps>> crops;  ///< per observation
  double heat_range_mm = 10.0;  ///< the heat maps saturate at ± this (model.json's view range)
};

/// The notes the page shows about what is missing; Add returns the note's HTML.
struct Notes {
  std::vector<std::string> list;
  std::string Add(const std::string& text);
};

std::string SummarySection(const ReportInputs& in, const ModelPictures& model);
std::string MapsSection(const ModelPictures& model, int jpeg_quality, Notes& notes);
/// The viewer, or a note when the model or the viewer's script is missing.
std::string ViewerSection(const ModelPictures& model, Notes& notes);
std::string ProfileSection(const std::optional<Profile>& profile, Notes& notes);
std::string ObservationsSection(const std::optional<std::vector<Observation>>& observations,
                                const ModelPictures& model, int jpeg_quality, Notes& notes);
std::string EvaluationSection(const std::vector<EvaluationText>& evaluations);

}  // namespace sewer3d::report
