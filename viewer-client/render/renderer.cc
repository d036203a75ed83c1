#include "viewer-client/render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "viewer-client/render/cylinder_mesh.h"
#include "viewer-client/render/egl_context.h"
#include "viewer-client/render/gl_objects.h"
#include "viewer-client/render/gl_projection.h"
#include "viewer-client/render/shaders.h"

namespace reenact::viewer {
namespace {

constexpr float kJointPointSize = 5.0f;

struct UploadedTexture {
  GlTexture texture;
  GlTexture visibility;  // RGBA32F: part label, depth in metres, normal (octahedral) or 4
  int width = 0;
  int height = 0;
  PinholeCamera camera;
};

// Octahedral coordinates in [-1, 1]^2 of a unit vector (the shader's OctahedralDecode inverts
// them).
Eigen::Vector2f OctahedralEncode(const Eigen::Vector3f& n) {
  const Eigen::Vector3f a = n / (std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z()));
  if (a.z() >= 0) return a.head<2>();
  return {(1 - std::abs(a.y())) * (a.x() >= 0 ? 1.0f : -1.0f),
          (1 - std::abs(a.x())) * (a.y() >= 0 ? 1.0f : -1.0f)};
}

std::array<float, 16> ToFloat(const Eigen::Matrix4d& m) {
  std::array<float, 16> out{};
  Eigen::Map<Eigen::Matrix4f>(out.data()) = m.cast<float>();  // column-major, as GL wants
  return out;
}

}  // namespace

struct Renderer::Impl {
  // Declared first so that it is destroyed last, after every GL object.
  std::optional<EglContext> context;

  // The cylinder program's variants (shaders.h): [0] kFirst, [n] the visible modes with n
  // candidates.
  struct CylinderProgram {
    GlProgram program;
    GLint projection = -1, model = -1, normal = -1, ring_width = -1, ring_depth = -1,
          surface = -1, surface_angles = -1, cap_depth = -1, textured = -1, color = -1, stored = -1,
          intrinsics = -1, size = -1, relight = -1, light = -1, stored_light = -1;
    GLint mode = -1, ranked = -1, weight = -1, label = -1,
          depth_tolerance = -1;  // visible variants only
  };
  std::array<CylinderProgram, 1 + kMaxTextureCandidates> cylinder_programs;
  GlProgram floor_program, background_program, overlay_program;
  GlVertexArray cylinder_vao, floor_vao, background_vao, overlay_vao;
  GlBuffer cylinder_vertices, cylinder_indices, floor_vertices, overlay_vertices;
  GLsizei cylinder_index_count = 0;

  GlTexture background_texture;
  int background_width = 0, background_height = 0;

  std::vector<UploadedTexture> textures;

  GlFramebuffer framebuffer;
  GlRenderbuffer color_buffer, depth_buffer;
  int width = 0, height = 0;

  // GL objects die in their own context: a headless one is made current first.
  ~Impl() {
    if (context) context->MakeCurrent();
  }
  void MakeCurrent() const {
    if (context) REENACT_CHECK(context->MakeCurrent(), "eglMakeCurrent failed");
  }

  Status Initialize(int w, int h);
  Status MakeFlatPrograms();
  Status MakeCylinderProgram(int variant);
  void MakeCylinderMesh();
  void MakeStreamedVertexArrays();
  void Resize(int w, int h);
  void DrawBackground(const ImageRgb8& image);
  void DrawFloor(const FloorGrid& floor, const std::array<float, 16>& projection);
  void DrawCylinders(const FrameDraw& frame, const std::array<float, 16>& projection);
  void SetFrameUniforms(const FrameDraw& frame, const std::array<float, 16>& projection);
  void SetShapeUniforms(const CylinderProgram& program, const CylinderDraw& c);
  void BindCandidates(const CylinderProgram& program, const CylinderDraw& c, int count,
                      bool visibility);
  void DrawBones(const FrameDraw& frame, const std::array<float, 16>& projection);
};

Status Renderer::Impl::Initialize(int w, int h) {
  REENACT_CHECK(w > 0 && h > 0, "renderer size must be positive");
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (version == nullptr) {
    return MakeError("gl_unavailable", "no current OpenGL context to render with");
  }
  if (epoxy_gl_version() < 33) {
    return MakeError("gl_unavailable",
                     std::string("OpenGL 3.3 core is required, the context offers ") + version);
  }
  if (Status made = MakeFlatPrograms(); !made.ok()) return made.error();
  for (int variant = 0; variant <= kMaxTextureCandidates; ++variant) {
    if (Status made = MakeCylinderProgram(variant); !made.ok()) return made.error();
  }
  glUseProgram(0);
  MakeCylinderMesh();
  MakeStreamedVertexArrays();
  glBindVertexArray(0);

  Resize(w, h);
  const std::string error = GlErrorString();
  if (!error.empty()) {
    return MakeError("gl_unavailable", "OpenGL setup failed with " + error);
  }
  return {};
}

// The floor, background and overlay programs.
Status Renderer::Impl::MakeFlatPrograms() {
  struct ProgramSource {
    GlProgram* program;
    const char* name;
    const char* vertex;
    const char* fragment;
  };
  for (const ProgramSource& p :
       {ProgramSource{&floor_program, "floor", shaders::kFloorVertex, shaders::kFloorFragment},
        ProgramSource{&background_program, "background", shaders::kBackgroundVertex,
                      shaders::kBackgroundFragment},
        ProgramSource{&overlay_program, "overlay", shaders::kOverlayVertex,
                      shaders::kOverlayFragment}}) {
    Expected<GlProgram> program = MakeProgram(p.name, p.vertex, p.fragment);
    if (!program) return program.error();
    *p.program = std::move(program).value();
  }
  return {};
}

// One variant of the cylinder program, its samplers' texture units set (candidate i's crop on
// unit i, its visibility texture on unit kMaxTextureCandidates + i) and its uniforms located;
// leaves it in use.
Status Renderer::Impl::MakeCylinderProgram(int variant) {
  const bool visibility = variant > 0;
  const int candidates = visibility ? variant : 1;
  CylinderProgram& c = cylinder_programs[static_cast<size_t>(variant)];
  Expected<GlProgram> program = MakeProgram("cylinder", shaders::CylinderVertex(kShapeRings, kMaxSurfaceAngles),
                                            shaders::CylinderFragment(candidates, visibility));
  if (!program) return program.error();
  c.program = std::move(program).value();
  const GlProgram& p = c.program;
  glUseProgram(p.id());
  for (int i = 0; i < candidates; ++i) {
    const std::string n = std::to_string(i);
    glUniform1i(UniformLocation(p, ("u_texture" + n).c_str()), i);
    glUniform1i(UniformLocation(p, ("u_visibility" + n).c_str()), kMaxTextureCandidates + i);
  }
  c.projection = UniformLocation(p, "u_projection");
  c.model = UniformLocation(p, "u_viewer_from_cylinder");
  c.normal = UniformLocation(p, "u_normal_from_cylinder");
  c.ring_width = UniformLocation(p, "u_ring_width");
  c.ring_depth = UniformLocation(p, "u_ring_depth");
  c.surface = UniformLocation(p, "u_surface");
  c.surface_angles = UniformLocation(p, "u_surface_angles");
  c.cap_depth = UniformLocation(p, "u_cap_depth");
  c.textured = UniformLocation(p, "u_textured");
  c.color = UniformLocation(p, "u_color");
  c.stored = UniformLocation(p, "u_stored_from_viewer");
  c.intrinsics = UniformLocation(p, "u_intrinsics");
  c.size = UniformLocation(p, "u_texture_size");
  c.relight = UniformLocation(p, "u_relight");
  c.light = UniformLocation(p, "u_light");
  c.stored_light = UniformLocation(p, "u_stored_light");
  if (visibility) {
    c.mode = UniformLocation(p, "u_mode");
    c.ranked = UniformLocation(p, "u_ranked");
    c.weight = UniformLocation(p, "u_weight");
    c.label = UniformLocation(p, "u_part_label");
    c.depth_tolerance = UniformLocation(p, "u_depth_tolerance");
  }
  return {};
}

// The unit cylinder's vertices (position, normal) and indices, uploaded once.
void Renderer::Impl::MakeCylinderMesh() {
  const CylinderMesh mesh = MakeUnitCylinderMesh(kDefaultCylinderSegments);
  std::vector<float> interleaved;
  interleaved.reserve(mesh.positions.size() * 6);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    interleaved.insert(interleaved.end(), mesh.positions[i].data(), mesh.positions[i].data() + 3);
    interleaved.insert(interleaved.end(), mesh.normals[i].data(), mesh.normals[i].data() + 3);
  }
  cylinder_vao = MakeVertexArray();
  cylinder_vertices = MakeBuffer();
  cylinder_indices = MakeBuffer();
  glBindVertexArray(cylinder_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, cylinder_vertices.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
               interleaved.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, cylinder_indices.id());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  cylinder_index_count = static_cast<GLsizei>(mesh.indices.size());
}

// The vertex arrays of the floor (position, grid coordinates) and the overlay (position),
// whose vertices are streamed per frame, and the background's (none: a full-screen triangle).
void Renderer::Impl::MakeStreamedVertexArrays() {
  floor_vao = MakeVertexArray();
  floor_vertices = MakeBuffer();
  glBindVertexArray(floor_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, floor_vertices.id());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));

  overlay_vao = MakeVertexArray();
  overlay_vertices = MakeBuffer();
  glBindVertexArray(overlay_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, overlay_vertices.id());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);

  background_vao = MakeVertexArray();
}

void Renderer::Impl::Resize(int w, int h) {
  if (w == width && h == height && framebuffer) return;
  color_buffer = MakeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, color_buffer.id());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  depth_buffer = MakeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer.id());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
  framebuffer = MakeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            color_buffer.id());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                            depth_buffer.id());
  REENACT_CHECK(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                "offscreen framebuffer incomplete");
  width = w;
  height = h;
}

void Renderer::Impl::DrawBackground(const ImageRgb8& image) {
  if (!background_texture || background_width != image.width || background_height != image.height) {
    background_texture = MakeTexture();
    glBindTexture(GL_TEXTURE_2D, background_texture.id());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 nullptr);
    background_width = image.width;
    background_height = image.height;
  }
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, background_texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE,
                  image.data.data());
  glUseProgram(background_program.id());
  glUniform1i(UniformLocation(background_program, "u_image"), 0);
  glUniform1i(UniformLocation(background_program, "u_height"), image.height);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindVertexArray(background_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Renderer::Impl::DrawFloor(const FloorGrid& floor, const std::array<float, 16>& projection) {
  REENACT_CHECK(floor.up_in_world.allFinite() && floor.up_in_world.norm() > 0,
                "floor up vector must be finite and non-zero");
  REENACT_CHECK(floor.extent_m > 0 && floor.spacing_m > 0 && std::isfinite(floor.extent_m) &&
                    std::isfinite(floor.spacing_m),
                "floor extent and spacing must be positive");
  const Eigen::Vector3d up = floor.up_in_world.normalized();
  const Eigen::Vector3d helper =
      std::abs(up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = up.cross(helper).normalized();
  const Eigen::Vector3d e2 = up.cross(e1);
  std::vector<float> vertices;
  const double e = floor.extent_m;
  for (const auto& [s, t] : std::array<std::pair<double, double>, 6>{
           {{-e, -e}, {e, -e}, {e, e}, {-e, -e}, {e, e}, {-e, e}}}) {
    const Eigen::Vector3d world = floor.point_on_floor_in_world + s * e1 + t * e2;
    const Eigen::Vector3d viewer = floor.viewer_from_world * world;
    vertices.insert(vertices.end(),
                    {static_cast<float>(viewer.x()), static_cast<float>(viewer.y()),
                     static_cast<float>(viewer.z()), static_cast<float>(s), static_cast<float>(t)});
  }
  glBindVertexArray(floor_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, floor_vertices.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STREAM_DRAW);
  glUseProgram(floor_program.id());
  glUniformMatrix4fv(UniformLocation(floor_program, "u_projection"), 1, GL_FALSE,
                     projection.data());
  glUniform1f(UniformLocation(floor_program, "u_spacing"), static_cast<float>(floor.spacing_m));
  glUniform1f(UniformLocation(floor_program, "u_extent"), static_cast<float>(floor.extent_m));
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDrawArrays(GL_TRIANGLES, 0, 6);
}

void Renderer::Impl::DrawCylinders(const FrameDraw& frame,
                                   const std::array<float, 16>& projection) {
  SetFrameUniforms(frame, projection);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glBindVertexArray(cylinder_vao.id());
  const CylinderProgram* current = nullptr;
  for (const CylinderDraw& c : frame.cylinders) {
    if ((c.b - c.a).norm() < 1e-12) continue;
    const bool textured = frame.textured && !c.candidates.empty();
    const bool visibility = textured && c.texturing != TexturingMode::kFirst;
    const int count = visibility ? static_cast<int>(c.candidates.size()) : 1;
    const CylinderProgram& program = cylinder_programs[visibility ? static_cast<size_t>(count) : 0];
    if (&program != current) {
      glUseProgram(program.program.id());
      current = &program;
    }
    SetShapeUniforms(program, c);
    glUniform1i(program.textured, textured ? 1 : 0);
    if (textured) BindCandidates(program, c, count, visibility);
    glDrawElements(GL_TRIANGLES, cylinder_index_count, GL_UNSIGNED_INT, nullptr);
  }
  glActiveTexture(GL_TEXTURE0);
}

// The uniforms every cylinder of a frame shares, in every variant of the program.
void Renderer::Impl::SetFrameUniforms(const FrameDraw& frame,
                                      const std::array<float, 16>& projection) {
  for (const CylinderProgram& c : cylinder_programs) {
    glUseProgram(c.program.id());
    glUniformMatrix4fv(c.projection, 1, GL_FALSE, projection.data());
    if (c.depth_tolerance >= 0)
      glUniform1f(c.depth_tolerance, static_cast<float>(frame.depth_tolerance_m));
    const Eigen::Vector3f light = frame.subject_light.cast<float>();
    glUniform1i(c.relight, light.isZero(0) ? 0 : 1);
    glUniform3f(c.light, light.x(), light.y(), light.z());
  }
}

// A cylinder's placement, ring shape and flat colour.
void Renderer::Impl::SetShapeUniforms(const CylinderProgram& program, const CylinderDraw& c) {
  const Eigen::Matrix4d viewer_from_cylinder =
      ViewerFromUnitCylinder(c.a, c.b, c.radius, c.width_direction);
  const std::array<float, 16> model = ToFloat(viewer_from_cylinder);
  glUniformMatrix4fv(program.model, 1, GL_FALSE, model.data());
  const Eigen::Matrix3f normal = NormalFromUnitCylinder(viewer_from_cylinder).cast<float>();
  glUniformMatrix3fv(program.normal, 1, GL_FALSE, normal.data());
  std::array<float, kShapeRings> width{}, depth{};
  for (int k = 0; k < kShapeRings; ++k) {
    width[k] = static_cast<float>(c.shape.width[k]);
    depth[k] = static_cast<float>(c.shape.depth[k]);
  }
  glUniform1fv(program.ring_width, kShapeRings, width.data());
  glUniform1fv(program.ring_depth, kShapeRings, depth.data());
  const PartSurface& surface = c.shape.surface;
  std::array<float, kShapeRings * kMaxSurfaceAngles> radial{};
  for (int k = 0; k < kShapeRings; ++k)
    for (int j = 0; j < surface.angles; ++j)
      radial[static_cast<size_t>(k * kMaxSurfaceAngles + j)] = static_cast<float>(surface.radial[k][j]);
  glUniform1fv(program.surface, kShapeRings * kMaxSurfaceAngles, radial.data());
  glUniform1i(program.surface_angles, surface.angles);
  glUniform2f(program.cap_depth, static_cast<float>(c.shape.cap_depth[0]),
              static_cast<float>(c.shape.cap_depth[1]));
  glUniform3f(program.color, c.color.x(), c.color.y(), c.color.z());
}

// A textured cylinder's first `count` candidates: their textures bound and their mappings,
// intrinsics, sizes and lights set, with the mode, ranking and weights of the visible modes.
void Renderer::Impl::BindCandidates(const CylinderProgram& program, const CylinderDraw& c,
                                    int count, bool visibility) {
  std::array<float, 16 * kMaxTextureCandidates> stored{};
  std::array<float, 4 * kMaxTextureCandidates> intrinsics{};
  std::array<float, 2 * kMaxTextureCandidates> size{};
  std::array<float, kMaxTextureCandidates> weight{};
  std::array<float, 3 * kMaxTextureCandidates> stored_light{};
  for (int i = 0; i < count; ++i) {
    const TextureCandidate& candidate = c.candidates[static_cast<size_t>(i)];
    const UploadedTexture& t = textures[static_cast<size_t>(candidate.texture)];
    const std::array<float, 16> m = ToFloat(candidate.stored_from_viewer);
    std::copy(m.begin(), m.end(), stored.begin() + 16 * i);
    const float k[4] = {static_cast<float>(t.camera.fx), static_cast<float>(t.camera.fy),
                        static_cast<float>(t.camera.cx), static_cast<float>(t.camera.cy)};
    std::copy(k, k + 4, intrinsics.begin() + 4 * i);
    size[2 * i] = static_cast<float>(t.width);
    size[2 * i + 1] = static_cast<float>(t.height);
    weight[i] = static_cast<float>(candidate.weight);
    for (int k = 0; k < 3; ++k)
      stored_light[3 * i + k] = static_cast<float>(candidate.stored_light[k]);
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, t.texture.id());
    glActiveTexture(GL_TEXTURE0 + kMaxTextureCandidates + i);
    glBindTexture(GL_TEXTURE_2D, t.visibility.id());
  }
  glUniformMatrix4fv(program.stored, count, GL_FALSE, stored.data());
  glUniform4fv(program.intrinsics, count, intrinsics.data());
  glUniform2fv(program.size, count, size.data());
  glUniform3fv(program.stored_light, count, stored_light.data());
  if (visibility) {
    glUniform1i(program.mode, static_cast<int>(c.texturing));
    glUniform1i(program.ranked, static_cast<int>(std::count_if(
                                    c.candidates.begin(), c.candidates.end(),
                                    [](const TextureCandidate& t) { return !t.fallback; })));

    glUniform1f(program.label, static_cast<float>(PartLabel(c.part)));
    glUniform1fv(program.weight, count, weight.data());
  }
}

void Renderer::Impl::DrawBones(const FrameDraw& frame, const std::array<float, 16>& projection) {
  std::vector<float> vertices;
  vertices.reserve(frame.bones.size() * 6);
  for (const auto& [p, q] : frame.bones) {
    for (const Eigen::Vector3d& v : {p, q}) {
      vertices.insert(vertices.end(), {static_cast<float>(v.x()), static_cast<float>(v.y()),
                                       static_cast<float>(v.z())});
    }
  }
  glBindVertexArray(overlay_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, overlay_vertices.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STREAM_DRAW);
  glUseProgram(overlay_program.id());
  glUniformMatrix4fv(UniformLocation(overlay_program, "u_projection"), 1, GL_FALSE,
                     projection.data());
  glUniform3f(UniformLocation(overlay_program, "u_color"), frame.bone_color.x(),
              frame.bone_color.y(), frame.bone_color.z());
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  const auto count = static_cast<GLsizei>(vertices.size() / 3);
  glUniform1f(UniformLocation(overlay_program, "u_point_size"), 1.0f);
  glDrawArrays(GL_LINES, 0, count);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glUniform1f(UniformLocation(overlay_program, "u_point_size"), kJointPointSize);
  glDrawArrays(GL_POINTS, 0, count);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Expected<Renderer> Renderer::CreateHeadless(int width, int height, EglPlatform platform) {
  Expected<EglContext> context = EglContext::Create(platform);
  if (!context) return context.error();
  auto impl = std::make_unique<Impl>();
  impl->context.emplace(std::move(context).value());
  if (Status s = impl->Initialize(width, height); !s) return s.error();
  return Renderer(std::move(impl));
}

Expected<Renderer> Renderer::CreateForCurrentContext(int width, int height) {
  auto impl = std::make_unique<Impl>();
  if (Status s = impl->Initialize(width, height); !s) return s.error();
  return Renderer(std::move(impl));
}

int Renderer::UploadTexture(const StoredTexture& texture) {
  const ImageRgb8& color = texture.color;
  const ImageGray8& mask = texture.mask;
  REENACT_CHECK(!color.empty() && color.channels == 3, "texture colour must be non-empty RGB");
  REENACT_CHECK(mask.channels == 1 && mask.width == color.width && mask.height == color.height,
                "texture mask must be single-channel and the colour's size");
  texture.camera.Check();
  REENACT_CHECK(texture.camera.width == color.width && texture.camera.height == color.height,
                "texture camera must have the crop's size");
  const auto empty_or_crop_sized = [&color](const auto& image) {
    return image.empty() ||
           (image.channels == 1 && image.width == color.width && image.height == color.height);
  };
  REENACT_CHECK(empty_or_crop_sized(texture.part_labels),
                "texture part labels must be empty or single-channel of the crop's size");
  REENACT_CHECK(empty_or_crop_sized(texture.depth_m),
                "texture depth must be empty or single-channel of the crop's size");
  REENACT_CHECK(texture.normals.empty() ||
                    (texture.normals.channels == 3 && texture.normals.width == color.width &&
                     texture.normals.height == color.height),
                "texture normals must be empty or 3-channel of the crop's size");
  REENACT_CHECK(std::all_of(texture.normals.data.begin(), texture.normals.data.end(),
                            [](float v) { return std::isfinite(v); }),
                "texture normals must be finite");
  impl_->MakeCurrent();
  std::vector<uint8_t> rgba(static_cast<size_t>(color.width) * color.height * 4);
  for (size_t i = 0, n = static_cast<size_t>(color.width) * color.height; i < n; ++i) {
    const bool subject = mask.data[i] >= 128;
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = subject ? color.data[3 * i + c] : 0;
    rgba[4 * i + 3] = subject ? 255 : 0;
  }
  UploadedTexture uploaded{MakeTexture(), MakeTexture(), color.width, color.height, texture.camera};
  glBindTexture(GL_TEXTURE_2D, uploaded.texture.id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, color.width, color.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               rgba.data());
  std::vector<float> data(static_cast<size_t>(color.width) * color.height * 4, 0.0f);
  for (size_t i = 0, n = static_cast<size_t>(color.width) * color.height; i < n; ++i) {
    data[4 * i] = texture.part_labels.empty() ? -1.0f : texture.part_labels.data[i];
    if (!texture.depth_m.empty()) data[4 * i + 1] = texture.depth_m.data[i];
    const Eigen::Vector3f normal =
        texture.normals.empty()
            ? Eigen::Vector3f::Zero()
            : Eigen::Vector3f(texture.normals.data[3 * i], texture.normals.data[3 * i + 1],
                              texture.normals.data[3 * i + 2]);
    const Eigen::Vector2f e = normal.isZero(0) ? Eigen::Vector2f(4, 4) : OctahedralEncode(normal);
    data[4 * i + 2] = e.x();
    data[4 * i + 3] = e.y();
  }
  glBindTexture(GL_TEXTURE_2D, uploaded.visibility.id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, color.width, color.height, 0, GL_RGBA, GL_FLOAT,
               data.data());
  impl_->textures.push_back(std::move(uploaded));
  return static_cast<int>(impl_->textures.size() - 1);
}

size_t Renderer::texture_count() const { return impl_->textures.size(); }

std::string Renderer::driver() const {
  impl_->MakeCurrent();
  const auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

void Renderer::ClearTextures() {
  impl_->MakeCurrent();
  impl_->textures.clear();
}

RenderedFrame Renderer::Render(const FrameDraw& frame) {
  Draw(frame);
  return ReadBack();
}

void Renderer::Draw(const FrameDraw& frame) {
  frame.camera.Check();
  for (const CylinderDraw& c : frame.cylinders) {
    REENACT_CHECK(c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius > 0,
                  "cylinder end points must be finite and its radius positive");
    REENACT_CHECK(c.color.allFinite(), "cylinder colour must be finite");
    REENACT_CHECK(c.shape.IsValid(),
                  "cylinder shape values must be finite and > 0 (PartShape::IsValid)");
    REENACT_CHECK(!c.width_direction || c.width_direction->allFinite(),
                  "cylinder width direction must be finite");
    REENACT_CHECK(
        c.candidates.size() <= static_cast<size_t>(kMaxTextureCandidates),
        "a cylinder has at most " + std::to_string(kMaxTextureCandidates) + " texture candidates");
    for (size_t i = 0; i < c.candidates.size(); ++i) {
      const TextureCandidate& t = c.candidates[i];
      REENACT_CHECK(t.fallback || i == 0 || !c.candidates[i - 1].fallback,
                    "fallback candidates must follow every ranked one");
      REENACT_CHECK(t.stored_from_viewer.allFinite(), "stored_from_viewer must be finite");
      REENACT_CHECK(std::isfinite(t.weight) && t.weight >= 0,
                    "candidate weights must be finite and >= 0");
      REENACT_CHECK(t.stored_light.allFinite(), "candidate stored_light must be finite");
      REENACT_CHECK(t.texture >= 0 && t.texture < static_cast<int>(impl_->textures.size()),
                    "cylinder texture index " + std::to_string(t.texture) + " was never uploaded");
    }
  }
  REENACT_CHECK(std::isfinite(frame.depth_tolerance_m) && frame.depth_tolerance_m >= 0,
                "depth_tolerance_m must be finite and >= 0");
  REENACT_CHECK(frame.subject_light.allFinite(), "subject_light must be finite");
  for (const auto& [p, q] : frame.bones) {
    REENACT_CHECK(p.allFinite() && q.allFinite(), "bone end points must be finite");
  }
  if (frame.background != nullptr) {
    const ImageRgb8& bg = *frame.background;
    REENACT_CHECK(
        bg.channels == 3 && bg.width == frame.camera.width && bg.height == frame.camera.height,
        "background must be an RGB image of the camera's size");
  }
  impl_->MakeCurrent();
  impl_->Resize(frame.camera.width, frame.camera.height);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->framebuffer.id());
  glViewport(0, 0, impl_->width, impl_->height);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDepthFunc(GL_LESS);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glClearColor(frame.clear_color.x(), frame.clear_color.y(), frame.clear_color.z(), 0.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  const std::array<float, 16> projection = ToFloat(GlProjectionFromPinhole(frame.camera));
  // Alpha is the subject mask: only cylinders write it.
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  if (frame.background != nullptr) impl_->DrawBackground(*frame.background);
  if (frame.floor) impl_->DrawFloor(*frame.floor, projection);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  impl_->DrawCylinders(frame, projection);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  if (!frame.bones.empty()) impl_->DrawBones(frame, projection);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindVertexArray(0);
  glUseProgram(0);
}

RenderedFrame Renderer::ReadBack() const {
  impl_->MakeCurrent();
  const int w = impl_->width, h = impl_->height;
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->framebuffer.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  RenderedFrame out{ImageRgb8(w, h, 3), ImageGray8(w, h, 1)};
  for (int y = 0; y < h; ++y) {
    const uint8_t* in = rgba.data() + static_cast<size_t>(h - 1 - y) * w * 4;
    uint8_t* color = out.color.data.data() + static_cast<size_t>(y) * w * 3;
    uint8_t* mask = out.subject_mask.data.data() + static_cast<size_t>(y) * w;
    for (int x = 0; x < w; ++x, in += 4, color += 3) {
      color[0] = in[0];
      color[1] = in[1];
      color[2] = in[2];
      mask[x] = in[3] >= 128 ? 255 : 0;
    }
  }
  return out;
}

void Renderer::BlitToDefaultFramebuffer(int framebuffer_width, int framebuffer_height) const {
  impl_->MakeCurrent();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glViewport(0, 0, framebuffer_width, framebuffer_height);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (framebuffer_width <= 0 || framebuffer_height <= 0) return;
  const double scale = std::min(static_cast<double>(framebuffer_width) / impl_->width,
                                static_cast<double>(framebuffer_height) / impl_->height);
  const int w = static_cast<int>(std::lround(impl_->width * scale));
  const int h = static_cast<int>(std::lround(impl_->height * scale));
  const int x0 = (framebuffer_width - w) / 2, y0 = (framebuffer_height - h) / 2;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->framebuffer.id());
  glBlitFramebuffer(0, 0, impl_->width, impl_->height, x0, y0, x0 + w, y0 + h, GL_COLOR_BUFFER_BIT,
                    GL_LINEAR);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  // The offscreen alpha holds the subject mask; a window must be opaque on compositing
  // desktops, so its alpha is set to 1 everywhere.
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

int Renderer::width() const { return impl_->width; }
int Renderer::height() const { return impl_->height; }

}  // namespace reenact::viewer
