#include "capture-client/slam/rolling_shutter.h"

#include <Eigen/Geometry>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::capture::slam {

void CompensateRollingShutter(const Eigen::Matrix3d& rotation_per_frame, double readout_ratio,
                              int image_height, FrameFeatures& features) {
  REENACT_CHECK(readout_ratio >= 0 && readout_ratio <= 1, "readout_ratio must be in [0, 1]");
  REENACT_CHECK(image_height > 0, "image_height must be > 0");
  if (readout_ratio == 0) return;
  const Eigen::AngleAxisd aa(rotation_per_frame);
  const Eigen::Vector3d omega = aa.angle() * aa.axis();  // rotation vector per frame
  if (!omega.allFinite() || omega.norm() == 0) return;
  const double centre = 0.5 * (image_height - 1);
  for (size_t i = 0; i < features.size(); ++i) {
    const double a = (features.keypoints[i].pt.y - centre) / image_height * readout_ratio;
    const Eigen::Matrix3d mid_from_row = ExpSo3(a * omega).transpose();
    KeypointObservation& o = features.observations[i];
    const Eigen::Vector3d b = mid_from_row * Eigen::Vector3d(o.normalized.x(), o.normalized.y(), 1);
    if (!(b.z() > 1e-6)) continue;
    o.normalized = b.head<2>() / b.z();
    if (o.depth_m > 0) {
      features.points_in_camera[i] = mid_from_row * features.points_in_camera[i];
      o.depth_m = features.points_in_camera[i].z();
    }
  }
}

}  // namespace reenact::capture::slam
