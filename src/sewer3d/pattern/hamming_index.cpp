#include "sewer3d/pattern/hamming_index.hpp"

#include <algorithm>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

HammingIndex::HammingIndex(int bits, int radius, int capacity) : radius_(radius) {
  SEWER3D_CHECK(bits >= 1 && bits <= 64, "bits " << bits);
  SEWER3D_CHECK(radius >= 0 && radius < bits, "radius " << radius);
  SEWER3D_CHECK(capacity >= 0);
  constexpr int kMaxChunkBits = 16;  // bucket tables of at most 65536 entries per chunk
  chunks_ = std::max(radius + 1, (bits + kMaxChunkBits - 1) / kMaxChunkBits);
  chunks_ = std::min(chunks_, bits);
  std::size_t offset = 0;
  int start = 0;
  for (int k = 0; k < chunks_; ++k) {
    const int width = bits / chunks_ + (k < bits % chunks_ ? 1 : 0);
    shift_.push_back(start);
    mask_.push_back(width == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1);
    offset_.push_back(offset);
    offset += std::size_t{1} << width;
    start += width;
  }
  buckets_.resize(offset);
  codes_.assign(capacity, 0);
  present_.assign(capacity, 0);
}

void HammingIndex::Insert(int id, std::uint64_t code) {
  SEWER3D_CHECK(!present_[id], "id " << id << " already stored");
  codes_[id] = code;
  present_[id] = 1;
  for (int k = 0; k < chunks_; ++k) buckets_[Bucket(k, Key(code, k))].push_back(id);
}

void HammingIndex::Remove(int id) {
  SEWER3D_CHECK(present_[id], "id " << id << " not stored");
  for (int k = 0; k < chunks_; ++k) {
    auto& bucket = buckets_[Bucket(k, Key(codes_[id], k))];
    auto it = std::find(bucket.begin(), bucket.end(), id);
    *it = bucket.back();
    bucket.pop_back();
  }
  present_[id] = 0;
}

}  // namespace sewer3d
