#pragma once
// Rolling-shutter compensation of keypoints. A rolling-shutter colour camera (Kinect v1,
// Xtion and most webcams) exposes its rows one after another: row v is read at
//   t(v) = t_mid + (v - (H - 1) / 2) / H * readout_ratio * frame_interval,
// readout_ratio = readout time / frame interval, in [0, 1] (0 = global shutter). While the
// sensor turns, rows see the scene from different orientations, which a single-pose model
// cannot explain (straight lines bend, the image shears; a few pixels at 100 degrees/s).
//
// With the sensor's rotation over one frame interval, R = sensor_now_from_sensor_before (the
// constant-velocity prediction), the sensor at row v is turned by
//   dR(v) = Exp(a(v) log R),  a(v) = (v - (H - 1) / 2) / H * readout_ratio
// relative to the mid-frame sensor, so a keypoint's bearing b(v) in its row's frame is
// b = dR(v)^T b(v) in the mid-frame sensor's frame: every keypoint is moved to where a
// global-shutter camera at t_mid would have seen it (exact for rotation; the translation
// during the readout, millimetres for a hand-held sensor, is neglected). Its 3D point from
// depth is rotated alike.

#include <Eigen/Core>

#include "capture-client/slam/vision_names.h"

namespace reenact::capture::slam {

// Readout ratio of the Kinect v1 colour camera (TUM RGB-D's sensor; Xtion-class sensors are
// alike), calibrated on TUM fr1_rpy's first 60 frames against the motion-capture ground
// truth: the trajectory error of forward runs from frames 0, 10, ..., 40 is lowest for
// ratios 0.5-0.7 and rises on both sides (and compensating with the opposite sign makes it
// clearly worse), i.e. about 18 ms of a 33 ms frame interval.
inline constexpr double kKinectV1ReadoutRatio = 0.55;

// Corrects features in place. rotation_per_frame: sensor_now_from_sensor_before over one
// frame interval; image_height: rows (> 0). Preconditions (CHECK): readout_ratio in [0, 1].
void CompensateRollingShutter(const Eigen::Matrix3d& rotation_per_frame, double readout_ratio,
                              int image_height, FrameFeatures& features);

}  // namespace reenact::capture::slam
