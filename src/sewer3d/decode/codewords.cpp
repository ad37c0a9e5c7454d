#include "sewer3d/decode/codewords.hpp"

#include <algorithm>
#include <climits>

namespace sewer3d {
namespace {

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
  // Dense grids per group over its nodes' bounding box, grown by a window on the low sides
  // (windows start up to n − 1 nodes before a spot): occupancy and the cached window results.
  struct GroupGrid {
    int r0 = 0, c0 = 0, rows = 0, cols = 0, words = 0;  // words: 64-bit words per row (padded)
    std::vector<std::uint64_t> occupied;                // one bit per node
    void Set(int r, int c) {
      const int k = c - c0;
      occupied[static_cast<size_t>(r - r0) * words + (k >> 6)] |= std::uint64_t{1} << (k & 63);
    }
    // Bits of nodes (r, c .. c + width − 1), lowest bit first; 0 outside the grid.
    std::uint64_t Bits(int r, int c, int width) const {
      if (r < r0 || r >= r0 + rows) return 0;
      const int k = c - c0;  // >= 0: the grid starts a window before any node
      const std::uint64_t* row = occupied.data() + static_cast<size_t>(r - r0) * words;
      const int w = k >> 6, shift = k & 63;
      std::uint64_t bits = row[w] >> shift;
      if (shift != 0) bits |= row[w + 1] << (64 - shift);
      return bits & ((std::uint64_t{1} << width) - 1);
    }
    std::vector<std::int8_t> state;  // −1 not read yet, 0 unobservable or not decoded, 1 decoded
    std::vector<WindowResult> results;
    int Index(int r, int c) const { return (r - r0) * cols + (c - c0); }
  };
  std::vector<GroupGrid> grids(lattice.groups);
  {
    std::vector<Eigen::Vector4i> box(lattice.groups,
                                     Eigen::Vector4i(INT_MAX, INT_MAX, INT_MIN, INT_MIN));
    for (size_t i = 0; i < spots.size(); ++i) {
      if (lattice.group[i] < 0) continue;
      Eigen::Vector4i& b = box[lattice.group[i]];
      const Eigen::Vector2i& node = lattice.node[i];
      b = Eigen::Vector4i(std::min(b[0], node.x()), std::min(b[1], node.y()),
                          std::max(b[2], node.x()), std::max(b[3], node.y()));
    }
    for (int g = 0; g < lattice.groups; ++g) {
      if (box[g][0] > box[g][2]) continue;
      GroupGrid& grid = grids[g];
      grid.r0 = box[g][0] - (n - 1);
      grid.c0 = box[g][1] - (n - 1);
      grid.rows = box[g][2] - grid.r0 + 1;
      grid.cols = box[g][3] - grid.c0 + 1;
      grid.words = (grid.cols + n) / 64 + 2;  // room for a window past the last column
      grid.occupied.assign(static_cast<size_t>(grid.rows) * grid.words, 0);
      grid.state.assign(static_cast<size_t>(grid.rows) * grid.cols, -1);
      grid.results.resize(grid.state.size());
    }
    for (size_t i = 0; i < spots.size(); ++i) {
      if (lattice.group[i] < 0) continue;
      GroupGrid& grid = grids[lattice.group[i]];
      grid.Set(lattice.node[i].x(), lattice.node[i].y());
    }
  }
  auto inside_image = [&](const Eigen::Vector2d& q) {
    return q.x() >= options.border_px && q.y() >= options.border_px &&
           q.x() <= image_size.width - 1 - options.border_px &&
           q.y() <= image_size.height - 1 - options.border_px;
  };
  // The window with top-left node (top, left) of spot s's group, read once; its nodes' image
  // positions are extrapolated with s's local steps (affine, so its corners decide).
  auto read_window = [&](int s, int top, int left) -> const WindowResult* {
    GroupGrid& grid = grids[lattice.group[s]];
    const int index = grid.Index(top, left);
    if (grid.state[index] >= 0) return grid.state[index] ? &grid.results[index] : nullptr;
    grid.state[index] = 0;
    const Eigen::Vector2d& p = spots[s].centre_px;
    const LatticeSteps& steps = lattice.steps[s];
    const Eigen::Vector2d origin = p + steps.row_step * (top - lattice.node[s].x()) +
                                   steps.column_step * (left - lattice.node[s].y());
    const Eigen::Vector2d down = steps.row_step * (n - 1), right = steps.column_step * (n - 1);
    if (!inside_image(origin) || !inside_image(origin + down) || !inside_image(origin + right) ||
        !inside_image(origin + down + right)) {
      return nullptr;
    }
    std::uint64_t code = 0;
    for (int i = 0; i < n; ++i) code |= grid.Bits(top + i, left, n) << (i * n);
    ++st.windows_read;
    const auto match = codebook.Decode(code, codebook.min_hamming() >= 3 ? 1 : 0);
    if (!match) return nullptr;
    ++st.windows_decoded;
    st.bits_corrected += match->corrected_bits;
    WindowResult& result = grid.results[index];
    result.decoded = true;
    result.row_offset = Mod(match->position.row - top, array_rows);
    result.col_offset = Mod(match->position.col - left, array_cols);
    result.corrected = code ^ match->codeword;
    grid.state[index] = 1;
    return &result;
  };

  std::vector<SpotCode> codes;
  std::vector<std::pair<std::pair<int, int>, int>> votes;  // (offset, count), few entries
  for (size_t s = 0; s < spots.size(); ++s) {
    if (lattice.group[s] < 0) continue;
    votes.clear();
    int total = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const WindowResult* w =
            read_window(static_cast<int>(s), lattice.node[s].x() - i, lattice.node[s].y() - j);
        if (!w) continue;
        // The spot itself was the corrected bit: the codeword says no spot at its node. A spot
        // whose lattice label slipped by one element always lands on such a node (spots are
        // isolated), so it must not inherit its neighbours' offset.
        if (w->corrected & (std::uint64_t{1} << (i * n + j))) continue;
        const std::pair<int, int> offset{w->row_offset, w->col_offset};
        auto it = std::find_if(votes.begin(), votes.end(),
                               [&](const auto& v) { return v.first == offset; });
        if (it == votes.end())
          votes.push_back({offset, 1});
        else
          ++it->second;
        ++total;
      }
    }
    int best = 0;
    std::pair<int, int> winner{0, 0};
    for (const auto& [offset, count] : votes) {
      if (count > best || (count == best && offset < winner)) best = count, winner = offset;
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
