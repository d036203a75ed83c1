#pragma once
// Kinect v1 (Kinect for Windows SDK 1.x / NiTE-era) 20-joint skeleton tracks in the text
// layouts of the public action data sets, read into a SkeletonTrack (16 joints, sensor
// frame).
//
// Layouts (detected from the count of numbers on the first data line, or forced by the
// variant):
// - UTKinect-Action3D, joints_sXX_eYY.txt: one line per frame, "n x1 y1 z1 ... x20 y20 z20"
//   (61 numbers): n = the frame's image number (integer >= 0, colorImg<n>.jpg), then the 20
//   joints in Kinect SDK order in skeleton space (metres). frame_index = n. The files repeat
//   some frame numbers: a repeated line is skipped (the first one wins; the description
//   counts them); a frame number that goes backwards is an error.
// - MSR Action3D, aXX_sYY_eZZ_skeleton3D.txt ("skeleton data in real world coordinates"):
//   no header; 20 lines of "x y z c" per frame, one per joint, in the MSR joint order below;
//   frame_index = 0, 1, 2, ... in file order. The c column is ignored (the data set's own
//   description calls it "supposed to be the confidence value, but not useful").
//   The data set's aXX_sYY_eZZ_skeleton.txt ("screen coordinates": u, v in pixels, depth) has
//   the same 4-column layout; it is refused (code "unsupported"), recognised by values that
//   cannot be metres, with a message pointing to the _skeleton3D.txt file.
// - MSR DailyActivity3D, aXX_sYY_eZZ_skeleton.txt: a header "frames joints" (joints = 20),
//   then per frame a line with a row count R (0: no skeleton, 40: one, 80: two) and R rows of
//   4 numbers, two per joint in Kinect SDK order: first "x y z c" in real-world coordinates
//   (used), then "u v depth c" in screen coordinates (ignored). With two skeletons the first
//   is used. frame_index = 0-based frame number in the file.
// - UTD-MHAD, skeleton.txt (as in ../shared/data/utd-mhad/aA_sS_t1/): no header; 20 lines of
//   "x y z" per frame (metres, Kinect skeleton space), one per joint in the UTD-MHAD order
//   below; frame_index = 0, 1, 2, ... in file order (frame i belongs to depth image i).
// Sources of this understanding (no official specification is public beyond the data sets'
// readmes): the DailyActivity3D readme as quoted in public loaders (e.g. the MSRDA import
// scripts on GitHub); MSR Action3D / UTKinect readers in public code: R. Vemulapalli et al.'s
// Lie-group action recognition code (process_skeletal_data.m: UTKinect "frame + 60 values",
// MSR "4 x 20 per frame"), the dai MSRActionSkeletonInstance reader (4 values per joint line,
// its joint order) and other Python readers of *_skeleton3D.txt. We have no sample file of
// any of these sets except UTD-MHAD (../shared/data/utd-mhad, read by tests); the others'
// tests write files by construction.
//
// MSR Action3D joint order (line k of a frame -> Kinect SDK joint), as named by the dai
// reader and others: 0 ShoulderRight, 1 ShoulderLeft, 2 ShoulderCenter, 3 Spine, 4 HipRight,
// 5 HipLeft, 6 HipCenter, 7 ElbowRight, 8 ElbowLeft, 9 WristRight, 10 WristLeft,
// 11 HandRight, 12 HandLeft, 13 KneeRight, 14 KneeLeft, 15 AnkleRight, 16 AnkleLeft,
// 17 FootRight, 18 FootLeft, 19 Head. Caveat: Vemulapalli et al. map UTKinect onto this
// order with left and right exchanged; the data set names no joints, so its left/right is
// uncertain; the order above is the one its readers name explicitly.
//
// UTD-MHAD joint order (the data set's own list): head, shoulder_center, spine, hip_center,
// then the SDK order from ShoulderLeft on: the first four are the SDK's first four reversed.
//
// Kinect SDK joint order (NUI_SKELETON_POSITION_INDEX; UTKinect, DailyActivity3D):
// HipCenter, Spine, ShoulderCenter, Head, ShoulderLeft, ElbowLeft, WristLeft, HandLeft,
// ShoulderRight, ElbowRight, WristRight, HandRight, HipLeft, KneeLeft, AnkleLeft, FootLeft,
// HipRight, KneeRight, AnkleRight, FootRight. Left/right are the subject's own side (kept).
//
// Frames. Kinect skeleton space: metres, origin at the sensor, y up, z along the sensor's
// view, x to the sensor's left. Our sensor frame (OpenCV): x right, y down, z forward, so
//   p_sensor = (-x, -y, z)   (a rotation by pi about z; no reflection).
// The Kinect SDK delivers its images mirrored, so skeleton x points to the right of the
// mirrored image: the track is in the frame of the true (unmirrored) camera, the frame of a
// depth folder read with mirrored=1 (rgbd:DIR?mirrored=1, rgbd_folder_source.h).
// The MSR sets' real-world coordinates are taken to be this same skeleton space (they were
// recorded with Kinect-class sensors and are read that way by the readers above).
//
// 20 -> 16 joints: KinectV1Joints() of common/skeleton/joint_maps.h, the one table:
//   head = Head, neck = ShoulderCenter, torso = Spine, waist = HipCenter,
//   l_shoulder = ShoulderLeft, l_elbow = ElbowLeft, l_hand = HandLeft (else WristLeft),
//   l_hip = HipLeft, l_knee = KneeLeft, l_foot = AnkleLeft (else FootLeft); right alike.
// Why: our forearm cylinder spans elbow -> hand and our synthetic subject puts the hand joint
// at the palm centre (synthetic/body_model.h), which is where Kinect's
// HandLeft sits, so the cylinder covers the hand as the thesis's NiTE hand did; WristLeft is
// the fallback when the hand is untracked. Our shin spans knee -> foot and the synthetic foot
// joint is the ankle centre (NiTE's foot is at the ankle too), so AnkleLeft; FootLeft (on the
// instep, ahead of the ankle) only when the ankle is untracked. ShoulderCenter lies between
// the shoulders at the base of the neck, our neck joint (the top of the upper torso,
// slightly above the shoulders); HipCenter is the pelvis centre, our waist. Kinect's Spine
// sits lower on the back than our mid-spine torso joint, so imported skeletons have a
// somewhat longer upper torso and shorter lower torso than synthetic ones; both cylinders
// still span neck -> waist together.
//
// Missing joints: a joint whose three coordinates are all 0 (how these sets store untracked
// joints) is missing (confidence 0); a frame whose 20 joints are all 0 has no skeleton and
// is left out of the track. Present joints get confidence 1.
//
// Errors (code "corrupt" unless noted), each naming the file and line: an empty file (or one
// without a tracked skeleton), a token that is not a number, a non-finite number (nan, inf),
// a line with the wrong count of numbers (truncated line), a joint count other than 20, a
// file cut off inside a frame (MSR Action3D, UTD-MHAD: joint lines not a multiple of 20), a
// non-integral or negative frame number, a frame number that goes backwards; "unsupported": values that cannot be metres (screen coordinates, mm);
// "not_found" / "io": the file cannot be read.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "capture-client/skeleton/skeleton_track.h"
#include "common/error/expected.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

enum class KinectTextVariant {
  kDetect,              // from the first data line: 61, 4 or 3 numbers or a 2-number header
  kUtKinect,            // joints_sXX_eYY.txt
  kMsrAction3d,         // aXX_sYY_eZZ_skeleton3D.txt
  kMsrDailyActivity3d,  // aXX_sYY_eZZ_skeleton.txt of MSR DailyActivity3D
  kUtdMhad              // skeleton.txt of UTD-MHAD (as converted in ../shared/data)
};

// "utkinect", "msr-action3d", "msr-daily", "utd-mhad" (and "detect") <-> variant.
std::string_view KinectTextVariantName(KinectTextVariant variant);
std::optional<KinectTextVariant> KinectTextVariantFromName(std::string_view name);

struct KinectV1ReadOptions {
  KinectTextVariant variant = KinectTextVariant::kDetect;
  // Largest |x|, |y| and z of a present joint accepted as metres; a value beyond (or z <= 0)
  // makes the file "unsupported" (not metres). > 0. Kinect v1 sees up to about 4.5 m.
  double max_metres = 10.0;
  SkeletonTrackLookupOptions lookup;  // passed to the track

  void Check() const;  // throws CheckError
};

// Reads a Kinect v1 text track (see the header comment).
Expected<SkeletonTrack> ReadKinectV1SkeletonTrack(const std::string& path,
                                                  const KinectV1ReadOptions& options = {});
// The same from text; `name` starts messages and the description.
Expected<SkeletonTrack> ParseKinectV1SkeletonText(std::string_view text, const std::string& name,
                                                  const KinectV1ReadOptions& options = {});

// Kinect skeleton space -> our sensor frame: (-x, -y, z).
Eigen::Vector3d SensorFromKinectSkeletonSpace(const Eigen::Vector3d& p_kinect);

// MSR Action3D line k of a frame -> Kinect SDK joint index (the order above).
const std::array<int, 20>& MsrAction3dToKinectSdk();
// UTD-MHAD line k of a frame -> Kinect SDK joint index (the order above).
const std::array<int, 20>& UtdMhadToKinectSdk();

// One Kinect skeleton (20 joints in SDK order, skeleton space, all-zero = untracked) in our
// 16 joints, sensor frame.
Skeleton KinectSdkJointsToSkeleton(const std::array<Eigen::Vector3d, 20>& joints_in_kinect);

}  // namespace reenact::capture
