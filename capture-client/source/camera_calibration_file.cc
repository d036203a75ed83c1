#include "capture-client/source/camera_calibration_file.h"

#include <charconv>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/io/text_file.h"

namespace reenact::capture {
namespace {

// A key of the wrong type or out of range; caught at the reader's boundary.
class KeyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string Number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void Fail(const std::string& key, const std::string& what) {
  std::string message = key;
  message += ' ';
  message += what;
  throw KeyError(message);
}

bool IsNumber(const cv::FileNode& n) { return n.isInt() || n.isReal(); }

double NumberOf(const cv::FileNode& n, const std::string& key) {
  if (!IsNumber(n)) Fail(key, "must be a number");
  const double v = n.isInt() ? static_cast<double>(static_cast<int>(n)) : static_cast<double>(n);
  if (!std::isfinite(v)) Fail(key, "must be a finite number");
  return v;
}

int PositiveInt(const cv::FileNode& n, const std::string& key) {
  if (!n.isInt() || static_cast<int>(n) <= 0) Fail(key, "must be an integer > 0");
  return static_cast<int>(n);
}

std::optional<double> OptionalNumber(const cv::FileNode& root, const std::string& key) {
  const cv::FileNode n = root[key];
  if (n.empty()) return std::nullopt;
  return NumberOf(n, key);
}

// The numbers of an !!opencv-matrix (rows, cols, data) or of a plain list; rows and cols of a
// list are (1, size).
std::vector<double> MatrixValues(const cv::FileNode& n, const std::string& key, int* rows,
                                 int* cols) {
  cv::FileNode data = n;
  if (n.isMap()) {
    *rows = PositiveInt(n["rows"], key + ".rows");
    *cols = PositiveInt(n["cols"], key + ".cols");
    data = n["data"];
    if (!data.isSeq()) Fail(key + ".data", "must be a list of numbers");
    if (static_cast<int64_t>(data.size()) != static_cast<int64_t>(*rows) * *cols)
      Fail(key + ".data", "holds " + std::to_string(data.size()) + " numbers, not rows x cols = " +
                              std::to_string(static_cast<int64_t>(*rows) * *cols));
  } else if (n.isSeq()) {
    *rows = 1;
    *cols = static_cast<int>(n.size());
  } else {
    Fail(key, "must be an !!opencv-matrix (rows, cols, data) or a list of numbers");
  }
  std::vector<double> values;
  for (size_t i = 0; i < data.size(); ++i) {
    std::string element = key;
    element += ".data[";
    element += std::to_string(i);
    element += ']';
    values.push_back(NumberOf(data[static_cast<int>(i)], element));
  }
  return values;
}

void ReadCameraMatrix(const cv::FileNode& node, PinholeCamera* camera) {
  int rows = 0, cols = 0;
  const std::vector<double> k = MatrixValues(node, "camera_matrix", &rows, &cols);
  if (!(rows == 3 && cols == 3) && !(rows == 1 && cols == 9))
    Fail("camera_matrix",
         "must be 3x3 (9 numbers), not " + std::to_string(rows) + "x" + std::to_string(cols));
  if (k[1] != 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1)
    Fail("camera_matrix", "must be [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  camera->fx = k[0];
  camera->cx = k[2];
  camera->fy = k[4];
  camera->cy = k[5];
}

void ReadDistortion(const cv::FileNode& node, PinholeCamera* camera) {
  int rows = 0, cols = 0;
  const std::vector<double> d = MatrixValues(node, "distortion_coefficients", &rows, &cols);
  if (rows != 1 && cols != 1)
    Fail("distortion_coefficients", "must be one row or column of numbers");
  if (d.size() != 4 && d.size() != 5 && d.size() != 8)
    Fail("distortion_coefficients",
         "must hold 4, 5 or 8 values (k1 k2 p1 p2 [k3 [k4 k5 k6]]), not " +
             std::to_string(d.size()));
  for (size_t i = 5; i < d.size(); ++i)
    if (d[i] != 0)
      throw std::domain_error(
          "the rational distortion terms k4-k6 are not supported; calibrate with the "
          "5-coefficient model");
  camera->distortion.k1 = d[0];
  camera->distortion.k2 = d[1];
  camera->distortion.p1 = d[2];
  camera->distortion.p2 = d[3];
  if (d.size() >= 5) camera->distortion.k3 = d[4];
}

void ReadSize(const cv::FileNode& root, PinholeCamera* camera) {
  if (!root["image_width"].empty() && !root["width"].empty())
    Fail("image_width", "and width both give the image size; keep one");
  for (const auto& [w, h] :
       {std::pair<std::string, std::string>{"image_width", "image_height"}, {"width", "height"}}) {
    const cv::FileNode wn = root[w], hn = root[h];
    if (wn.empty() && hn.empty()) continue;
    if (wn.empty() || hn.empty()) Fail(wn.empty() ? w : h, "is missing (give both or neither)");
    camera->width = PositiveInt(wn, w);
    camera->height = PositiveInt(hn, h);
  }
}

CameraCalibrationFile ReadFields(const cv::FileNode& root) {
  CameraCalibrationFile out;
  PinholeCamera& camera = out.camera;
  ReadSize(root, &camera);
  const cv::FileNode matrix = root["camera_matrix"];
  const bool has_fx = !root["fx"].empty();
  if (!matrix.empty() && has_fx) Fail("camera_matrix", "and fx both give the intrinsics; keep one");
  if (!matrix.empty()) {
    ReadCameraMatrix(matrix, &camera);
  } else {
    for (const char* key : {"fx", "fy", "cx", "cy"})
      if (root[key].empty())
        Fail(key,
             "is missing: the file needs camera_matrix (OpenCV) or fx, fy, cx and cy (pixels)");
    camera.fx = NumberOf(root["fx"], "fx");
    camera.fy = NumberOf(root["fy"], "fy");
    camera.cx = NumberOf(root["cx"], "cx");
    camera.cy = NumberOf(root["cy"], "cy");
  }
  if (!(camera.fx > 0)) Fail("fx", "= " + Number(camera.fx) + " must be > 0 (pixels)");
  if (!(camera.fy > 0)) Fail("fy", "= " + Number(camera.fy) + " must be > 0 (pixels)");
  if (const cv::FileNode d = root["distortion_coefficients"]; !d.empty())
    ReadDistortion(d, &camera);

  out.depth_unit_m = OptionalNumber(root, "depth_unit_m");
  if (out.depth_unit_m && !(*out.depth_unit_m > 0 && *out.depth_unit_m <= 1))
    Fail("depth_unit_m", "= " + Number(*out.depth_unit_m) + " must be in (0, 1] (metres per unit)");
  out.fps = OptionalNumber(root, "fps");
  if (out.fps && !(*out.fps > 0)) Fail("fps", "= " + Number(*out.fps) + " must be > 0");
  if (const cv::FileNode n = root["frames"]; !n.empty()) out.frames = PositiveInt(n, "frames");
  if (const cv::FileNode n = root["mirrored"]; !n.empty()) {
    if (n.isInt() && (static_cast<int>(n) == 0 || static_cast<int>(n) == 1))
      out.mirrored = static_cast<int>(n) == 1;
    else if (n.isString() &&
             (static_cast<std::string>(n) == "true" || static_cast<std::string>(n) == "false"))
      out.mirrored = static_cast<std::string>(n) == "true";
    else
      Fail("mirrored", "must be 0 or 1 (true or false)");
  }
  return out;
}

// cv::FileStorage reads YAML only after a "%YAML" line; hand-written files often lack it.
std::string WithYamlHeader(std::string text) {
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return text;
  if (text[first] == '{' || text[first] == '<' || text.compare(first, 5, "%YAML") == 0) return text;
  return "%YAML:1.0\n" + text;
}

}  // namespace

Expected<CameraCalibrationFile> ReadCameraCalibrationFile(const std::filesystem::path& path) {
  const auto text = ReadTextFile(path, "calibration file");
  if (!text.ok()) return text.error();
  const std::string name = "calibration " + path.string() + ": ";
  if (text->find_first_not_of(" \t\r\n") == std::string::npos)
    return MakeError("corrupt", name +
                                    "the file is empty; expected camera_matrix (OpenCV) or "
                                    "fx, fy, cx, cy");
  cv::FileStorage storage;
  try {
    storage.open(WithYamlHeader(*text), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    return MakeError("corrupt", name + "not a readable YAML or JSON file (" + e.err + ")");
  }
  if (!storage.isOpened() || !storage.root().isMap())
    return MakeError("corrupt", name + "not a YAML or JSON map of keys");
  try {
    return ReadFields(storage.root());
  } catch (const KeyError& e) {
    return MakeError("corrupt", name + e.what());
  } catch (const std::domain_error& e) {
    return MakeError("unsupported", name + e.what());
  } catch (const cv::Exception& e) {
    return MakeError("corrupt", name + "unreadable key (" + e.err + ")");
  }
}

}  // namespace reenact::capture
