#include "synthetic/gltf_skin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <optional>

#include "synthetic/tinygltf_private.h"

namespace reenact::capture {
namespace {

using Eigen::Vector3d;
using Eigen::Vector4d;

// Reads and validates glTF content for one file; every error names the file.
class Reader {
 public:
  Reader(const tinygltf::Model& m, std::string path) : m_(m), path_(std::move(path)) {}

  Error Corrupt(const std::string& what) const {
    return MakeError("corrupt", path_ + ": " + what + "; the glTF file is malformed, re-export it");
  }
  Error Unsupported(const std::string& what) const {
    return MakeError("unsupported", path_ + ": " + what);
  }

  // Accessor `index` as count rows of `components` doubles. Normalised integer types map to
  // [0, 1] or [-1, 1] (as the accessor says); other integers keep their value.
  struct Values {
    size_t count = 0;
    int components = 0;
    std::vector<double> v;  // row-major
    double at(size_t row, int c) const { return v[row * components + c]; }
  };
  Expected<Values> Read(int index, const std::string& what, const std::vector<int>& types,
                        const std::vector<int>& component_types) const {
    if (index < 0 || index >= static_cast<int>(m_.accessors.size()))
      return Corrupt(what + " refers to accessor " + std::to_string(index) + " but the file has " +
                     std::to_string(m_.accessors.size()) + " accessors");
    const tinygltf::Accessor& a = m_.accessors[index];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (std::find(types.begin(), types.end(), a.type) == types.end())
      return Corrupt(name + " has the wrong element type " + std::to_string(a.type));
    if (std::find(component_types.begin(), component_types.end(), a.componentType) ==
        component_types.end())
      return Corrupt(name + " has the wrong component type " + std::to_string(a.componentType));
    if (a.sparse.isSparse) return Unsupported(name + " is a sparse accessor, which is not read");
    const int n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    Values out;
    out.count = a.count;
    out.components = n;
    if (a.count > (size_t{1} << 28)) return Corrupt(name + " has an implausible count");
    out.v.assign(a.count * n, 0.0);
    if (a.bufferView < 0) return out;  // no buffer view: zeros (glTF 2.0, "Accessors")
    if (a.bufferView >= static_cast<int>(m_.bufferViews.size()))
      return Corrupt(name + " refers to buffer view " + std::to_string(a.bufferView) +
                     " which does not exist");
    const tinygltf::BufferView& view = m_.bufferViews[a.bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(m_.buffers.size()))
      return Corrupt(name + ": buffer view " + std::to_string(a.bufferView) +
                     " refers to a buffer that does not exist");
    const std::vector<unsigned char>& data = m_.buffers[view.buffer].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
      return Corrupt(name + ": buffer view " + std::to_string(a.bufferView) +
                     " runs past the end of its buffer (truncated file?)");
    const size_t element = static_cast<size_t>(n) * size;
    const size_t stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element) return Corrupt(name + " has a byte stride smaller than its element");
    if (a.count > 0 && (a.byteOffset > view.byteLength ||
                        (a.count - 1) * stride + element > view.byteLength - a.byteOffset))
      return Corrupt(name + " runs past the end of its buffer view");
    const unsigned char* base = data.data() + view.byteOffset + a.byteOffset;
    for (size_t i = 0; i < a.count; ++i) {
      for (int c = 0; c < n; ++c) {
        const unsigned char* p = base + i * stride + static_cast<size_t>(c) * size;
        out.v[i * n + c] = Component(p, a.componentType, a.normalized);
      }
    }
    return out;
  }

  const tinygltf::Model& model() const { return m_; }
  const std::string& path() const { return path_; }

 private:
  template <typename T>
  static T Load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
  }
  static double Component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return Load<float>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const double v = Load<uint8_t>(p);
        return normalized ? v / 255.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const double v = Load<uint16_t>(p);
        return normalized ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double v = Load<int8_t>(p);
        return normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const double v = Load<int16_t>(p);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return Load<uint32_t>(p);
      default:
        return 0;
    }
  }

  const tinygltf::Model& m_;
  std::string path_;
};

const std::vector<int> kFloat = {TINYGLTF_COMPONENT_TYPE_FLOAT};
const std::vector<int> kFloatOrNormalizedUnsigned = {TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kFloatOrNormalized = {
    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
const std::vector<int> kIndexTypes = {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT};

bool AllFinite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Decomposes a glTF node matrix (column-major) into T * R * S; nullopt with shear or a
// singular matrix.
std::optional<NodeTransform> Decompose(const std::vector<double>& m) {
  Eigen::Matrix4d a;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a(r, c) = m[c * 4 + r];
  if (!a.allFinite() || (a.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    return std::nullopt;
  NodeTransform t;
  t.translation = a.block<3, 1>(0, 3);
  Eigen::Matrix3d l = a.block<3, 3>(0, 0);
  for (int k = 0; k < 3; ++k) t.scale[k] = l.col(k).norm();
  if (t.scale.minCoeff() < 1e-12) return std::nullopt;
  if (l.determinant() < 0) t.scale.x() = -t.scale.x();
  const Eigen::Matrix3d r = l * t.scale.cwiseInverse().asDiagonal();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-4)
    return std::nullopt;  // shear
  t.rotation = Eigen::Quaterniond(r).normalized();
  return t;
}

Eigen::Vector3d TriangleNormal(const std::vector<SkinVertex>& v, const Eigen::Vector3i& t) {
  return (v[t[1]].position - v[t[0]].position).cross(v[t[2]].position - v[t[0]].position);
}

// Triangles (as index triples into the primitive's vertices) of a primitive's index list.
Expected<std::vector<Eigen::Vector3i>> AssembleTriangles(const Reader& r, int mode,
                                                         const std::vector<int64_t>& idx,
                                                         const std::string& what) {
  std::vector<Eigen::Vector3i> tris;
  const auto add = [&](int64_t a, int64_t b, int64_t c) {
    if (a != b && b != c && a != c)  // degenerate strip/fan joints carry no surface
      tris.emplace_back(static_cast<int>(a), static_cast<int>(b), static_cast<int>(c));
  };
  const size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0)
      return r.Corrupt(what + " has " + std::to_string(n) + " indices, not a multiple of 3");
    for (size_t i = 0; i + 2 < n; i += 3) add(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) {
      if (i % 2 == 0)
        add(idx[i], idx[i + 1], idx[i + 2]);
      else
        add(idx[i + 1], idx[i], idx[i + 2]);
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t i = 1; i + 1 < n; ++i) add(idx[0], idx[i], idx[i + 1]);
  } else {
    return r.Unsupported(what + " has primitive mode " + std::to_string(mode) +
                         " (points or lines); only triangles are read");
  }
  return tris;
}

// Appends one primitive's vertices and triangles to `out`.
// A primitive's attributes by name, each read with the primitive's vertex count checked.
class PrimitiveAttributes {
 public:
  PrimitiveAttributes(const Reader& r, const tinygltf::Primitive& p, const std::string& what)
      : r_(r), p_(p), what_(what) {}

  // The attribute's accessor, -1 where the primitive has none.
  int Find(const std::string& name) const {
    const auto it = p_.attributes.find(name);
    return it == p_.attributes.end() ? -1 : it->second;
  }
  // The attribute's values: `type` of one of `components`, n elements, all finite.
  Expected<Reader::Values> ReadSized(const std::string& name, int type,
                                     const std::vector<int>& components, size_t n) const {
    Expected<Reader::Values> v = r_.Read(Find(name), what_ + " " + name, {type}, components);
    if (!v.ok()) return v;
    if (v->count != n)
      return r_.Corrupt(what_ + " " + name + " has " + std::to_string(v->count) +
                        " elements but POSITION has " + std::to_string(n));
    if (!AllFinite(v->v)) return r_.Corrupt(what_ + " " + name + " has a value that is not finite");
    return v;
  }

 private:
  const Reader& r_;
  const tinygltf::Primitive& p_;
  const std::string& what_;
};

// Normals (unit; *generated where the primitive has none) and texture coordinates (set
// texcoord_set, where the texture needs them) of vertices [first, first + n).
Status ReadNormalsAndUv(const Reader& r, const PrimitiveAttributes& a, const std::string& what,
                        int texcoord_set, size_t first, size_t n, GltfSkinModel* out,
                        bool* generated_normals) {
  if (a.Find("NORMAL") >= 0) {
    Expected<Reader::Values> nor = a.ReadSized("NORMAL", TINYGLTF_TYPE_VEC3, kFloat, n);
    if (!nor.ok()) return nor.error();
    for (size_t i = 0; i < n; ++i) {
      const Vector3d v(nor->at(i, 0), nor->at(i, 1), nor->at(i, 2));
      if (!(v.norm() > 1e-12)) return r.Corrupt(what + " NORMAL " + std::to_string(i) + " is zero");
      out->vertices[first + i].normal = v.normalized();
    }
  } else {
    *generated_normals = true;
  }
  if (texcoord_set >= 0) {
    const std::string name = "TEXCOORD_" + std::to_string(texcoord_set);
    if (a.Find(name) < 0)
      return r.Corrupt(what + " has no " + name + " attribute, which its texture needs");
    Expected<Reader::Values> uv =
        a.ReadSized(name, TINYGLTF_TYPE_VEC2, kFloatOrNormalizedUnsigned, n);
    if (!uv.ok()) return uv.error();
    for (size_t i = 0; i < n; ++i)
      out->vertices[first + i].uv = Eigen::Vector2d(uv->at(i, 0), uv->at(i, 1));
  }
  return {};
}

// Skin influences of vertices [first, first + n) from both JOINTS/WEIGHTS sets, the four
// largest kept (*extra_influences counts the vertices that had more) and normalised
// (*normalised counts those whose weights did not sum to 1).
Status ReadInfluences(const Reader& r, const PrimitiveAttributes& a, const std::string& what,
                      int joint_count, size_t first, size_t n, GltfSkinModel* out, int* normalised,
                      int* extra_influences) {
  std::vector<std::pair<Expected<Reader::Values>, Expected<Reader::Values>>> sets;
  for (int set = 0; set < 2; ++set) {
    const std::string j = "JOINTS_" + std::to_string(set), w = "WEIGHTS_" + std::to_string(set);
    if (a.Find(j) < 0 && a.Find(w) < 0) continue;
    if (a.Find(j) < 0 || a.Find(w) < 0)
      return r.Corrupt(what + " has one of " + j + " and " + w + " without the other");
    Expected<Reader::Values> jv = a.ReadSized(
        j, TINYGLTF_TYPE_VEC4,
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, n);
    if (!jv.ok()) return jv.error();
    Expected<Reader::Values> wv = a.ReadSized(w, TINYGLTF_TYPE_VEC4, kFloatOrNormalizedUnsigned, n);
    if (!wv.ok()) return wv.error();
    sets.emplace_back(std::move(jv), std::move(wv));
  }
  for (size_t i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> influences;  // (weight, joint)
    for (const auto& [jv, wv] : sets) {
      for (int k = 0; k < 4; ++k) {
        const double w = wv->at(i, k);
        const int j = static_cast<int>(jv->at(i, k));
        if (w < 0)
          return r.Corrupt(what + " vertex " + std::to_string(i) + " has a negative skin weight");
        if (w == 0) continue;
        if (j >= joint_count)
          return r.Corrupt(what + " vertex " + std::to_string(i) + " refers to joint " +
                           std::to_string(j) + " but the skin has " + std::to_string(joint_count) +
                           " joints");
        influences.emplace_back(w, j);
      }
    }
    if (influences.empty())
      return r.Corrupt(what + " vertex " + std::to_string(i) + " has all skin weights zero");
    std::stable_sort(influences.begin(), influences.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    if (influences.size() > 4) {
      ++*extra_influences;
      influences.resize(4);
    }
    double sum = 0;
    for (const auto& [w, j] : influences) sum += w;
    // Weights stored as floats (or normalised bytes) sum to 1 only to within their rounding.
    if (std::abs(sum - 1) > 2e-3) ++*normalised;
    SkinVertex& v = out->vertices[first + i];
    for (size_t k = 0; k < influences.size(); ++k) {
      v.weights[k] = influences[k].first / sum;
      v.joints[k] = influences[k].second;
    }
  }
  return {};
}

// The primitive's triangles, its indices checked against its n vertices, offset by first.
Status ReadTriangles(const Reader& r, const tinygltf::Primitive& p, const std::string& what,
                     size_t first, size_t n, GltfSkinModel* out) {
  std::vector<int64_t> idx;
  if (p.indices >= 0) {
    Expected<Reader::Values> iv =
        r.Read(p.indices, what + " indices", {TINYGLTF_TYPE_SCALAR}, kIndexTypes);
    if (!iv.ok()) return iv.error();
    idx.reserve(iv->count);
    for (size_t i = 0; i < iv->count; ++i) {
      const double k = iv->v[i];
      if (k >= static_cast<double>(n))
        return r.Corrupt(what + " index " + std::to_string(i) + " is " +
                         std::to_string(static_cast<int64_t>(k)) + " but the primitive has " +
                         std::to_string(n) + " vertices");
      idx.push_back(static_cast<int64_t>(k));
    }
  } else {
    idx.resize(n);
    std::iota(idx.begin(), idx.end(), int64_t{0});
  }
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  Expected<std::vector<Eigen::Vector3i>> tris = AssembleTriangles(r, mode, idx, what);
  if (!tris.ok()) return tris.error();
  for (const Eigen::Vector3i& t : *tris)
    out->triangles.push_back(t + Eigen::Vector3i::Constant(static_cast<int>(first)));
  return {};
}

Status ReadPrimitive(const Reader& r, const tinygltf::Primitive& p, const std::string& what,
                     int texcoord_set, int joint_count, GltfSkinModel* out, int* normalised,
                     int* extra_influences, bool* generated_normals) {
  const PrimitiveAttributes a(r, p, what);
  if (a.Find("POSITION") < 0) return r.Corrupt(what + " has no POSITION attribute");
  Expected<Reader::Values> pos =
      r.Read(a.Find("POSITION"), what + " POSITION", {TINYGLTF_TYPE_VEC3}, kFloat);
  if (!pos.ok()) return pos.error();
  const size_t n = pos->count;
  if (!AllFinite(pos->v)) return r.Corrupt(what + " POSITION has a value that is not finite");
  if (a.Find("JOINTS_0") < 0 || a.Find("WEIGHTS_0") < 0)
    return r.Corrupt(what + " of the skinned mesh has no JOINTS_0 / WEIGHTS_0 attributes");
  const size_t first = out->vertices.size();
  out->vertices.resize(first + n);
  for (size_t i = 0; i < n; ++i)
    out->vertices[first + i].position = Vector3d(pos->at(i, 0), pos->at(i, 1), pos->at(i, 2));
  if (Status s = ReadNormalsAndUv(r, a, what, texcoord_set, first, n, out, generated_normals);
      !s.ok())
    return s.error();
  if (Status s =
          ReadInfluences(r, a, what, joint_count, first, n, out, normalised, extra_influences);
      !s.ok())
    return s.error();
  return ReadTriangles(r, p, what, first, n, out);
}

Expected<GltfTexture> ReadTexture(const Reader& r, int texture_index) {
  const tinygltf::Model& m = r.model();
  if (texture_index >= static_cast<int>(m.textures.size()))
    return r.Corrupt("the material refers to texture " + std::to_string(texture_index) +
                     " which does not exist");
  const tinygltf::Texture& t = m.textures[texture_index];
  if (t.source < 0 || t.source >= static_cast<int>(m.images.size()))
    return r.Corrupt("texture " + std::to_string(texture_index) + " has no valid image source");
  const tinygltf::Image& img = m.images[t.source];
  const size_t bytes = img.bits == 16 ? 2 : 1;
  if (img.width <= 0 || img.height <= 0 || img.component < 1 || img.component > 4 ||
      (img.bits != 8 && img.bits != 16) ||
      img.image.size() < static_cast<size_t>(img.width) * img.height * img.component * bytes)
    return r.Corrupt("image " + std::to_string(t.source) + " (" + img.uri + img.mimeType +
                     ") could not be decoded");
  GltfTexture tex;
  tex.image = ImageRgb8(img.width, img.height, 3, 0);
  for (size_t i = 0; i < static_cast<size_t>(img.width) * img.height; ++i) {
    for (int c = 0; c < 3; ++c) {
      const int src = img.component >= 3 ? c : 0;  // grey (+ alpha) images: replicated
      const size_t at = (i * img.component + src) * bytes;
      if (bytes == 2) {  // stb decodes 16-bit images in native byte order
        uint16_t v;
        std::memcpy(&v, &img.image[at], 2);
        tex.image.data[i * 3 + c] = static_cast<uint8_t>((v + 128) / 257);
      } else {
        tex.image.data[i * 3 + c] = img.image[at];
      }
    }
  }
  const auto wrap = [&](int mode) -> Expected<TextureWrap> {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_REPEAT:
        return TextureWrap::kRepeat;
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
        return TextureWrap::kClampToEdge;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
        return TextureWrap::kMirroredRepeat;
      default:
        return r.Corrupt("texture sampler has an unknown wrap mode " + std::to_string(mode));
    }
  };
  if (t.sampler >= 0) {
    if (t.sampler >= static_cast<int>(m.samplers.size()))
      return r.Corrupt("texture " + std::to_string(texture_index) + " refers to sampler " +
                       std::to_string(t.sampler) + " which does not exist");
    Expected<TextureWrap> u = wrap(m.samplers[t.sampler].wrapS);
    if (!u.ok()) return u.error();
    Expected<TextureWrap> v = wrap(m.samplers[t.sampler].wrapT);
    if (!v.ok()) return v.error();
    tex.wrap_u = *u;
    tex.wrap_v = *v;
  }
  return tex;
}

// A sampler's interpolation and key times (increasing); its values are read per channel.
Expected<GltfAnimationSampler> ReadSamplerKeys(const Reader& r, const tinygltf::AnimationSampler& s,
                                               const std::string& sw) {
  GltfAnimationSampler out_s;
  if (s.interpolation == "LINEAR" || s.interpolation.empty())
    out_s.interpolation = AnimationInterpolation::kLinear;
  else if (s.interpolation == "STEP")
    out_s.interpolation = AnimationInterpolation::kStep;
  else if (s.interpolation == "CUBICSPLINE")
    return r.Unsupported(sw +
                         " uses CUBICSPLINE interpolation, which is not read; "
                         "re-export the animation with linear interpolation");
  else
    return r.Corrupt(sw + " has an unknown interpolation '" + s.interpolation + "'");
  Expected<Reader::Values> in = r.Read(s.input, sw + " input", {TINYGLTF_TYPE_SCALAR}, kFloat);
  if (!in.ok()) return in.error();
  if (in->count == 0) return r.Corrupt(sw + " has no key times");
  if (!AllFinite(in->v)) return r.Corrupt(sw + " has a key time that is not finite");
  for (size_t k = 1; k < in->count; ++k)
    if (in->v[k] < in->v[k - 1])
      return r.Corrupt(sw + " has key times that decrease (key " + std::to_string(k) + ")");
  out_s.times = in->v;
  return out_s;
}

Status ReadAnimations(const Reader& r, GltfSkinModel* out) {
  const tinygltf::Model& m = r.model();
  int ignored_channels = 0;
  for (size_t a = 0; a < m.animations.size(); ++a) {
    const tinygltf::Animation& src = m.animations[a];
    const std::string what =
        "animation " + std::to_string(a) + (src.name.empty() ? "" : " '" + src.name + "'");
    GltfAnimation anim;
    anim.name = src.name;
    std::vector<int> sampler_of(src.samplers.size(), -1);  // source sampler -> ours
    for (size_t c = 0; c < src.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = src.channels[c];
      const std::string cw = what + " channel " + std::to_string(c);
      AnimationPath path;
      if (ch.target_path == "translation")
        path = AnimationPath::kTranslation;
      else if (ch.target_path == "rotation")
        path = AnimationPath::kRotation;
      else if (ch.target_path == "scale")
        path = AnimationPath::kScale;
      else {
        ++ignored_channels;  // morph target weights or an extension's path
        continue;
      }
      if (ch.target_node < 0 || ch.target_node >= static_cast<int>(out->nodes.size()))
        return r.Corrupt(cw + " targets node " + std::to_string(ch.target_node) +
                         " which does not exist");
      if (!m.nodes[ch.target_node].matrix.empty())
        return r.Corrupt(cw + " animates node " + std::to_string(ch.target_node) +
                         " which has a matrix (glTF allows animating TRS nodes only)");
      if (ch.sampler < 0 || ch.sampler >= static_cast<int>(src.samplers.size()))
        return r.Corrupt(cw + " refers to sampler " + std::to_string(ch.sampler) +
                         " which does not exist");
      if (sampler_of[ch.sampler] < 0) {
        Expected<GltfAnimationSampler> keys = ReadSamplerKeys(
            r, src.samplers[ch.sampler], what + " sampler " + std::to_string(ch.sampler));
        if (!keys.ok()) return keys.error();
        sampler_of[ch.sampler] = static_cast<int>(anim.samplers.size());
        anim.samplers.push_back(std::move(keys).value());
      }
      GltfAnimationSampler& s = anim.samplers[sampler_of[ch.sampler]];
      const tinygltf::AnimationSampler& ss = src.samplers[ch.sampler];
      const bool rotation = path == AnimationPath::kRotation;
      Expected<Reader::Values> values =
          r.Read(ss.output, what + " sampler " + std::to_string(ch.sampler) + " output",
                 {rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3},
                 rotation ? kFloatOrNormalized : kFloat);
      if (!values.ok()) return values.error();
      if (values->count != s.times.size())
        return r.Corrupt(cw + ": its sampler has " + std::to_string(s.times.size()) +
                         " key times but " + std::to_string(values->count) + " values");
      if (!AllFinite(values->v)) return r.Corrupt(cw + " has a value that is not finite");
      if (!s.values.empty() && s.values.size() != values->count)
        return r.Corrupt(cw + " shares its sampler with a channel of another kind");
      s.values.resize(values->count);
      for (size_t k = 0; k < values->count; ++k) {
        Vector4d v = Vector4d::Zero();
        for (int c = 0; c < values->components; ++c) v[c] = values->at(k, c);
        if (rotation) {
          if (!(v.norm() > 1e-9))
            return r.Corrupt(cw + " key " + std::to_string(k) + " is a zero quaternion");
          v.normalize();
        }
        s.values[k] = v;
      }
      anim.duration_s = std::max(anim.duration_s, s.times.back());
      anim.channels.push_back({ch.target_node, path, sampler_of[ch.sampler]});
    }
    out->animations.push_back(std::move(anim));
  }
  if (ignored_channels > 0)
    out->warnings.push_back(std::to_string(ignored_channels) +
                            " animation channels that drive morph target weights or an "
                            "extension's property were ignored");
  return {};
}

Status ReadNodes(const Reader& r, GltfSkinModel* out) {
  const tinygltf::Model& m = r.model();
  const int count = static_cast<int>(m.nodes.size());
  out->nodes.resize(count);
  for (int i = 0; i < count; ++i) {
    const tinygltf::Node& n = m.nodes[i];
    GltfNode& node = out->nodes[i];
    node.name = n.name;
    const std::string what =
        "node " + std::to_string(i) + (n.name.empty() ? "" : " '" + n.name + "'");
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) return r.Corrupt(what + " has a matrix without 16 values");
      std::optional<NodeTransform> t = Decompose(n.matrix);
      if (!t)
        return r.Corrupt(what +
                         "'s matrix is not a translation, rotation and scale (it shears, "
                         "is singular or not finite)");
      node.rest = *t;
    } else {
      if ((!n.translation.empty() && n.translation.size() != 3) ||
          (!n.rotation.empty() && n.rotation.size() != 4) ||
          (!n.scale.empty() && n.scale.size() != 3) || !AllFinite(n.translation) ||
          !AllFinite(n.rotation) || !AllFinite(n.scale))
        return r.Corrupt(what + " has a malformed translation, rotation or scale");
      if (!n.translation.empty())
        node.rest.translation = Vector3d(n.translation[0], n.translation[1], n.translation[2]);
      if (!n.rotation.empty()) {
        const Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        if (!(q.norm() > 1e-9)) return r.Corrupt(what + " has a zero rotation quaternion");
        node.rest.rotation = q.normalized();
      }
      if (!n.scale.empty()) node.rest.scale = Vector3d(n.scale[0], n.scale[1], n.scale[2]);
    }
    for (int c : n.children) {
      if (c < 0 || c >= count)
        return r.Corrupt(what + " has child " + std::to_string(c) + " which does not exist");
      if (out->nodes[c].parent >= 0 || c == i)
        return r.Corrupt("node " + std::to_string(c) +
                         " has more than one parent; the node hierarchy must be a tree");
      out->nodes[c].parent = i;
      node.children.push_back(c);
    }
  }
  // Every node must be reachable from a root: otherwise the parent links form a cycle.
  std::vector<bool> seen(count, false);
  std::vector<int> stack;
  for (int i = 0; i < count; ++i)
    if (out->nodes[i].parent < 0) stack.push_back(i);
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    seen[i] = true;
    for (int c : out->nodes[i].children) stack.push_back(c);
  }
  for (int i = 0; i < count; ++i)
    if (!seen[i])
      return r.Corrupt("node " + std::to_string(i) +
                       " is part of a cycle; the node hierarchy must be a tree");
  return {};
}

// The first node with a mesh and a skin (out->mesh_node); other meshes are counted in a warning.
Status FindSkinnedMesh(const Reader& r, GltfSkinModel* out) {
  const tinygltf::Model& m = r.model();
  int other_meshes = 0;
  for (int i = 0; i < static_cast<int>(m.nodes.size()); ++i) {
    if (m.nodes[i].mesh < 0) continue;
    if (m.nodes[i].mesh >= static_cast<int>(m.meshes.size()))
      return r.Corrupt("node " + std::to_string(i) + " refers to mesh " +
                       std::to_string(m.nodes[i].mesh) + " which does not exist");
    if (m.nodes[i].skin >= 0 && out->mesh_node < 0)
      out->mesh_node = i;
    else
      ++other_meshes;
  }
  if (m.meshes.empty()) return r.Unsupported("the file has no mesh; a skinned body mesh is needed");
  if (out->mesh_node < 0)
    return r.Unsupported("no node has both a mesh and a skin: the file has no skinned mesh");
  if (other_meshes > 0)
    out->warnings.push_back(std::to_string(other_meshes) +
                            " other mesh nodes were ignored (only the first skinned mesh is read)");
  return {};
}

// The skin of the mesh node: its joint nodes and inverse bind matrices.
Status ReadSkin(const Reader& r, GltfSkinModel* out) {
  const tinygltf::Model& m = r.model();
  const tinygltf::Node& mesh_node = m.nodes[out->mesh_node];
  if (mesh_node.skin >= static_cast<int>(m.skins.size()))
    return r.Corrupt("node " + std::to_string(out->mesh_node) + " refers to skin " +
                     std::to_string(mesh_node.skin) + " which does not exist");
  const tinygltf::Skin& skin = m.skins[mesh_node.skin];
  if (skin.joints.empty())
    return r.Corrupt("skin " + std::to_string(mesh_node.skin) + " has no joints");
  for (int j : skin.joints) {
    if (j < 0 || j >= static_cast<int>(out->nodes.size()))
      return r.Corrupt("skin " + std::to_string(mesh_node.skin) + " names joint node " +
                       std::to_string(j) + " which does not exist");
    out->joint_nodes.push_back(j);
  }
  const int joint_count = static_cast<int>(out->joint_nodes.size());
  if (skin.inverseBindMatrices >= 0) {
    Expected<Reader::Values> ibm = r.Read(skin.inverseBindMatrices, "skin inverse bind matrices",
                                          {TINYGLTF_TYPE_MAT4}, kFloat);
    if (!ibm.ok()) return ibm.error();
    if (ibm->count != out->joint_nodes.size())
      return r.Corrupt("the skin has " + std::to_string(joint_count) + " joints but " +
                       std::to_string(ibm->count) + " inverse bind matrices");
    for (size_t k = 0; k < ibm->count; ++k) {
      Eigen::Matrix4d a;
      for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) a(row, c) = ibm->at(k, c * 4 + row);
      if (!a.allFinite() || std::abs(a.block<3, 3>(0, 0).determinant()) < 1e-12)
        return r.Corrupt("inverse bind matrix " + std::to_string(k) + " is singular or not finite");
      out->inverse_bind.emplace_back(a);
    }
  } else {
    out->inverse_bind.assign(joint_count, Eigen::Affine3d::Identity());
  }

  return {};
}

// The mesh's one material: double-sidedness, base colour factor and texture; *texcoord_set:
// the texture's coordinate set (-1 without a texture).
Status ReadMaterial(const Reader& r, const tinygltf::Mesh& mesh, int mesh_index, GltfSkinModel* out,
                    int* texcoord_set) {
  const tinygltf::Model& m = r.model();
  if (mesh.primitives.empty())
    return r.Corrupt("mesh " + std::to_string(mesh_index) + " has no primitives");
  const int material = mesh.primitives[0].material;
  for (const tinygltf::Primitive& p : mesh.primitives)
    if (p.material != material)
      return r.Unsupported(
          "the skinned mesh's primitives use different materials; merge them "
          "into one textured material");
  if (material >= static_cast<int>(m.materials.size()))
    return r.Corrupt("the skinned mesh refers to material " + std::to_string(material) +
                     " which does not exist");
  if (material >= 0) {
    const tinygltf::Material& mat = m.materials[material];
    out->double_sided = mat.doubleSided;
    const std::vector<double>& f = mat.pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4 || !AllFinite(f))
      return r.Corrupt("material " + std::to_string(material) + " has a malformed baseColorFactor");
    out->base_color_factor = Vector4d(f[0], f[1], f[2], f[3]).cwiseMax(0.0).cwiseMin(1.0);
    const tinygltf::TextureInfo& info = mat.pbrMetallicRoughness.baseColorTexture;
    if (info.index >= 0) {
      Expected<GltfTexture> tex = ReadTexture(r, info.index);
      if (!tex.ok()) return tex.error();
      out->base_color_texture = std::move(tex).value();
      *texcoord_set = std::max(info.texCoord, 0);
    }
  }
  if (out->base_color_texture.image.empty()) {
    const Vector4d& f = out->base_color_factor;
    char buf[96];
    std::snprintf(buf, sizeof(buf), "(%.3f, %.3f, %.3f)", f[0], f[1], f[2]);
    out->warnings.push_back(std::string("no base colour texture: the body is drawn in the ") +
                            (material >= 0 ? "material's base colour factor " : "default white ") +
                            buf);
  }

  return {};
}

// Every primitive's vertices and triangles, normals computed where the mesh has none, and the
// warnings of what was adjusted or ignored.
Status ReadGeometry(const Reader& r, const tinygltf::Mesh& mesh, int mesh_index, int texcoord_set,
                    GltfSkinModel* out) {
  const int joint_count = static_cast<int>(out->joint_nodes.size());
  int normalised = 0, extra_influences = 0, morph = 0;
  bool generated_normals = false;
  for (size_t k = 0; k < mesh.primitives.size(); ++k) {
    const std::string what =
        "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(k);
    if (!mesh.primitives[k].targets.empty()) ++morph;
    Status s = ReadPrimitive(r, mesh.primitives[k], what, texcoord_set, joint_count, out,
                             &normalised, &extra_influences, &generated_normals);
    if (!s.ok()) return s.error();
  }
  if (out->triangles.empty()) return r.Corrupt("the skinned mesh has no triangles");
  if (generated_normals) {
    std::vector<Vector3d> acc(out->vertices.size(), Vector3d::Zero());
    for (const Eigen::Vector3i& t : out->triangles) {
      const Vector3d n = TriangleNormal(out->vertices, t);  // length = 2 x area
      for (int c = 0; c < 3; ++c) acc[t[c]] += n;
    }
    for (size_t i = 0; i < acc.size(); ++i)
      if (acc[i].norm() > 0) out->vertices[i].normal = acc[i].normalized();
    out->warnings.push_back("the mesh has no normals: area-weighted vertex normals were computed");
  }
  if (normalised > 0)
    out->warnings.push_back(
        std::to_string(normalised) +
        " vertices had skin weights that do not sum to 1; they were normalised");
  if (extra_influences > 0)
    out->warnings.push_back(std::to_string(extra_influences) +
                            " vertices had more than 4 joint influences; the 4 largest were kept");
  if (morph > 0) out->warnings.push_back("morph targets were ignored");

  return {};
}

Expected<GltfSkinModel> Convert(const tinygltf::Model& m, const std::string& path) {
  const Reader r(m, path);
  GltfSkinModel out;
  out.path = path;
  if (m.asset.version.empty() || m.asset.version[0] != '2')
    return r.Unsupported("glTF version '" + m.asset.version + "' is not read; only glTF 2.x");
  Status nodes = ReadNodes(r, &out);
  if (!nodes.ok()) return nodes.error();
  if (Status s = FindSkinnedMesh(r, &out); !s.ok()) return s.error();
  if (Status s = ReadSkin(r, &out); !s.ok()) return s.error();
  const int mesh_index = m.nodes[out.mesh_node].mesh;
  const tinygltf::Mesh& mesh = m.meshes[mesh_index];
  int texcoord_set = -1;
  if (Status s = ReadMaterial(r, mesh, mesh_index, &out, &texcoord_set); !s.ok()) return s.error();
  if (Status s = ReadGeometry(r, mesh, mesh_index, texcoord_set, &out); !s.ok()) return s.error();
  Status anims = ReadAnimations(r, &out);
  if (!anims.ok()) return anims.error();
  return out;
}

Eigen::Quaterniond ToQuaternion(const Vector4d& v) {
  return Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
}

double WrapCoordinate(double x, TextureWrap wrap, int size) {
  // x in texel units, texel centres at k + 0.5.
  switch (wrap) {
    case TextureWrap::kRepeat:
      return x - size * std::floor(x / size);
    case TextureWrap::kMirroredRepeat: {
      const double period = 2.0 * size;
      double m = x - period * std::floor(x / period);
      return m < size ? m : period - m;
    }
    case TextureWrap::kClampToEdge:
      return std::clamp(x, 0.5, size - 0.5);
  }
  return x;
}

}  // namespace

Eigen::Affine3d NodeTransform::Matrix() const {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.translate(translation);
  a.rotate(rotation.normalized());
  a.scale(scale);
  return a;
}

std::vector<std::string> GltfSkinModel::JointNames() const {
  std::vector<std::string> names;
  for (int n : joint_nodes) names.push_back(nodes[n].name);
  return names;
}

Expected<GltfSkinModel> LoadGltfSkin(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return MakeError("not_found", path + ": no such glTF file");
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {0, 0, 0, 0};
  in.read(magic, 4);
  if (!in && in.gcount() == 0 && std::filesystem::file_size(path, ec) > 0)
    return MakeError("io", path + ": cannot read the file");
  const bool binary = in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    std::string message = err.empty() ? warn : err;
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return MakeError("corrupt", path + ": not a readable glTF 2.0 " +
                                    std::string(binary ? "binary (.glb)" : "JSON (.gltf)") +
                                    " file (" + message + ")");
  }
  return Convert(model, path);
}

std::vector<NodeTransform> RestTransforms(const GltfSkinModel& model) {
  std::vector<NodeTransform> out;
  out.reserve(model.nodes.size());
  for (const GltfNode& n : model.nodes) out.push_back(n.rest);
  return out;
}

std::vector<NodeTransform> SampleAnimation(const GltfSkinModel& model, int animation, double t_s,
                                           bool loop) {
  REENACT_CHECK(animation >= 0 && animation < static_cast<int>(model.animations.size()),
                "animation " + std::to_string(animation) + " out of range");
  REENACT_CHECK(std::isfinite(t_s), "animation time must be finite");
  const GltfAnimation& a = model.animations[animation];
  if (loop && a.duration_s > 0) t_s -= a.duration_s * std::floor(t_s / a.duration_s);
  std::vector<NodeTransform> out = RestTransforms(model);
  for (const GltfAnimationChannel& ch : a.channels) {
    const GltfAnimationSampler& s = a.samplers[ch.sampler];
    const std::vector<double>& t = s.times;
    Vector4d value;
    bool rotation = ch.path == AnimationPath::kRotation;
    if (t_s <= t.front()) {
      value = s.values.front();
    } else if (t_s >= t.back()) {
      value = s.values.back();
    } else {
      const size_t k1 = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), t_s) - t.begin());
      const size_t k0 = k1 - 1;
      const double span = t[k1] - t[k0];
      const double u = span > 0 ? (t_s - t[k0]) / span : 0.0;
      if (s.interpolation == AnimationInterpolation::kStep) {
        value = s.values[k0];
      } else if (rotation) {
        const Eigen::Quaterniond q =
            ToQuaternion(s.values[k0]).slerp(u, ToQuaternion(s.values[k1]));
        value = Vector4d(q.x(), q.y(), q.z(), q.w());
      } else {
        value = (1 - u) * s.values[k0] + u * s.values[k1];
      }
    }
    NodeTransform& n = out[ch.node];
    switch (ch.path) {
      case AnimationPath::kTranslation:
        n.translation = value.head<3>();
        break;
      case AnimationPath::kRotation:
        n.rotation = ToQuaternion(value).normalized();
        break;
      case AnimationPath::kScale:
        n.scale = value.head<3>();
        break;
    }
  }
  return out;
}

std::vector<Eigen::Affine3d> SceneFromNode(const GltfSkinModel& model,
                                           const std::vector<NodeTransform>& local) {
  REENACT_CHECK(local.size() == model.nodes.size(), "one local transform per node is needed");
  std::vector<Eigen::Affine3d> out(model.nodes.size(), Eigen::Affine3d::Identity());
  std::vector<int> stack;
  for (int i = 0; i < static_cast<int>(model.nodes.size()); ++i)
    if (model.nodes[i].parent < 0) stack.push_back(i);
  while (!stack.empty()) {  // the hierarchy is a tree (checked when loading)
    const int i = stack.back();
    stack.pop_back();
    const int p = model.nodes[i].parent;
    out[i] = (p < 0 ? Eigen::Affine3d::Identity() : out[p]) * local[i].Matrix();
    for (int c : model.nodes[i].children) stack.push_back(c);
  }
  return out;
}

std::vector<NodeTransform> BindTransforms(const GltfSkinModel& model) {
  std::vector<NodeTransform> local = RestTransforms(model);
  const Eigen::Affine3d scene_from_mesh = model.mesh_node >= 0
                                              ? SceneFromNode(model, local)[model.mesh_node]
                                              : Eigen::Affine3d::Identity();
  std::vector<int> joint_of(model.nodes.size(), -1);
  for (size_t j = 0; j < model.joint_nodes.size(); ++j)
    joint_of[model.joint_nodes[j]] = static_cast<int>(j);
  std::vector<Eigen::Affine3d> scene(model.nodes.size(), Eigen::Affine3d::Identity());
  std::vector<int> stack;
  for (int i = 0; i < static_cast<int>(model.nodes.size()); ++i)
    if (model.nodes[i].parent < 0) stack.push_back(i);
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    const int p = model.nodes[i].parent;
    const Eigen::Affine3d parent = p < 0 ? Eigen::Affine3d::Identity() : scene[p];
    if (joint_of[i] >= 0) {
      const Eigen::Affine3d want = scene_from_mesh * model.inverse_bind[joint_of[i]].inverse();
      const Eigen::Matrix4d l = (parent.inverse() * want).matrix();
      std::vector<double> cm(16);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) cm[c * 4 + r] = l(r, c);
      std::optional<NodeTransform> t = Decompose(cm);
      if (t) local[i] = *t;  // a bind pose with shear keeps the rest transform
    }
    scene[i] = parent * local[i].Matrix();
    for (int c : model.nodes[i].children) stack.push_back(c);
  }
  return local;
}

Eigen::Vector3d SampleBaseColor(const GltfSkinModel& model, const Eigen::Vector2d& uv) {
  const Vector3d factor = model.base_color_factor.head<3>();
  const GltfTexture& tex = model.base_color_texture;
  if (tex.image.empty() || !uv.allFinite()) return factor;
  const int w = tex.image.width, h = tex.image.height;
  // Continuous texel coordinates with texel centres at k + 0.5, wrapped, then bilinear
  // between the centres around them (neighbours wrapped the same way).
  const double x = WrapCoordinate(uv.x() * w, tex.wrap_u, w) - 0.5;
  const double y = WrapCoordinate(uv.y() * h, tex.wrap_v, h) - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  const auto texel = [&](int i, int j) {
    const auto wrap_index = [](int k, int n, TextureWrap mode) {
      if (mode == TextureWrap::kClampToEdge) return std::clamp(k, 0, n - 1);
      if (mode == TextureWrap::kMirroredRepeat) {
        const int period = 2 * n;
        int m = ((k % period) + period) % period;
        return m < n ? m : period - 1 - m;
      }
      return ((k % n) + n) % n;
    };
    const int xi = wrap_index(i, w, tex.wrap_u), yi = wrap_index(j, h, tex.wrap_v);
    return Vector3d(tex.image.at(xi, yi, 0), tex.image.at(xi, yi, 1), tex.image.at(xi, yi, 2));
  };
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const Vector3d c = (1 - ay) * ((1 - ax) * texel(x0, y0) + ax * texel(x0 + 1, y0)) +
                     ay * ((1 - ax) * texel(x0, y0 + 1) + ax * texel(x0 + 1, y0 + 1));
  return c.cwiseProduct(factor) / 255.0;
}

}  // namespace reenact::capture
