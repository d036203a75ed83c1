#include "proto/clip/map_codec.h"

#include <cmath>
#include <limits>
#include <string>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/expert_encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/point_cloud/point_cloud.h>
#include <draco/point_cloud/point_cloud_builder.h>

#include "common/error/check.h"
#include "proto/clip/byte_io.h"

namespace reenact::proto {
namespace {

using internal::ByteReader;
using internal::ByteWriter;

constexpr char kMagic[4] = {'R', 'M', 'A', 'P'};
constexpr size_t kDescriptorBytes = 32;

Error Corrupt(const std::string& message) { return MakeError("corrupt", "map: " + message); }

// The float32 cube side handed to Draco: at least extent, and positive.
float QuantizationRange(double extent) {
  if (!(extent > 0)) return 1.0f;
  return std::nextafter(static_cast<float>(extent), std::numeric_limits<float>::infinity());
}

Expected<std::vector<uint8_t>> DracoEncode(const ClipMap& map, const Eigen::Vector3d& origin,
                                           double extent, const MapCodecOptions& options) {
  const auto n = static_cast<draco::PointIndex::ValueType>(map.points.size());
  draco::PointCloudBuilder builder;
  builder.Start(n);
  const int att = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (draco::PointIndex::ValueType i = 0; i < n; ++i) {
    const Eigen::Vector3f offset = (map.points[i].position_in_world - origin).cast<float>();
    builder.SetAttributeValueForPoint(att, draco::PointIndex(i), offset.data());
  }
  const std::unique_ptr<draco::PointCloud> cloud = builder.Finalize(/*deduplicate_points=*/false);
  if (!cloud) return MakeError("internal", "map: Draco could not build the point cloud");

  draco::ExpertEncoder encoder(*cloud);
  encoder.SetEncodingMethod(draco::POINT_CLOUD_SEQUENTIAL_ENCODING);
  encoder.SetSpeedOptions(options.draco_speed, options.draco_speed);
  const float zero[3] = {0, 0, 0};
  encoder.SetAttributeExplicitQuantization(att, options.position_quantization_bits, 3, zero,
                                           QuantizationRange(extent));
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeToBuffer(&buffer);
  if (!status.ok())
    return MakeError("internal", std::string("map: Draco encoding failed: ") + status.error_msg());
  return std::vector<uint8_t>(reinterpret_cast<const uint8_t*>(buffer.data()),
                              reinterpret_cast<const uint8_t*>(buffer.data()) + buffer.size());
}

}  // namespace

void MapCodecOptions::Check() const {
  REENACT_CHECK(position_quantization_bits >= 1 && position_quantization_bits <= 30,
                "position_quantization_bits must lie in [1, 30]");
  REENACT_CHECK(draco_speed >= 0 && draco_speed <= 10, "draco_speed must lie in [0, 10]");
}

double MapPositionErrorBound(double extent_m, int bits) {
  return extent_m / (2.0 * (std::ldexp(1.0, bits) - 1.0)) + std::ldexp(extent_m, -21);
}

Expected<std::vector<uint8_t>> EncodeMap(const ClipMap& map, const MapCodecOptions& options) {
  options.Check();
  if (map.points.size() > kMaxMapPoints)
    return MakeError("invalid_argument", "map: " + std::to_string(map.points.size()) +
                                             " points exceed the limit of " +
                                             std::to_string(kMaxMapPoints));
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < map.points.size(); ++i) {
    const Eigen::Vector3d& p = map.points[i].position_in_world;
    if (!p.allFinite())
      return MakeError("invalid_argument",
                       "map: point " + std::to_string(i) + " has a non-finite position");
    lo = i == 0 ? p : Eigen::Vector3d(lo.cwiseMin(p));
    hi = i == 0 ? p : Eigen::Vector3d(hi.cwiseMax(p));
  }
  const double extent = (hi - lo).maxCoeff();
  if (extent > kMaxMapExtentM)
    return MakeError("invalid_argument", "map: points span " + std::to_string(extent) +
                                             " m, more than the limit of " +
                                             std::to_string(kMaxMapExtentM) + " m");

  std::vector<uint8_t> draco_bytes;
  if (!map.points.empty()) {
    auto encoded = DracoEncode(map, lo, extent, options);
    if (!encoded) return encoded.error();
    draco_bytes = std::move(encoded).value();
  }

  ByteWriter out;
  out.Bytes(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(kMagic), 4));
  out.U32(kMapFormatVersion);
  out.U32(static_cast<uint32_t>(map.points.size()));
  out.U32(static_cast<uint32_t>(options.position_quantization_bits));
  for (int k = 0; k < 3; ++k) out.F64(lo[k]);
  out.U64(draco_bytes.size());
  out.Bytes(draco_bytes);
  for (const MapPoint& p : map.points) out.Bytes(p.descriptor);
  for (const MapPoint& p : map.points) out.U32(p.observations);
  return std::move(out.bytes());
}

Expected<ClipMap> DecodeMap(std::span<const uint8_t> bytes) {
  ByteReader in(bytes);
  std::span<const uint8_t> magic;
  if (!in.Take(4, &magic)) return Corrupt("truncated: " + std::to_string(bytes.size()) + " bytes");
  if (!std::equal(magic.begin(), magic.end(), kMagic))
    return Corrupt("bad magic (not an RMAP map container)");
  uint32_t version = 0, count = 0, bits = 0;
  if (!in.U32(&version)) return Corrupt("truncated container header");
  if (version != kMapFormatVersion)
    return MakeError("unsupported", "map: container version " + std::to_string(version) +
                                        " is not supported (this build reads " +
                                        std::to_string(kMapFormatVersion) + ")");
  Eigen::Vector3d origin;
  uint64_t draco_length = 0;
  if (!in.U32(&count) || !in.U32(&bits) || !in.F64(&origin.x()) || !in.F64(&origin.y()) ||
      !in.F64(&origin.z()) || !in.U64(&draco_length))
    return Corrupt("truncated container header");
  if (count > kMaxMapPoints)
    return Corrupt("point count " + std::to_string(count) + " exceeds the limit");
  if (bits < 1 || bits > 30) return Corrupt("quantisation bits " + std::to_string(bits) + " outside [1, 30]");
  if (!origin.allFinite()) return Corrupt("non-finite origin");
  if ((count == 0) != (draco_length == 0))
    return Corrupt("Draco stream length " + std::to_string(draco_length) + " disagrees with " +
                   std::to_string(count) + " points");
  // Checked in 64 bits before anything is allocated: the rest must hold exactly this much.
  const uint64_t expected = draco_length + uint64_t{count} * (kDescriptorBytes + 4);
  if (draco_length > in.remaining() || expected != in.remaining())
    return Corrupt("size " + std::to_string(bytes.size()) + " bytes disagrees with " +
                   std::to_string(count) + " points and a " + std::to_string(draco_length) +
                   "-byte Draco stream (truncated or trailing bytes)");

  std::span<const uint8_t> draco_bytes, descriptors;
  in.Take(draco_length, &draco_bytes);
  in.Take(uint64_t{count} * kDescriptorBytes, &descriptors);

  ClipMap map;
  map.points.resize(count);
  if (count > 0) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(draco_bytes.data()), draco_bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
    if (!decoded.ok())
      return Corrupt(std::string("Draco stream does not decode: ") + decoded.status().error_msg());
    const std::unique_ptr<draco::PointCloud> cloud = std::move(decoded).value();
    const draco::PointAttribute* att =
        cloud ? cloud->GetNamedAttribute(draco::GeometryAttribute::POSITION) : nullptr;
    if (!att || cloud->num_points() != count || att->num_components() != 3)
      return Corrupt("Draco stream does not hold " + std::to_string(count) + " 3D positions");
    for (uint32_t i = 0; i < count; ++i) {
      float offset[3];
      if (!att->ConvertValue<float, 3>(att->mapped_index(draco::PointIndex(i)), offset))
        return Corrupt("Draco position " + std::to_string(i) + " cannot be read");
      const Eigen::Vector3d p = origin + Eigen::Vector3f(offset[0], offset[1], offset[2]).cast<double>();
      if (!p.allFinite()) return Corrupt("position " + std::to_string(i) + " is not finite");
      map.points[i].position_in_world = p;
    }
  }
  for (uint32_t i = 0; i < count; ++i) {
    std::copy_n(descriptors.begin() + i * kDescriptorBytes, kDescriptorBytes,
                map.points[i].descriptor.begin());
    uint32_t observations = 0;
    in.U32(&observations);
    map.points[i].observations = observations;
  }
  return map;
}

}  // namespace reenact::proto
