#include "sewer3d/decode/codewords.hpp"

#include <map>
#include <unordered_map>

namespace sewer3d {
namespace {

long long NodeKey(int group, int row, int col) {
  return (static_cast<long long>(group) << 40) ^ (static_cast<long long>(row + (1 << 19)) << 20) ^
         static_cast<long long>(col + (1 << 19));
}

int Mod(int a, int m) { return ((a % m) + m) % m; }

struct WindowResult {
  bool decoded = false;
  int row_offset = 0, col_offset = 0;  // array position − lattice position (mod sizes)
  std::uint64_t corrected = 0;         // bits where the observation differs from the codeword
};

}  // namespace

std::vector<SpotCode> DecodeCodewords(const std::vector<Spot>& spots, const LatticeLabels& lattice,
                                      const Codebook& codebook, int array_rows, int array_cols,
                                      cv::Size image_size, const CodewordOptions& options,
                                      CodewordStats* stats) {
  CodewordStats local;
  CodewordStats& st = stats ? *stats : local;
  const int n = codebook.window();
  std::unordered_map<long long, int> occupied;  // node -> spot
  for (size_t i = 0; i < spots.size(); ++i) {
    if (lattice.group[i] >= 0) {
      occupied[NodeKey(lattice.group[i], lattice.node[i].x(), lattice.node[i].y())] = static_cast<int>(i);
    }
  }
  std::unordered_map<long long, WindowResult> windows;
  auto read_window = [&](int s, int top, int left) -> WindowResult {
    const int group = lattice.group[s];
    const long long key = NodeKey(group, top, left);
    if (const auto it = windows.find(key); it != windows.end()) return it->second;
    WindowResult result;
    std::uint64_t code = 0;
    bool observable = true;
    const Eigen::Vector2d& p = spots[s].centre_px;
    const LatticeSteps& steps = lattice.steps[s];
    for (int i = 0; i < n && observable; ++i) {
      for (int j = 0; j < n; ++j) {
        const int row = top + i, col = left + j;
        const Eigen::Vector2d q = p + steps.row_step * (row - lattice.node[s].x()) +
                                  steps.column_step * (col - lattice.node[s].y());
        if (q.x() < options.border_px || q.y() < options.border_px ||
            q.x() > image_size.width - 1 - options.border_px ||
            q.y() > image_size.height - 1 - options.border_px) {
          observable = false;
          break;
        }
        if (occupied.count(NodeKey(group, row, col))) code |= std::uint64_t{1} << (i * n + j);
      }
    }
    if (observable) {
      ++st.windows_read;
      if (const auto match = codebook.Decode(code, codebook.min_hamming() >= 3 ? 1 : 0)) {
        ++st.windows_decoded;
        st.bits_corrected += match->corrected_bits;
        result.decoded = true;
        result.row_offset = Mod(match->position.row - top, array_rows);
        result.col_offset = Mod(match->position.col - left, array_cols);
        result.corrected = code ^ match->codeword;
      }
    }
    windows.emplace(key, result);
    return result;
  };

  std::vector<SpotCode> codes;
  for (size_t s = 0; s < spots.size(); ++s) {
    if (lattice.group[s] < 0) continue;
    std::map<std::pair<int, int>, int> votes;
    int total = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const WindowResult w = read_window(static_cast<int>(s), lattice.node[s].x() - i, lattice.node[s].y() - j);
        if (!w.decoded) continue;
        // The spot itself was the corrected bit: the codeword says no spot at its node. A spot
        // whose lattice label slipped by one element always lands on such a node (spots are
        // isolated), so it must not inherit its neighbours' offset.
        if (w.corrected & (std::uint64_t{1} << (i * n + j))) continue;
        ++votes[{w.row_offset, w.col_offset}];
        ++total;
      }
    }
    int best = 0;
    std::pair<int, int> winner{0, 0};
    for (const auto& [offset, count] : votes) {
      if (count > best) best = count, winner = offset;
    }
    if (best < options.min_votes || best < options.min_agreement * total) {
      if (total > 0) ++st.spots_ambiguous;
      continue;
    }
    SpotCode code;
    code.spot = static_cast<int>(s);
    code.row = Mod(lattice.node[s].x() + winner.first, array_rows);
    code.col = Mod(lattice.node[s].y() + winner.second, array_cols);
    code.votes = best;
    code.dissent = total - best;
    codes.push_back(code);
    ++st.spots_decoded;
  }
  return codes;
}

}  // namespace sewer3d
