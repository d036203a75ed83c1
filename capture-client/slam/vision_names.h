#pragma once
// The generic feature and pose pieces the SLAM builds on live in vision/ (shared with the
// viewer's relocaliser, docs/decisions.md "vision/ layer"); this header names them in
// reenact::capture::slam so that the SLAM code keeps its spelling.

#include "vision/features/feature_matching.h"
#include "vision/features/orb_features.h"
#include "vision/pose/observation_model.h"
#include "vision/pose/pnp_estimator.h"
#include "vision/pose/pose_refinement.h"

namespace reenact::capture::slam {

using vision::ApplyPoseUpdate;
using vision::DescriptorDistance;
using vision::EvaluateObservation;
using vision::ExtractOrbFeatures;
using vision::FeatureMatch;
using vision::FrameFeatures;
using vision::kChi2Dof2;
using vision::kChi2Dof3;
using vision::KeypointGrid;
using vision::KeypointObservation;
using vision::MatchByDescriptor;
using vision::MatchByProjection;
using vision::MatchCandidate;
using vision::MatchOptions;
using vision::ObservationNoise;
using vision::ObservationResidual;
using vision::OrbFeatureOptions;
using vision::PnpEstimator;
using vision::PointJacobianWrtPose;
using vision::PointObservation;
using vision::PoseRefinementOptions;
using vision::PoseRefinementResult;
using vision::RefinePose;

}  // namespace reenact::capture::slam
