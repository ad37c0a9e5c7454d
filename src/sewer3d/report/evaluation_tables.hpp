#pragma once
/// \file
/// The accuracy section: an evaluation.json (WS/evaluation/<stage>/, written by `sewer3d
/// evaluate`) shown as tables, whatever its stage: nested objects as "a / b" rows, arrays of
/// objects as tables of their own.

#include <string>

namespace sewer3d {

/// HTML tables of the JSON text `json_text` under a heading `name`; a visible note instead
/// when the text is not JSON.
std::string EvaluationTables(const std::string& name, const std::string& json_text);

}  // namespace sewer3d
