#include "sewer3d/io/file_stamp_json.hpp"

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <string>

namespace sewer3d {

nlohmann::json StampToJson(const FileStamp& stamp) {
  return {{"bytes", stamp.bytes},
          {"mtime_ns", stamp.mtime_ns},
          {"hash", fmt::format("{:016x}", stamp.hash)}};
}

FileStamp StampFromJson(const nlohmann::json& j) {
  FileStamp s;
  s.bytes = j.at("bytes").get<std::uintmax_t>();
  s.mtime_ns = j.at("mtime_ns").get<std::int64_t>();
  s.hash = std::stoull(j.at("hash").get<std::string>(), nullptr, 16);
  return s;
}

}  // namespace sewer3d
