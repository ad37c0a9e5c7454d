#include "sewer3d/decode/decoder.hpp"

#include <chrono>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

std::vector<CodedObservation> CodedObservations(const DecodeResult& decoded) {
  std::vector<CodedObservation> observations;
  observations.reserve(decoded.codes.size());
  for (const SpotCode& c : decoded.codes)
    observations.push_back({decoded.spots[c.spot].centre_px, c.row, c.col});
  return observations;
}

Decoder::Decoder(const ModuleDescription& module, const BinaryArray& pattern,
                 const PatternConstraints& constraints, const DecoderOptions& options)
    : module_(module),
      pattern_(pattern),
      codebook_(pattern, constraints),
      options_(options),
      binariser_(options.niblack) {
  module_.Check();
  const CameraModel camera(module.camera), projector(module.projector);
  const Rigid3d camera_from_projector = module.projector_from_camera.Inverse();
  const double z = options.prediction_depth_mm, pitch = module.pattern.pitch_px;
  grid_cols_ = module.camera.width / grid_step_ + 1;
  grid_rows_ = module.camera.height / grid_step_ + 1;
  predicted_.resize(static_cast<size_t>(grid_cols_) * grid_rows_);
  // Camera position of projector pixel uv on the plane Z = z (camera frame).
  auto camera_of = [&](const Eigen::Vector2d& uv) -> std::optional<Eigen::Vector2d> {
    const auto ray = projector.Ray(uv);
    if (!ray) return std::nullopt;
    const Eigen::Vector3d origin = camera_from_projector.translation;
    const Eigen::Vector3d direction = camera_from_projector.rotation * *ray;
    if (std::abs(direction.z()) < 1e-12) return std::nullopt;
    return camera.Project(origin + direction * ((z - origin.z()) / direction.z()));
  };
  for (int gy = 0; gy < grid_rows_; ++gy) {
    for (int gx = 0; gx < grid_cols_; ++gx) {
      LatticeSteps steps{{0.0, pitch}, {-pitch, 0.0}};  // fallback: the default module's layout
      const auto xy = camera.Unproject({double(gx * grid_step_), double(gy * grid_step_)});
      if (xy) {
        const auto uv = projector.Project(module.projector_from_camera *
                                          (Eigen::Vector3d(xy->x(), xy->y(), 1.0) * z));
        if (uv) {
          const auto p = camera_of(*uv), pc = camera_of(*uv + Eigen::Vector2d(pitch, 0)),
                     pr = camera_of(*uv + Eigen::Vector2d(0, pitch));
          if (p && pc && pr) steps = {*pc - *p, *pr - *p};
        }
      }
      predicted_[static_cast<size_t>(gy) * grid_cols_ + gx] = steps;
    }
  }
}

LatticeSteps Decoder::PredictSteps(const Eigen::Vector2d& pixel) const {
  const int gx =
      std::clamp(static_cast<int>(std::lround(pixel.x() / grid_step_)), 0, grid_cols_ - 1);
  const int gy =
      std::clamp(static_cast<int>(std::lround(pixel.y() / grid_step_)), 0, grid_rows_ - 1);
  return predicted_[static_cast<size_t>(gy) * grid_cols_ + gx];
}

DecodeResult Decoder::Decode(const cv::Mat& image) {
  SEWER3D_VALIDATE(image.cols == module_.camera.width && image.rows == module_.camera.height,
                   "image",
                   "is " << image.cols << "x" << image.rows << " but the module's camera is "
                         << module_.camera.width << "x" << module_.camera.height);
  DecodeResult result;
  auto t = Clock::now();
  binariser_.Apply(image, mask_);
  result.seconds_binarise = Since(t);
  t = Clock::now();
  result.spots = DetectSpots(mask_, binariser_.excess(), options_.spots, &spot_workspace_);
  result.seconds_spots = Since(t);
  t = Clock::now();
  result.lattice = LabelLattice(result.spots, options_.lattice,
                                [this](const Eigen::Vector2d& p) { return PredictSteps(p); });
  result.seconds_lattice = Since(t);
  t = Clock::now();
  result.codes = DecodeCodewords(result.spots, result.lattice, codebook_, pattern_.rows,
                                 pattern_.cols, image.size(), options_.codewords, &result.stats);
  result.seconds_codewords = Since(t);
  return result;
}

}  // namespace sewer3d
