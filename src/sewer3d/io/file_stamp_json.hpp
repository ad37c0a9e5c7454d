#pragma once
/// \file
/// A FileStamp as JSON, as workspace.json and the rgbd reports record it:
/// `{"bytes": N, "mtime_ns": N, "hash": "<16 hex digits>"}`.

#include <nlohmann/json_fwd.hpp>

#include "sewer3d/io/file_stamp.hpp"

namespace sewer3d {

nlohmann::json StampToJson(const FileStamp& stamp);
/// Throws nlohmann::json::exception or std::invalid_argument when a member is missing or of
/// another type; callers that read a file turn that into a FileError naming it.
FileStamp StampFromJson(const nlohmann::json& j);

}  // namespace sewer3d
