#pragma once
/// \file
/// The files of the registration stage (DESIGN.md contract "processing workspace";
/// docs/registration.md): WS/registration/poses.csv, edges.csv, graph.g2o (g2o_io.hpp),
/// report.json, graph.png, and the per-pair cache pairs/m<a>_<counter>-m<b>_<counter>.json that
/// lets an interrupted stage resume. Also the reading of an acquisition's colour and depth
/// from WS/rgbd. Every write is atomic; errors are FileError naming the file.

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

/// A row of poses.csv: module,counter,time_s,x_mm,y_mm,z_mm,qx,qy,qz,qw, world_from_camera at
/// the pattern image's time, model frame.
struct RegistrationPoseRow {
  int module = 0;
  int counter = 0;
  double time_s = 0.0;
  Rigid3d world_from_camera;
};
void WriteRegistrationPoses(const std::filesystem::path& path,
                            const std::vector<RegistrationPoseRow>& rows);
std::vector<RegistrationPoseRow> ReadRegistrationPoses(const std::filesystem::path& path);

/// The vertex id of an acquisition in graph.g2o and edges.csv: module · 10⁶ + counter.
int RegistrationVertexId(int module, int counter);

/// A row of edges.csv: from,to (vertex ids),from_module,from_counter,to_module,to_counter,type,
/// inliers,rms_mm,eig0..eig5 (information eigenvalues, 1/mm², rotation as arc at the stage's
/// length scale, ascending),chi2 (rᵀΩr at the final poses),accepted (0/1). graph.g2o holds the
/// accepted edges in the order of their rows.
struct RegistrationEdgeRow {
  int from_module = 0, from_counter = 0, to_module = 0, to_counter = 0;
  std::string type;
  int inliers = 0;
  double rms_mm = 0.0;
  Eigen::Matrix<double, 6, 1> eigenvalues = Eigen::Matrix<double, 6, 1>::Zero();
  double chi2 = 0.0;
  bool accepted = false;
};
void WriteRegistrationEdges(const std::filesystem::path& path,
                            const std::vector<RegistrationEdgeRow>& rows);
std::vector<RegistrationEdgeRow> ReadRegistrationEdges(const std::filesystem::path& path);

/// The cached result of one pairwise registration.
struct PairRecord {
  int a_module = 0, a_counter = 0, b_module = 0, b_counter = 0;
  std::string kind;    ///< "along" or "around"
  std::string method;  ///< "feature", "projection", or "none" (both failed)
  Rigid3d a_from_b;    ///< valid unless method is "none"
  Matrix6d information = Matrix6d::Zero();
  int inliers = 0;
  double rms_mm = 0.0;
  double seconds = 0.0;
  bool degenerate = false;   ///< projection: the information's spectrum is degenerate
  bool photometric = false;  ///< projection: the texture term was used (photometric.hpp)
  std::string message;       ///< why the feature registration (or both) failed
};
/// `pairs_folder`/m<a>_<counter 6 digits>-m<b>_<counter 6 digits>.json.
std::filesystem::path PairRecordFile(const std::filesystem::path& pairs_folder, int a_module,
                                     int a_counter, int b_module, int b_counter);
void WritePairRecord(const std::filesystem::path& path, const PairRecord& record);
/// nullopt when the file does not exist; FileError when it is malformed.
std::optional<PairRecord> ReadPairRecord(const std::filesystem::path& path);

/// An acquisition's corrected texture (BGR) and depth map (mm, NaN = none) from WS/rgbd; FileError
/// when either is missing, unreadable, of the wrong type or the sizes differ.
struct RgbdPairInput {
  cv::Mat3b color_bgr;
  cv::Mat1f depth_mm;
};
RgbdPairInput ReadRgbdForRegistration(const std::filesystem::path& rgbd_folder, int module,
                                      int counter);

/// The depth map alone (mm, NaN = none); FileError when it is missing, unreadable or not
/// float32.
cv::Mat1f ReadRgbdDepth(const std::filesystem::path& rgbd_folder, int module, int counter);

/// The picture of the graph over the unrolled pipe (paper's figure): x = station (mm), y = clock
/// of each camera (0–12 h, crown at the top); edges as lines coloured by type (feature green,
/// projection blue, rig orange, odometry grey, straightness magenta; rejected ones thin red),
/// nodes as dots; a legend. Written as PNG.
struct GraphPictureNode {
  double station_mm = 0.0;
  double clock_h = 0.0;
};
struct GraphPictureEdge {
  int a = 0, b = 0;  ///< node indices
  int type = 0;      ///< 0 feature, 1 projection, 2 rig, 3 odometry, 4 straightness
  bool accepted = true;
};
void WriteRegistrationGraphPicture(const std::filesystem::path& path,
                                   const std::vector<GraphPictureNode>& nodes,
                                   const std::vector<GraphPictureEdge>& edges);

}  // namespace sewer3d
