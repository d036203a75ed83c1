#include "capture-client/segment/mask_fill.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace reenact::capture {
int FillDepthHoles(const std::function<double(int, int)>& depth_m, int max_run_px,
                   const PixelRect& box, ImageGray8* mask) {
  if (max_run_px <= 0 || box.empty()) return 0;
  const PixelRect scan = box.Grown(max_run_px + 1, mask->width, mask->height);
  int added = 0;
  for (int y = scan.y0; y < scan.y1; ++y) {
    int x = scan.x0;
    while (x < scan.x1) {
      if (depth_m(x, y) > 0 || mask->at(x, y)) {
        ++x;
        continue;
      }
      const int start = x;
      while (x < scan.x1 && depth_m(x, y) <= 0 && !mask->at(x, y)) ++x;
      const int end = x;  // the run is [start, end)
      if (start == scan.x0 || end == scan.x1 || end - start > max_run_px) continue;
      const double left = depth_m(start - 1, y), right = depth_m(end, y);
      if (left <= 0 || right <= 0) continue;  // a masked hole pixel, not a reading
      const int far_x = left >= right ? start - 1 : end;
      if (!mask->at(far_x, y)) continue;
      for (int u = start; u < end; ++u) mask->at(u, y) = 255;
      added += end - start;
    }
  }
  return added;
}

int FillEnclosedHoles(const std::function<double(int, int)>& depth_m,
                      const std::function<bool(int, int, double)>& is_floor,
                      const DepthTolerance& step, double person_ratio, const PixelRect& box,
                      ImageGray8* mask) {
  if (box.empty()) return 0;
  const PixelRect work = box.Grown(1, mask->width, mask->height);
  const int w = mask->width, ww = work.x1 - work.x0;
  std::vector<uint8_t> seen(static_cast<size_t>(ww) * (work.y1 - work.y0), 0);
  const auto local = [&](int x, int y) { return (y - work.y0) * ww + (x - work.x0); };
  std::vector<int> component;  // image indices
  std::vector<double> border_depths;
  int added = 0;
  for (int y = work.y0; y < work.y1; ++y)
    for (int x = work.x0; x < work.x1; ++x) {
      if (mask->at(x, y) || seen[local(x, y)]) continue;
      component.assign(1, y * w + x);
      seen[local(x, y)] = 1;
      bool exterior = false;
      for (size_t head = 0; head < component.size(); ++head) {
        const int cx = component[head] % w, cy = component[head] / w;
        if (cx == work.x0 || cy == work.y0 || cx == work.x1 - 1 || cy == work.y1 - 1)
          exterior = true;
        const int nx[4] = {cx - 1, cx + 1, cx, cx};
        const int ny[4] = {cy, cy, cy - 1, cy + 1};
        for (int k = 0; k < 4; ++k) {
          if (!work.Contains(nx[k], ny[k])) continue;
          if (mask->at(nx[k], ny[k]) || seen[local(nx[k], ny[k])]) continue;
          seen[local(nx[k], ny[k])] = 1;
          component.push_back(ny[k] * w + nx[k]);
        }
      }
      if (exterior) continue;
      border_depths.clear();
      for (int index : component) {
        const int cx = index % w, cy = index / w;
        const int nx[4] = {cx - 1, cx + 1, cx, cx};
        const int ny[4] = {cy, cy, cy - 1, cy + 1};
        for (int k = 0; k < 4; ++k)  // enclosed: every neighbour lies inside the work box
          if (mask->at(nx[k], ny[k]))
            if (const double z = depth_m(nx[k], ny[k]); z > 0) border_depths.push_back(z);
      }
      double far = INFINITY;
      if (!border_depths.empty()) {
        const auto mid = border_depths.begin() + border_depths.size() / 2;
        std::nth_element(border_depths.begin(), mid, border_depths.end());
        far = *mid + step.At(*mid);
      }
      int person = 0;
      for (int index : component) {
        const int cx = index % w, cy = index / w;
        const double z = depth_m(cx, cy);
        person += z > 0 && z <= far && !is_floor(cx, cy, z);
      }
      if (person < person_ratio * static_cast<double>(component.size())) continue;
      for (int index : component) mask->data[index] = 255;
      added += static_cast<int>(component.size());
    }
  return added;
}

}  // namespace reenact::capture
