#include "viewer-client/render/shaders.h"

namespace reenact::viewer::shaders {

const char* const kCylinderVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_projection;
uniform mat4 u_viewer_from_cylinder;
out vec3 v_position;
out vec3 v_normal;
void main() {
  vec4 p = u_viewer_from_cylinder * vec4(a_position, 1.0);
  v_position = p.xyz;
  v_normal = mat3(u_viewer_from_cylinder) * a_normal;
  gl_Position = u_projection * p;
}
)";

const char* const kCylinderFragment = R"(#version 330 core
in vec3 v_position;
in vec3 v_normal;
uniform int u_textured;
uniform vec3 u_color;
uniform mat4 u_stored_from_viewer;
uniform vec4 u_intrinsics;
uniform vec2 u_texture_size;
uniform sampler2D u_texture;
layout(location = 0) out vec4 out_color;
void main() {
  if (u_textured != 0) {
    vec4 ps = u_stored_from_viewer * vec4(v_position, 1.0);
    vec3 p = ps.xyz / ps.w;
    if (p.z <= 0.0) discard;
    vec2 uv = vec2(u_intrinsics.x * p.x / p.z + u_intrinsics.z,
                   u_intrinsics.y * p.y / p.z + u_intrinsics.w);
    vec2 tc = (uv + 0.5) / u_texture_size;
    if (any(lessThan(tc, vec2(0.0))) || any(greaterThan(tc, vec2(1.0)))) discard;
    vec4 texel = texture(u_texture, tc);
    if (texel.a < 0.5) discard;
    out_color = vec4(texel.rgb / texel.a, 1.0);
  } else {
    vec3 n = normalize(v_normal);
    vec3 to_eye = normalize(-v_position);
    float lambert = abs(dot(n, to_eye));
    out_color = vec4(u_color * (0.35 + 0.65 * lambert), 1.0);
  }
}
)";

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
