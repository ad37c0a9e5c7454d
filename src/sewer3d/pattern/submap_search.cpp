#include "sewer3d/pattern/submap_search.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "sewer3d/pattern/hamming_index.hpp"

namespace sewer3d {
namespace {

/// A set of ints in [0, capacity) with O(1) insert, erase and uniform sampling.
class IndexedSet {
 public:
  explicit IndexedSet(int capacity) : position_(capacity, -1) {}
  void Set(int id, bool member) {
    if (member == (position_[id] >= 0)) return;
    if (member) {
      position_[id] = static_cast<int>(items_.size());
      items_.push_back(id);
    } else {
      const int last = items_.back();
      items_[position_[id]] = last;
      position_[last] = position_[id];
      items_.pop_back();
      position_[id] = -1;
    }
  }
  int size() const { return static_cast<int>(items_.size()); }
  int Sample(std::mt19937_64& rng) const {
    return items_[std::uniform_int_distribution<int>(0, size() - 1)(rng)];
  }

 private:
  std::vector<int> position_;
  std::vector<int> items_;
};

struct Change {
  int cell;
  std::uint8_t value;
};

/// The array, its window codes and the bookkeeping of the cost.
class SearchState {
 public:
  explicit SearchState(const SubmapSearchOptions& o)
      : rows_(o.rows),
        cols_(o.cols),
        n_(o.constraints.window),
        min_hamming_(o.constraints.min_hamming),
        min_weight_(o.constraints.min_weight),
        isolated_(o.constraints.isolated),
        win_rows_(o.constraints.torus ? rows_ : rows_ - n_ + 1),
        win_cols_(o.constraints.torus ? cols_ : cols_ - n_ + 1),
        windows_(win_rows_ * win_cols_),
        index_(n_ * n_, min_hamming_ - 1, windows_),
        violated_(windows_),
        cells_(rows_ * cols_, 0),
        codes_(windows_, 0),
        conflicts_(windows_, 0),
        stamp_(windows_, 0),
        slot_(windows_, 0),
        cell_windows_(rows_ * cols_),
        neighbours_(rows_ * cols_) {
    const bool torus = o.constraints.torus;
    for (int wr = 0; wr < win_rows_; ++wr) {
      for (int wc = 0; wc < win_cols_; ++wc) {
        for (int i = 0; i < n_; ++i) {
          for (int j = 0; j < n_; ++j) {
            const int cell = ((wr + i) % rows_) * cols_ + (wc + j) % cols_;
            cell_windows_[cell].push_back({wr * win_cols_ + wc, i * n_ + j});
          }
        }
      }
    }
    for (int r = 0; r < rows_; ++r) {
      for (int c = 0; c < cols_; ++c) {
        for (int dr = -1; dr <= 1; ++dr) {
          for (int dc = -1; dc <= 1; ++dc) {
            if (dr == 0 && dc == 0) continue;
            int rr = r + dr, cc = c + dc;
            if (!torus && (rr < 0 || rr >= rows_ || cc < 0 || cc >= cols_)) continue;
            rr = (rr + rows_) % rows_;
            cc = (cc + cols_) % cols_;
            const int other = rr * cols_ + cc;
            auto& list = neighbours_[r * cols_ + c];
            if (other != r * cols_ + c &&
                std::find(list.begin(), list.end(), other) == list.end()) {
              list.push_back(other);
            }
          }
        }
      }
    }
  }

  int windows() const { return windows_; }
  int cells() const { return rows_ * cols_; }
  int window_cell(int w, int i, int j) const {
    const int wr = w / win_cols_, wc = w % win_cols_;
    return ((wr + i) % rows_) * cols_ + (wc + j) % cols_;
  }
  int n() const { return n_; }
  std::uint8_t cell(int c) const { return cells_[c]; }
  const std::vector<int>& neighbours(int c) const { return neighbours_[c]; }
  int cost() const { return conflict_pairs_ + deficit_; }
  const IndexedSet& violated() const { return violated_; }

  /// Random isolated start: elements in random order, each set with probability p if free.
  /// False when `stop` ended the set-up (the conflict counts are then incomplete).
  bool Initialise(std::mt19937_64& rng, double p, const std::function<bool()>& stop) {
    std::vector<int> order(cells());
    for (int i = 0; i < cells(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::bernoulli_distribution coin(p);
    for (int c : order) {
      const bool free = !isolated_ || std::none_of(neighbours_[c].begin(), neighbours_[c].end(),
                                                   [&](int o) { return cells_[o] != 0; });
      if (free && coin(rng)) cells_[c] = 1;
    }
    return Rebuild(stop);
  }

  const std::vector<std::uint8_t>& cells_vector() const { return cells_; }

  /// Change of the cost if `changes` were applied.
  int Delta(const std::vector<Change>& changes) {
    Gather(changes);
    int delta = 0;
    for (size_t a = 0; a < affected_.size(); ++a) {
      const int w = affected_[a];
      const std::uint64_t old_code = codes_[w], new_code = new_codes_[a];
      delta += Deficit(new_code) - Deficit(old_code);
      // Pairs with windows outside the affected set: index counts minus affected members.
      int outside = index_.CountWithin(new_code) - index_.CountWithin(old_code);
      for (size_t b = 0; b < affected_.size(); ++b) {
        const std::uint64_t other = codes_[affected_[b]];
        outside -= Close(new_code, other);
        outside += Close(old_code, other);
      }
      delta += outside;
      for (size_t b = a + 1; b < affected_.size(); ++b) {
        delta += Close(new_code, new_codes_[b]) - Close(old_code, codes_[affected_[b]]);
      }
    }
    return delta;
  }

  void Apply(const std::vector<Change>& changes) {
    Gather(changes);
    touched_.clear();
    for (int w : affected_) {
      index_.ForEachWithin(codes_[w], [&](int v) {
        if (v == w) return;
        --conflicts_[v];
        --conflicts_[w];
        --conflict_pairs_;
        touched_.push_back(v);
      });
      index_.Remove(w);
      deficit_ -= Deficit(codes_[w]);
    }
    for (size_t a = 0; a < affected_.size(); ++a) {
      const int w = affected_[a];
      codes_[w] = new_codes_[a];
      deficit_ += Deficit(codes_[w]);
      index_.ForEachWithin(codes_[w], [&](int v) {
        ++conflicts_[v];
        ++conflicts_[w];
        ++conflict_pairs_;
        touched_.push_back(v);
      });
      index_.Insert(w, codes_[w]);
    }
    for (const Change& ch : changes) cells_[ch.cell] = ch.value;
    for (int w : affected_) UpdateViolated(w);
    for (int v : touched_) UpdateViolated(v);
  }

 private:
  int Close(std::uint64_t a, std::uint64_t b) const {
    return std::popcount(a ^ b) < min_hamming_ ? 1 : 0;
  }
  int Deficit(std::uint64_t code) const { return std::max(0, min_weight_ - std::popcount(code)); }
  void UpdateViolated(int w) {
    violated_.Set(w, conflicts_[w] > 0 || std::popcount(codes_[w]) < min_weight_);
  }

  bool Rebuild(const std::function<bool()>& stop) {
    index_ = HammingIndex(n_ * n_, min_hamming_ - 1, windows_);
    conflict_pairs_ = 0;
    deficit_ = 0;
    std::fill(codes_.begin(), codes_.end(), 0);
    for (int c = 0; c < cells(); ++c) {
      if (!cells_[c]) continue;
      for (auto [w, bit] : cell_windows_[c]) codes_[w] |= std::uint64_t{1} << bit;
    }
    for (int w = 0; w < windows_; ++w) {
      // Large arrays with a wide distance take seconds here: the time budget holds too.
      if (w % 1024 == 0 && stop()) return false;
      conflicts_[w] = 0;
      index_.ForEachWithin(codes_[w], [&](int v) {
        ++conflicts_[v];
        ++conflicts_[w];
        ++conflict_pairs_;
      });
      index_.Insert(w, codes_[w]);
      deficit_ += Deficit(codes_[w]);
    }
    for (int w = 0; w < windows_; ++w) UpdateViolated(w);
    return true;
  }

  // Fills affected_ / new_codes_ with the windows that `changes` modify.
  void Gather(const std::vector<Change>& changes) {
    ++generation_;
    affected_.clear();
    new_codes_.clear();
    for (const Change& ch : changes) {
      if (cells_[ch.cell] == ch.value) continue;
      for (auto [w, bit] : cell_windows_[ch.cell]) {
        if (stamp_[w] != generation_) {
          stamp_[w] = generation_;
          slot_[w] = static_cast<int>(affected_.size());
          affected_.push_back(w);
          new_codes_.push_back(codes_[w]);
        }
        new_codes_[slot_[w]] ^= std::uint64_t{1} << bit;
      }
    }
  }

  int rows_, cols_, n_, min_hamming_, min_weight_;
  bool isolated_;
  int win_rows_, win_cols_, windows_;
  HammingIndex index_;
  IndexedSet violated_;
  std::vector<std::uint8_t> cells_;
  std::vector<std::uint64_t> codes_;
  std::vector<int> conflicts_;
  std::vector<std::uint32_t> stamp_;
  std::vector<int> slot_;
  std::uint32_t generation_ = 0;
  std::vector<std::vector<std::pair<int, int>>> cell_windows_;  // (window, bit)
  std::vector<std::vector<int>> neighbours_;
  std::vector<int> affected_;
  std::vector<std::uint64_t> new_codes_;
  std::vector<int> touched_;
  int conflict_pairs_ = 0;
  int deficit_ = 0;
};

}  // namespace

namespace {

// n choose k as a double (exact up to 2^53; a bound beyond).
double BinomialCoefficient(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// How many n x n windows hold at least min_weight spots, with no two spots 8-adjacent when
// isolated: row by row, each row a bit mask, counting by spot count.
double DistinctWindows(int n, int min_weight, bool isolated) {
  if (!isolated) {
    double distinct = 0.0;
    for (int k = min_weight; k <= n * n; ++k) distinct += std::round(BinomialCoefficient(n * n, k));
    return distinct;
  }
  const int masks = 1 << n;
  auto alone = [](int m) { return (m & (m << 1)) == 0; };
  // by[mask][w]: windows of the rows so far whose last row is mask, holding w spots.
  std::vector<std::vector<double>> by(masks, std::vector<double>(n * n + 1, 0.0));
  for (int m = 0; m < masks; ++m)
    if (alone(m)) by[m][std::popcount(static_cast<unsigned>(m))] = 1.0;
  for (int row = 1; row < n; ++row) {
    std::vector<std::vector<double>> next(masks, std::vector<double>(n * n + 1, 0.0));
    for (int m = 0; m < masks; ++m) {
      if (!alone(m)) continue;
      const int add = std::popcount(static_cast<unsigned>(m));
      for (int prev = 0; prev < masks; ++prev) {
        if ((m & (prev | prev << 1 | prev >> 1)) != 0) continue;
        for (int w = 0; w + add <= n * n; ++w) next[m][w + add] += by[prev][w];
      }
    }
    by = std::move(next);
  }
  double distinct = 0.0;
  for (int m = 0; m < masks; ++m)
    for (int w = min_weight; w <= n * n; ++w) distinct += by[m][w];
  return distinct;
}

}  // namespace

void SubmapSearchOptions::Check() const {
  constraints.Check();
  const int n = constraints.window;
  // The field that is too small (both when both are).
  const char* small = rows < n && cols < n ? "rows, cols" : rows < n ? "rows" : "cols";
  SEWER3D_VALIDATE(rows >= n && cols >= n, small,
                   "the array (" << rows << "x" << cols << ") must be at least the window (" << n
                                 << "x" << n << ")");
  SEWER3D_VALIDATE(static_cast<std::int64_t>(rows) * cols <= kMaxPatternElements, "cols",
                   "the array (" << rows << "x" << cols << ") must have at most "
                                 << kMaxPatternElements << " elements");
  // Every window must differ from every other: there must be as many distinct windows of
  // at least min_weight spots as the array has windows (the isolated rule allows even fewer).
  const double distinct = DistinctWindows(n, constraints.min_weight, constraints.isolated);
  const int needed = WindowCount(rows, cols, constraints);
  SEWER3D_VALIDATE(needed >= 2, "rows",
                   "the " << rows << "x" << cols << " array holds one " << n << "x" << n
                          << " window: a perfect submap needs at least 2 (a larger array, or a "
                             "torus)");
  // With no spots required the window itself is too small (or the array too large).
  SEWER3D_VALIDATE(distinct >= needed, constraints.min_weight > 0 ? "min_weight" : "window",
                   "only " << distinct << " distinct " << n << "x" << n << " windows have at least "
                           << constraints.min_weight << " spots"
                           << (constraints.isolated ? " with none 8-adjacent" : "") << ", and the "
                           << rows << "x" << cols << " array needs " << needed);
  // Codes of n*n bits at least d apart: no more than the Hamming (sphere-packing) bound,
  // 2^(n*n) / (the number of codes within (d - 1) / 2 of one).
  const int bits = n * n, radius = (constraints.min_hamming - 1) / 2;
  double ball = 0.0;
  for (int k = 0; k <= std::min(radius, bits); ++k) ball += BinomialCoefficient(bits, k);
  // Two windows of isolated spots differ in at most twice the most such spots one can hold.
  const int most_isolated = ((n + 1) / 2) * ((n + 1) / 2);
  const bool too_far = constraints.min_hamming > bits ||
                       (constraints.isolated && constraints.min_hamming > 2 * most_isolated);
  const double most = too_far ? 1.0 : std::floor(std::ldexp(1.0, bits) / ball);
  SEWER3D_VALIDATE(most >= needed, "min_hamming",
                   "at most " << most << " " << n << "x" << n << " windows can differ pairwise in "
                              << constraints.min_hamming << " spots, and the " << rows << "x"
                              << cols << " array needs " << needed);
  SEWER3D_VALIDATE(max_moves > 0, "max_moves", "must be > 0, got " << max_moves);
  SEWER3D_VALIDATE(noise >= 0.0 && noise <= 1.0, "noise", "must be 0..1, got " << noise);
  SEWER3D_VALIDATE(tabu_tenure >= 0, "tabu_tenure", "must not be negative, got " << tabu_tenure);
  SEWER3D_VALIDATE(progress_interval_moves > 0, "progress_interval_moves",
                   "must be > 0, got " << progress_interval_moves);
}

SubmapSearchResult SearchPerfectSubmap(const SubmapSearchOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::mt19937_64 rng(options.seed);
  SearchState state(options);
  SubmapSearchResult result;
  const auto out_of_time = [&] {
    return options.max_seconds > 0.0 && elapsed() > options.max_seconds;
  };
  if (!state.Initialise(rng, 0.6, out_of_time)) {
    result.array = BinaryArray(options.rows, options.cols);
    result.array.bits = state.cells_vector();
    result.final_cost = -1;
    result.termination = "time budget";
    result.elapsed_s = elapsed();
    return result;
  }

  std::vector<std::uint8_t> best_cells = state.cells_vector();
  int best_cost = state.cost();
  std::vector<std::int64_t> tabu_until(state.cells(), 0);
  std::bernoulli_distribution take_random(options.noise);
  std::vector<std::vector<Change>> candidates;
  std::vector<int> candidate_cell, deltas, best_indices;
  const bool isolated = options.constraints.isolated;

  std::int64_t move = 0;
  result.termination = "move budget";
  for (; move < options.max_moves; ++move) {
    if (state.cost() == 0) {
      result.termination = "reached";
      break;
    }
    if (out_of_time()) {
      result.termination = "time budget";
      break;
    }
    if (move % options.progress_interval_moves == 0 && move > 0) {
      if (options.progress &&
          !options.progress({move, state.cost(), best_cost, state.violated().size(), elapsed()})) {
        result.termination = "stopped";
        break;
      }
    }
    // Min-conflicts: repair one violated window by changing one of its elements.
    const int w = state.violated().Sample(rng);
    candidates.clear();
    candidate_cell.clear();
    for (int i = 0; i < state.n(); ++i) {
      for (int j = 0; j < state.n(); ++j) {
        const int c = state.window_cell(w, i, j);
        std::vector<Change> change{{c, static_cast<std::uint8_t>(state.cell(c) ^ 1)}};
        if (isolated && state.cell(c) == 0) {
          // Setting a spot clears its 8-neighbours, so isolation always holds.
          for (int o : state.neighbours(c)) {
            if (state.cell(o)) change.push_back({o, 0});
          }
        }
        candidates.push_back(std::move(change));
        candidate_cell.push_back(c);
      }
    }
    size_t chosen;
    if (take_random(rng)) {
      chosen = std::uniform_int_distribution<size_t>(0, candidates.size() - 1)(rng);
    } else {
      deltas.resize(candidates.size());
      int best_delta = std::numeric_limits<int>::max();
      best_indices.clear();
      for (size_t k = 0; k < candidates.size(); ++k) {
        deltas[k] = state.Delta(candidates[k]);
        const bool aspiration = state.cost() + deltas[k] < best_cost;
        if (tabu_until[candidate_cell[k]] > move && !aspiration) continue;
        if (deltas[k] < best_delta) {
          best_delta = deltas[k];
          best_indices.clear();
        }
        if (deltas[k] == best_delta) best_indices.push_back(static_cast<int>(k));
      }
      if (best_indices.empty()) continue;  // everything tabu: sample another window
      chosen = best_indices[std::uniform_int_distribution<size_t>(0, best_indices.size() - 1)(rng)];
    }
    state.Apply(candidates[chosen]);
    const int tenure = options.tabu_tenure;
    for (const Change& ch : candidates[chosen]) {
      tabu_until[ch.cell] =
          move + 1 + tenure + std::uniform_int_distribution<int>(0, std::max(tenure, 0))(rng);
    }
    if (state.cost() < best_cost) {
      best_cost = state.cost();
      best_cells = state.cells_vector();
    }
  }
  if (state.cost() < best_cost || state.cost() == 0) {
    best_cost = state.cost();
    best_cells = state.cells_vector();
  }
  result.array = BinaryArray(options.rows, options.cols);
  result.array.bits = best_cells;
  result.final_cost = best_cost;
  result.reached = best_cost == 0;
  result.moves = move;
  result.elapsed_s = elapsed();
  return result;
}

}  // namespace sewer3d
