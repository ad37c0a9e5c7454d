#include "sewer3d/pipeline/register_pairs.hpp"

#include <fmt/format.h>

#include <chrono>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/pipeline/parallel_items.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;

// What the texture term's search found, for the pair record's message.
std::string TextureMessage(const ProjectionRegistrationReport& t) {
  const char* use = t.photometric        ? ""
                    : t.texture_diverged ? ", not used (did not converge with it)"
                                         : ", not used";
  return fmt::format(
      "; texture: {} samples overlap, correlation {:.2f} at the guess, {:.2f} at the peak "
      "({:.2f}{} elsewhere), moved {:.2f} mm{}",
      t.texture_overlap, t.ncc_start, t.ncc_peak, t.ncc_other,
      t.texture_ridge ? " off the ridge" : "", t.search_shift_mm.norm(), use);
}

PairRecord Register(const AcquisitionNode& a, const AcquisitionNode& b, const Rig& rig,
                    const std::filesystem::path& rgbd_folder,
                    const PairRegistrationOptions& options) {
  const auto start = Clock::now();
  const RgbdPairInput in_a = ReadRgbdForRegistration(rgbd_folder, a.module, a.counter);
  const RgbdPairInput in_b = ReadRgbdForRegistration(rgbd_folder, b.module, b.counter);
  const CameraModel camera_a(rig.modules[a.module].module.camera);
  const CameraModel camera_b(rig.modules[b.module].module.camera);
  PairRecord r;
  r.method = "none";
  FeatureRegistrationResult f;
  if (options.feature_registration)
    f = RegisterFeatures({in_a.color_bgr, in_a.depth_mm}, camera_a, {in_b.color_bgr, in_b.depth_mm},
                         camera_b, options.features);
  if (f.converged) {
    r.method = "feature";
    r.a_from_b = f.a_from_b;
    r.information = f.information;
    r.inliers = f.inliers;
    r.rms_mm = f.rms_mm;
  } else {
    r.message = "features: " + std::to_string(f.report.matches) + " matches, " +
                std::to_string(f.report.with_depth) + " with depth, " +
                std::to_string(f.report.inliers) + " inliers";
    if (options.projection_fallback) {
      const Rigid3d guess = a.world_from_camera.Inverse() * b.world_from_camera;
      const ProjectionRegistrationResult p = RegisterProjection(
          RgbdImage{in_a.color_bgr, in_a.depth_mm}, camera_a,
          RgbdImage{in_b.color_bgr, in_b.depth_mm}, camera_b, guess, options.projection);
      if (p.converged) {
        r.method = "projection";
        r.a_from_b = p.a_from_b;
        r.information = p.information;
        r.inliers = p.correspondences;
        r.rms_mm = p.rms_mm;
        r.degenerate = p.degenerate;
        r.photometric = p.report.photometric;
        r.message += TextureMessage(p.report);
      } else {
        r.message += "; projection: " + std::to_string(p.correspondences) +
                     " correspondences, did not converge in " +
                     std::to_string(p.report.iterations) + " iterations";
      }
    }
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

}  // namespace

PairRegistrationOutcome RegisterPairs(const std::vector<AcquisitionNode>& nodes,
                                      const std::vector<NeighbourPair>& pairs, const Rig& rig,
                                      const std::filesystem::path& rgbd_folder,
                                      const std::filesystem::path& pairs_folder,
                                      const PairRegistrationOptions& options, int threads,
                                      const std::function<void(int)>& done) {
  PairRegistrationOutcome outcome;
  outcome.records.resize(pairs.size());
  std::vector<char> from_cache(pairs.size(), 0);
  ForEachItem<int>(
      pairs.size(), threads, [] { return 0; },
      [&](size_t i, int&) {
        const AcquisitionNode& a = nodes[pairs[i].a];
        const AcquisitionNode& b = nodes[pairs[i].b];
        const std::filesystem::path file =
            PairRecordFile(pairs_folder, a.module, a.counter, b.module, b.counter);
        if (std::optional<PairRecord> cached = ReadPairRecord(file)) {
          outcome.records[i] = *cached;
          from_cache[i] = 1;
          return;
        }
        PairRecord r = Register(a, b, rig, rgbd_folder, options);
        r.a_module = a.module;
        r.a_counter = a.counter;
        r.b_module = b.module;
        r.b_counter = b.counter;
        r.kind = PairKindName(pairs[i].kind);
        WritePairRecord(file, r);
        outcome.records[i] = std::move(r);
      },
      done);
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (from_cache[i]) {
      ++outcome.skipped;
    } else {
      ++outcome.done;
      outcome.seconds_now += outcome.records[i].seconds;
    }
  }
  return outcome;
}

std::optional<RegistrationEdge> PairEdge(const PairRecord& record, const NeighbourPair& pair,
                                         const PairRegistrationOptions& options) {
  if (record.method == "none") return std::nullopt;
  RegistrationEdge e;
  e.a = pair.a;
  e.b = pair.b;
  e.type = record.method == "feature" ? RegistrationEdgeType::kFeature
                                      : RegistrationEdgeType::kProjection;
  e.a_from_b = record.a_from_b;
  e.information = 0.5 * (record.information + record.information.transpose());
  if (record.a_module != record.b_module)
    e.information = WithCovarianceFloor(e.information, options.between_modules_floor_mm,
                                        options.between_modules_floor_deg);
  if (!IsSymmetricPositiveDefinite(e.information)) {
    Vector6d floor;
    floor << 1e-6, 1e-6, 1e-6, 1e-2, 1e-2, 1e-2;
    e.information += Matrix6d(floor.asDiagonal());
  }
  e.inliers = record.inliers;
  e.rms_mm = record.rms_mm;
  return e;
}

}  // namespace sewer3d
