#include "lib/calibration/charuco_target.h"

#include <climits>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>

#include "lib/calibration/albedo_json.h"
#include "lib/image/image_io.h"
#include "lib/util/json_fields.h"

namespace lutex {

namespace {

cv::Ptr<cv::aruco::Dictionary> Dictionary(const std::string& name) {
  static const std::pair<const char*, cv::aruco::PREDEFINED_DICTIONARY_NAME> kNames[] = {
      {"DICT_4X4_50", cv::aruco::DICT_4X4_50},     {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
      {"DICT_4X4_250", cv::aruco::DICT_4X4_250},   {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000},
      {"DICT_5X5_50", cv::aruco::DICT_5X5_50},     {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
      {"DICT_5X5_250", cv::aruco::DICT_5X5_250},   {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000},
      {"DICT_6X6_50", cv::aruco::DICT_6X6_50},     {"DICT_6X6_100", cv::aruco::DICT_6X6_100},
      {"DICT_6X6_250", cv::aruco::DICT_6X6_250},   {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000},
      {"DICT_7X7_50", cv::aruco::DICT_7X7_50},     {"DICT_7X7_100", cv::aruco::DICT_7X7_100},
      {"DICT_7X7_250", cv::aruco::DICT_7X7_250},   {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000},
      {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL}};
  for (const auto& [known, id] : kNames) {
    if (name == known) return cv::aruco::getPredefinedDictionary(id);
  }
  throw std::invalid_argument("unknown ArUco dictionary '" + name + "' (e.g. DICT_4X4_50)");
}

cv::Ptr<cv::aruco::CharucoBoard> Board(const CharucoSpec& spec) {
  return cv::aruco::CharucoBoard::create(spec.squares_x, spec.squares_y, static_cast<float>(spec.square_size),
                                         static_cast<float>(spec.marker_size), Dictionary(spec.dictionary));
}

}  // namespace

void CharucoSpec::Check() const {
  if (squares_x < 3 || squares_y < 3) throw std::invalid_argument("a ChArUco board needs at least 3 x 3 squares");
  if (!(square_size > 0.0) || !(marker_size > 0.0) || !(marker_size < square_size)) {
    throw std::invalid_argument("a ChArUco board needs 0 < marker_size < square_size");
  }
  const long long markers = static_cast<long long>(squares_x) * squares_y / 2;  // a corrupt size must not overflow
  if (Dictionary(dictionary)->bytesList.rows < markers) {
    throw std::invalid_argument(dictionary + " has fewer markers than the board's " + std::to_string(markers));
  }
  if (!(black_albedo.minCoeff() >= 0.0 && black_albedo.maxCoeff() <= 1.0)) {
    throw std::invalid_argument("black albedo must be in [0, 1]");
  }
  for (const ColourPatch& patch : patches) {
    if (!((patch.max_in_board - patch.min_in_board).minCoeff() > 0.0)) {
      throw std::invalid_argument("patch '" + patch.name + "' is empty (corners must be [x0, y0, x1, y1], x0 < x1, y0 < y1)");
    }
    if (!(patch.albedo.minCoeff() >= 0.0 && patch.albedo.maxCoeff() <= 1.0)) {
      throw std::invalid_argument("patch '" + patch.name + "' albedo must be in [0, 1]");
    }
  }
  if (!(inner_fraction > 0.0 && inner_fraction <= 1.0)) throw std::invalid_argument("inner_fraction must be in (0, 1]");
  if (min_corners < 4) throw std::invalid_argument("min_corners must be at least 4");
}

CharucoSpec ReadCharucoSpec(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path.string() + ": cannot read the ChArUco board file");
  CharucoSpec spec;
  try {
    const nlohmann::json json = nlohmann::json::parse(file);
    const nlohmann::json& board = json.at("charuco");
    const nlohmann::json& squares = board.at("squares");
    if (!squares.is_array() || squares.size() != 2) throw std::runtime_error("squares must be [across, down]");
    spec.squares_x = static_cast<int>(WholeNumber(squares[0], "squares", 0, INT_MAX));
    spec.squares_y = static_cast<int>(WholeNumber(squares[1], "squares", 0, INT_MAX));
    spec.square_size = board.at("square_size").get<double>();
    spec.marker_size = board.at("marker_size").get<double>();
    spec.dictionary = board.value("dictionary", spec.dictionary);
    spec.black_albedo = ReadAlbedo(board, "black_albedo");
    for (const nlohmann::json& entry : board.value("patches", nlohmann::json::array())) {
      ColourPatch patch;
      patch.name = entry.value("name", "patch " + std::to_string(spec.patches.size() + 1));
      const auto corners = entry.at("corners").get<std::vector<double>>();
      if (corners.size() != 4) throw std::runtime_error("patch '" + patch.name + "': corners must be [x0, y0, x1, y1]");
      patch.min_in_board = Eigen::Vector2d(corners[0], corners[1]);
      patch.max_in_board = Eigen::Vector2d(corners[2], corners[3]);
      patch.albedo = ReadAlbedo(entry, "albedo");
      spec.patches.push_back(patch);
    }
    spec.Check();
  } catch (const std::exception& error) {
    throw std::runtime_error(path.string() + ": " + JsonErrorText(error));
  }
  return spec;
}

CharucoLayout CharucoBoardLayout(const CharucoSpec& spec) {
  const cv::Ptr<cv::aruco::CharucoBoard> board = Board(spec);
  CharucoLayout layout;
  layout.black.assign(static_cast<std::size_t>(spec.squares_x * spec.squares_y), true);
  for (std::size_t m = 0; m < board->objPoints.size(); ++m) {
    std::array<Eigen::Vector2d, 4> corners;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int k = 0; k < 4; ++k) {
      const cv::Point3f& point = board->objPoints[m][static_cast<std::size_t>(k)];
      corners[static_cast<std::size_t>(k)] = Eigen::Vector2d(point.x, point.y);
      centre += 0.25 * corners[static_cast<std::size_t>(k)];
    }
    const int i = static_cast<int>(std::floor(centre.x() / spec.square_size));
    const int j = static_cast<int>(std::floor(centre.y() / spec.square_size));
    if (i >= 0 && j >= 0 && i < spec.squares_x && j < spec.squares_y) {
      layout.black[static_cast<std::size_t>(j * spec.squares_x + i)] = false;  // a marker's square is white
    }
    layout.marker_corners.push_back(corners);
    layout.marker_ids.push_back(board->ids[m]);
  }
  return layout;
}

std::vector<bool> CharucoMarkerBits(const CharucoSpec& spec, int id, int* cells_per_side) {
  const cv::Ptr<cv::aruco::Dictionary> dictionary = Dictionary(spec.dictionary);
  *cells_per_side = dictionary->markerSize + 2;
  cv::Mat image;
  dictionary->drawMarker(id, *cells_per_side, image, 1);
  std::vector<bool> bits;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) bits.push_back(image.at<std::uint8_t>(r, c) > 127);
  }
  return bits;
}

std::optional<BoardView> FindCharuco(const cv::Mat& linear_rgb, const Camera& camera, const CharucoSpec& spec) {
  spec.Check();
  cv::Mat grey;
  cv::cvtColor(EncodeLinearImage(linear_rgb, ImageEncoding::kSrgb8), grey, cv::COLOR_BGR2GRAY);
  const cv::Ptr<cv::aruco::CharucoBoard> board = Board(spec);
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(grey, board->dictionary, marker_corners, marker_ids);
  if (marker_ids.empty()) return std::nullopt;
  std::vector<cv::Point2f> corners;
  std::vector<int> corner_ids;
  cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, grey, board, corners, corner_ids);
  if (static_cast<int>(corner_ids.size()) < spec.min_corners) return std::nullopt;
  std::vector<Eigen::Vector3d> points_in_board;
  std::vector<Eigen::Vector2d> pixels;
  for (std::size_t k = 0; k < corner_ids.size(); ++k) {
    const cv::Point3f& point = board->chessboardCorners[static_cast<std::size_t>(corner_ids[k])];
    points_in_board.emplace_back(point.x, point.y, point.z);
    pixels.emplace_back(corners[k].x + 0.5, corners[k].y + 0.5);  // OpenCV's pixel centres are integers
  }
  return PoseFromBoardPoints(points_in_board, pixels, camera);
}

BoardMaps RenderCharuco(const CharucoSpec& spec, const BoardView& view, const CameraRays& rays) {
  const CharucoLayout layout = CharucoBoardLayout(spec);
  const double s = spec.square_size;
  Eigen::Vector2d min_in_board(0.0, 0.0), max_in_board(spec.squares_x * s, spec.squares_y * s);
  for (const ColourPatch& patch : spec.patches) {
    min_in_board = min_in_board.cwiseMin(patch.min_in_board);
    max_in_board = max_in_board.cwiseMax(patch.max_in_board);
  }
  BoardPlaneMaps plane = RenderBoardPlane(view, rays, min_in_board, max_in_board);
  BoardMaps result;
  result.maps = std::move(plane.maps);
  result.known_albedo =
      cv::Mat(rays.height(), rays.width(), CV_32FC3, cv::Scalar::all(std::numeric_limits<float>::quiet_NaN()));
  const double margin = 0.5 * (1.0 - spec.inner_fraction);
  const auto inside = [margin](const Eigen::Vector2d& point, const Eigen::Vector2d& low, const Eigen::Vector2d& high) {
    const Eigen::Vector2d border = margin * (high - low);
    return (point - low - border).minCoeff() >= 0.0 && (high - border - point).minCoeff() >= 0.0;
  };
  for (int row = 0; row < rays.height(); ++row) {
    for (int col = 0; col < rays.width(); ++col) {
      const cv::Vec2f hit = plane.point_in_board.at<cv::Vec2f>(row, col);
      if (std::isnan(hit[0])) continue;
      const Eigen::Vector2d point(hit[0], hit[1]);
      const Eigen::Vector3d* albedo = nullptr;
      for (const ColourPatch& patch : spec.patches) {
        if (inside(point, patch.min_in_board, patch.max_in_board)) albedo = &patch.albedo;
      }
      const int i = static_cast<int>(std::floor(point.x() / s)), j = static_cast<int>(std::floor(point.y() / s));
      if (!albedo && i >= 0 && j >= 0 && i < spec.squares_x && j < spec.squares_y &&
          layout.black[static_cast<std::size_t>(j * spec.squares_x + i)] &&
          inside(point, Eigen::Vector2d(i * s, j * s), Eigen::Vector2d((i + 1) * s, (j + 1) * s))) {
        albedo = &spec.black_albedo;
      }
      if (albedo) {
        result.known_albedo.at<cv::Vec3f>(row, col) =
            cv::Vec3f(float(albedo->x()), float(albedo->y()), float(albedo->z()));
      }
    }
  }
  return result;
}

}  // namespace lutex
