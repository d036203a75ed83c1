#include "viewer-client/output/render_json.h"

namespace reenact::viewer {

nlohmann::json PoseJson(const Eigen::Isometry3d& pose) {
  nlohmann::json m = nlohmann::json::array();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.push_back(pose.matrix()(r, c));
  return m;
}

nlohmann::json CameraJson(const PinholeCamera& c) {
  const Distortion& d = c.distortion;
  return {{"width", c.width},
          {"height", c.height},
          {"fx", c.fx},
          {"fy", c.fy},
          {"cx", c.cx},
          {"cy", c.cy},
          {"distortion", {d.k1, d.k2, d.p1, d.p2, d.k3}}};
}

nlohmann::json SubjectLightJson(const SubjectLightFit& fit) {
  nlohmann::json j = {{"found", fit.found},
                      {"light_in_world", {fit.light.x(), fit.light.y(), fit.light.z()}},
                      {"strength", fit.light.norm()},
                      {"gain", fit.gain},
                      {"samples", fit.samples},
                      {"bins", fit.bins}};
  if (!fit.found) j["reason"] = fit.reason;
  return j;
}

}  // namespace reenact::viewer
