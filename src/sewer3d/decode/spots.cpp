#include "sewer3d/decode/spots.hpp"

#include <algorithm>
#include <climits>
#include <cstring>

#include "sewer3d/core/check.hpp"
#include "sewer3d/decode/niblack.hpp"

namespace sewer3d {

void SpotOptions::Check() const {
  SEWER3D_VALIDATE(min_area_px >= 1, "min_area_px", "must be >= 1, got " << min_area_px);
  SEWER3D_VALIDATE(max_area_px >= min_area_px, "max_area_px",
                   "must be >= min_area_px (" << min_area_px << "), got " << max_area_px);
  SEWER3D_VALIDATE(max_aspect >= 1.0, "max_aspect", "must be >= 1, got " << max_aspect);
}

namespace {

int Find(std::vector<SpotWorkspace::Run>& runs, int i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;  // path halving
    i = runs[i].parent;
  }
  return i;
}

// Runs of non-zero mask pixels, row by row; zero bytes skipped eight at a time.
void FindRuns(const cv::Mat1b& mask, SpotWorkspace& ws) {
  ws.runs.clear();
  ws.row_start.assign(mask.rows + 1, 0);
  for (int v = 0; v < mask.rows; ++v) {
    ws.row_start[v] = static_cast<int>(ws.runs.size());
    const std::uint8_t* row = mask[v];
    int u = 0;
    while (u < mask.cols) {
      while (u + 8 <= mask.cols) {
        std::uint64_t word;
        std::memcpy(&word, row + u, 8);
        if (word != 0) break;
        u += 8;
      }
      while (u < mask.cols && row[u] == 0) ++u;
      if (u >= mask.cols) break;
      const int start = u;
      while (u < mask.cols && row[u] != 0) ++u;
      const int index = static_cast<int>(ws.runs.size());
      ws.runs.push_back({v, start, u - 1, index});
    }
  }
  ws.row_start[mask.rows] = static_cast<int>(ws.runs.size());
}

// Joins runs of consecutive rows that touch (8-connectivity: columns overlap within one).
void JoinRuns(SpotWorkspace& ws, int rows) {
  for (int v = 1; v < rows; ++v) {
    int p = ws.row_start[v - 1];
    const int p_end = ws.row_start[v];
    for (int i = ws.row_start[v]; i < ws.row_start[v + 1]; ++i) {
      const SpotWorkspace::Run& run = ws.runs[i];
      while (p < p_end && ws.runs[p].u1 < run.u0 - 1) ++p;
      for (int q = p; q < p_end && ws.runs[q].u0 <= run.u1 + 1; ++q) {
        const int a = Find(ws.runs, i), b = Find(ws.runs, q);
        if (a != b) ws.runs[std::max(a, b)].parent = std::min(a, b);
      }
    }
  }
}

// Weighted centroid over the box; pixels of the mask that are not this component's runs
// (a neighbouring spot) are skipped. `own` lists the component's runs in row order.
bool Centroid(const cv::Mat1b& mask, const cv::Mat1w& excess, const SpotWorkspace& ws,
              const int* own, int own_count, int u0, int v0, int u1, int v1, Spot& spot) {
  double sum = 0.0, su = 0.0, sv = 0.0;
  int peak = 0, k = 0;
  for (int v = v0; v <= v1; ++v) {
    const std::uint8_t* mask_row = mask[v];
    const std::uint16_t* weight_row = excess[v];
    while (k < own_count && ws.runs[own[k]].v < v) ++k;
    double row_sum = 0.0, row_su = 0.0;
    for (int u = u0; u <= u1; ++u) {
      if (mask_row[u] != 0) {
        bool mine = false;
        for (int j = k; j < own_count && ws.runs[own[j]].v == v && !mine; ++j) {
          mine = u >= ws.runs[own[j]].u0 && u <= ws.runs[own[j]].u1;
        }
        if (!mine) continue;
      }
      const int weight = weight_row[u];
      row_sum += weight;
      row_su += static_cast<double>(weight) * u;
      peak = std::max(peak, weight);
    }
    sum += row_sum;
    su += row_su;
    sv += row_sum * v;
  }
  if (sum <= 0.0) return false;
  spot.centre_px = {su / sum, sv / sum};
  spot.contrast = peak / NiblackBinariser::kExcessScale;
  return true;
}

}  // namespace

std::vector<Spot> DetectSpots(const cv::Mat1b& mask, const cv::Mat1w& excess,
                              const SpotOptions& options, SpotWorkspace* workspace) {
  options.Check();
  SEWER3D_CHECK(mask.size() == excess.size(), "sizes differ");
  SpotWorkspace local;
  SpotWorkspace& ws = workspace ? *workspace : local;
  FindRuns(mask, ws);
  JoinRuns(ws, mask.rows);
  // Group runs by component (roots in order of first appearance: raster order of the
  // component's first run, as a label image would number them).
  const int run_count = static_cast<int>(ws.runs.size());
  ws.component.assign(run_count, -1);
  std::vector<int> first_run;  // per component: its root run
  for (int i = 0; i < run_count; ++i) {
    const int root = Find(ws.runs, i);
    if (ws.component[root] < 0) {
      ws.component[root] = static_cast<int>(first_run.size());
      first_run.push_back(root);
    }
    ws.component[i] = ws.component[root];
  }
  const int count = static_cast<int>(first_run.size());
  std::vector<int> start(count + 1, 0);
  for (int i = 0; i < run_count; ++i) ++start[ws.component[i] + 1];
  for (int c = 0; c < count; ++c) start[c + 1] += start[c];
  ws.members.resize(run_count);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int i = 0; i < run_count; ++i) ws.members[fill[ws.component[i]]++] = i;  // row order kept
  std::vector<Spot> spots;
  spots.reserve(count);
  for (int c = 0; c < count; ++c) {
    const int* own = ws.members.data() + start[c];
    const int own_count = start[c + 1] - start[c];
    int area = 0, left = INT_MAX, right = INT_MIN;
    for (int j = 0; j < own_count; ++j) {
      const SpotWorkspace::Run& run = ws.runs[own[j]];
      area += run.u1 - run.u0 + 1;
      left = std::min(left, run.u0);
      right = std::max(right, run.u1);
    }
    const int top = ws.runs[own[0]].v, bottom = ws.runs[own[own_count - 1]].v;
    const int w = right - left + 1, h = bottom - top + 1;
    if (area < options.min_area_px || area > options.max_area_px) continue;
    if (std::max(w, h) > options.max_aspect * std::min(w, h)) continue;
    const int u0 = std::max(0, left - 1), v0 = std::max(0, top - 1);
    const int u1 = std::min(mask.cols - 1, u0 + w + 1), v1 = std::min(mask.rows - 1, v0 + h + 1);
    Spot spot;
    spot.area_px = area;
    if (Centroid(mask, excess, ws, own, own_count, u0, v0, u1, v1, spot)) spots.push_back(spot);
  }
  return spots;
}

}  // namespace sewer3d
