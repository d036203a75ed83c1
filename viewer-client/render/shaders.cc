#include "viewer-client/render/shaders.h"

#include <string>

namespace reenact::viewer::shaders {

namespace {

// After "#version 330 core" and the defines RINGS (kShapeRings) and MAX_ANGLES
// (kMaxSurfaceAngles).
const char* const kCylinderVertexBody = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_projection;
uniform mat4 u_viewer_from_cylinder;
uniform mat3 u_normal_from_cylinder;
uniform float u_ring_width[RINGS];
uniform float u_ring_depth[RINGS];
uniform float u_surface[RINGS * MAX_ANGLES];
uniform int u_surface_angles;
uniform vec2 u_cap_depth;
out vec3 v_position;
out vec3 v_normal;
float SurfaceFactor(int k, float phi) {
  if (u_surface_angles == 0) return 1.0;
  float x = phi / 6.283185307179586 * float(u_surface_angles);
  float lo = floor(x);
  float f = x - lo;
  int j = int(mod(lo, float(u_surface_angles)));
  int j1 = j + 1 == u_surface_angles ? 0 : j + 1;
  return (1.0 - f) * u_surface[k * MAX_ANGLES + j] + f * u_surface[k * MAX_ANGLES + j1];
}
void main() {
  int k = clamp(int(floor(a_position.z * float(RINGS - 1) + 0.5)), 0, RINGS - 1);
  float w = u_ring_width[k];
  float d = u_ring_depth[k];
  float s = 1.0;
  if (u_surface_angles > 0 && (a_position.x != 0.0 || a_position.y != 0.0))
    s = SurfaceFactor(k, atan(a_position.y, a_position.x));
  vec3 n = a_normal;
  float z = a_position.z;
  if (a_normal.z != 0.0) {
    float dome = a_normal.z < 0.0 ? u_cap_depth.x : u_cap_depth.y;
    if (dome != 0.0) {
      float h = sqrt(max(0.0, 1.0 - dot(a_position.xy, a_position.xy)));
      z += a_normal.z < 0.0 ? -dome * h : dome * h;
      n = vec3(a_position.x / (s * w), a_position.y / (s * d), a_normal.z * h / dome);
    }
  } else {
    float c = a_normal.x;
    float sn = a_normal.y;
    float phi = atan(sn, c);
    int lo = max(k - 1, 0);
    int hi = min(k + 1, RINGS - 1);
    float scale = float(RINGS - 1) / float(hi - lo);
    float f_hi = SurfaceFactor(hi, phi);
    float f_lo = SurfaceFactor(lo, phi);
    float wz = (f_hi * u_ring_width[hi] - f_lo * u_ring_width[lo]) * scale;
    float dz = (f_hi * u_ring_depth[hi] - f_lo * u_ring_depth[lo]) * scale;
    float f_phi = 0.0;
    if (u_surface_angles > 0) {
      float h = 3.141592653589793 / float(u_surface_angles);
      f_phi = (SurfaceFactor(k, phi + h) - SurfaceFactor(k, phi - h)) / (2.0 * h);
    }
    float px = f_phi * w * c - s * w * sn;
    float py = f_phi * d * sn + s * d * c;
    n = vec3(py, -px, px * dz * sn - py * wz * c);
  }
  vec4 p = u_viewer_from_cylinder * vec4(a_position.x * s * w, a_position.y * s * d, z, 1.0);
  v_position = p.xyz;
  v_normal = u_normal_from_cylinder * n;
  gl_Position = u_projection * p;
}
)";

// After "#version 330 core", the defines CANDIDATES (1..kMaxTextureCandidates) and VISIBILITY
// (0 or 1), and the samplers u_texture<i>, u_visibility<i> of every candidate (CylinderFragment
// declares them; GLSL 3.30 indexes sampler arrays by constants only). Ends in main()'s head;
// CylinderFragment appends one line per candidate and the tail.
const char* const kCylinderFragmentHead = R"(
in vec3 v_position;
in vec3 v_normal;
uniform int u_textured;
uniform vec3 u_color;
uniform mat4 u_stored_from_viewer[CANDIDATES];
uniform vec4 u_intrinsics[CANDIDATES];
uniform vec2 u_texture_size[CANDIDATES];
uniform int u_relight;
uniform vec3 u_light;
uniform vec3 u_stored_light[CANDIDATES];
#if VISIBILITY
uniform int u_mode;
uniform int u_ranked;
uniform float u_weight[CANDIDATES];
uniform float u_part_label;
uniform float u_depth_tolerance;
#endif
layout(location = 0) out vec4 out_color;

// common/texture/subject_light.h's SubjectShade.
float Shade(vec3 n, vec3 light) { return 1.0 + max(0.0, dot(n, light)); }

vec2 SignNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

// The unit vector of octahedral coordinates e (renderer.cc's OctahedralEncode).
vec3 OctahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * SignNotZero(n.xy);
  return normalize(n);
}

// 0: unusable, 1: usable and labelled as another part, 2: usable, not visible otherwise (the
// depth disagrees, or the crop has no labels: label -1), 3: visible.
int Candidate(int i, sampler2D tex, sampler2D vis, out vec3 rgb) {
  rgb = vec3(0.0);
  vec4 ps = u_stored_from_viewer[i] * vec4(v_position, 1.0);
  vec3 p = ps.xyz / ps.w;
  if (p.z <= 0.0) return 0;
  vec2 uv = vec2(u_intrinsics[i].x * p.x / p.z + u_intrinsics[i].z,
                 u_intrinsics[i].y * p.y / p.z + u_intrinsics[i].w);
  vec2 tc = (uv + 0.5) / u_texture_size[i];
  if (any(lessThan(tc, vec2(0.0))) || any(greaterThan(tc, vec2(1.0)))) return 0;
  vec4 texel = texture(tex, tc);
  if (texel.a < 0.5) return 0;
  rgb = texel.rgb / texel.a;
  ivec2 size = ivec2(u_texture_size[i]);
  ivec2 nearest = clamp(ivec2(floor(uv + 0.5)), ivec2(0), size - 1);
  vec4 data = texelFetch(vis, nearest, 0);  // label, depth, stored normal (octahedral)
  if (u_relight != 0) {
    vec3 n = data.b <= 1.0 ? normalize(transpose(mat3(u_stored_from_viewer[i])) *
                                       OctahedralDecode(data.ba))
                           : normalize(v_normal);
    rgb *= Shade(n, u_light) / Shade(n, u_stored_light[i]);
  }
#if VISIBILITY
  if (data.r != u_part_label) return data.r < 0.0 ? 2 : 1;
  if (data.g > 0.0 && !(abs(data.g - p.z) <= u_depth_tolerance)) return 2;
  return 3;
#else
  return 1;
#endif
}

// The candidates seen so far in rank order: the weighted sum of the visible ranked ones (blend
// mode), the first visible and the first usable ranked colour, the first visible fallback.
float g_total = 0.0;
vec3 g_sum = vec3(0.0);
bool g_visible = false;
vec3 g_visible_rgb = vec3(0.0);
bool g_usable = false;
bool g_usable_other = false;
vec3 g_usable_rgb = vec3(0.0);
bool g_fallback = false;
vec3 g_fallback_rgb = vec3(0.0);

#if VISIBILITY
// Whether candidate i can still change the colour (common/render/texturing.h's modes): a
// ranked one in the blend mode while it has weight, or while no visible candidate has been
// seen; in the first-visible mode while no visible candidate has been seen. A fallback one
// (i >= u_ranked) only where no ranked one is visible, the first usable ranked one shows
// another part, and no earlier fallback is visible.
bool Needed(int i) {
  if (i >= u_ranked)
    return !g_visible && !g_fallback && g_usable_other;
  return u_mode == 2 ? (u_weight[i] > 0.0 || (g_total == 0.0 && !g_visible)) : !g_visible;
}

void Take(int i, int state, vec3 rgb) {
  if (i >= u_ranked) {
    if (state == 3) {
      g_fallback = true;
      g_fallback_rgb = rgb;
    }
    return;
  }
  if (state == 0) return;
  if (!g_usable) {
    g_usable = true;
    g_usable_other = state == 1;
    g_usable_rgb = rgb;
  }
  if (state != 3) return;
  if (!g_visible) {
    g_visible = true;
    g_visible_rgb = rgb;
  }
  if (u_mode == 2 && u_weight[i] > 0.0) {
    g_total += u_weight[i];
    g_sum += u_weight[i] * rgb;
  }
}
#endif

void main() {
  if (u_textured == 0) {
    vec3 n = normalize(v_normal);
    vec3 to_eye = normalize(-v_position);
    float lambert = abs(dot(n, to_eye));
    out_color = vec4(u_color * (0.35 + 0.65 * lambert), 1.0);
    return;
  }
  vec3 rgb;
)";

const char* const kCylinderFragmentTail = R"(
#if VISIBILITY
  if (g_total > 0.0) {
    out_color = vec4(g_sum / g_total, 1.0);
  } else if (g_visible) {
    out_color = vec4(g_visible_rgb, 1.0);
  } else if (g_fallback) {
    out_color = vec4(g_fallback_rgb, 1.0);
  } else if (g_usable) {
    out_color = vec4(g_usable_rgb, 1.0);
  } else {
    discard;
  }
#else
  if (Candidate(0, u_texture0, u_visibility0, rgb) == 0) discard;
  out_color = vec4(rgb, 1.0);
#endif
}
)";

}  // namespace

std::string CylinderVertex(int rings, int max_angles) {
  std::string source = "#version 330 core\n#define RINGS ";
  source += std::to_string(rings);
  source += "\n#define MAX_ANGLES ";
  source += std::to_string(max_angles);
  source += "\n";
  return source + kCylinderVertexBody;
}

std::string CylinderFragment(int candidates, bool visibility) {
  std::string source = "#version 330 core\n#define CANDIDATES " + std::to_string(candidates) +
                       "\n#define VISIBILITY " + (visibility ? "1" : "0") + "\n";
  for (int i = 0; i < candidates; ++i) {
    const std::string n = std::to_string(i);
    source += "uniform sampler2D u_texture" + n + ";\nuniform sampler2D u_visibility" + n + ";\n";
  }
  source += kCylinderFragmentHead;
  if (visibility)
    for (int i = 0; i < candidates; ++i) {
      const std::string n = std::to_string(i);
      source += "  if (Needed(" + n + ")) Take(" + n + ", Candidate(" + n + ", u_texture" + n +
                ", u_visibility" + n + ", rgb), rgb);\n";
    }
  return source + kCylinderFragmentTail;
}

const char* const kFloorVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_plane;
uniform mat4 u_projection;
out vec2 v_plane;
void main() {
  v_plane = a_plane;
  gl_Position = u_projection * vec4(a_position, 1.0);
}
)";

const char* const kFloorFragment = R"(#version 330 core
in vec2 v_plane;
uniform float u_spacing;
uniform float u_extent;
layout(location = 0) out vec4 out_color;
void main() {
  vec2 cell = v_plane / u_spacing;
  vec2 distance_to_line = abs(fract(cell - 0.5) - 0.5) / max(fwidth(cell), vec2(1e-6));
  float line = 1.0 - clamp(min(distance_to_line.x, distance_to_line.y) - 0.5, 0.0, 1.0);
  float fade = 1.0 - smoothstep(0.6, 1.0, length(v_plane) / u_extent);
  vec3 plane = vec3(0.32, 0.33, 0.35);
  vec3 grid = vec3(0.62, 0.64, 0.66);
  out_color = vec4(mix(plane, grid, line * fade), 1.0);
}
)";

const char* const kBackgroundVertex = R"(#version 330 core
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kBackgroundFragment = R"(#version 330 core
uniform sampler2D u_image;
uniform int u_height;
layout(location = 0) out vec4 out_color;
void main() {
  ivec2 frag_pixel = ivec2(gl_FragCoord.xy);
  out_color = vec4(texelFetch(u_image, ivec2(frag_pixel.x, u_height - 1 - frag_pixel.y), 0).rgb, 0.0);
}
)";

const char* const kOverlayVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_projection;
uniform float u_point_size;
void main() {
  gl_PointSize = u_point_size;
  gl_Position = u_projection * vec4(a_position, 1.0);
}
)";

const char* const kOverlayFragment = R"(#version 330 core
uniform vec3 u_color;
layout(location = 0) out vec4 out_color;
void main() { out_color = vec4(u_color, 1.0); }
)";

}  // namespace reenact::viewer::shaders
