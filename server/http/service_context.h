#pragma once
// What the route handlers need: the stores, the metrics and the service's limits.

#include <cstddef>
#include <cstdint>

#include "server/http/metrics.h"
#include "server/storage/blob_store.h"
#include "server/storage/metadata_store.h"

namespace reenact::server {

struct ServiceLimits {
  // Largest manifest body, bytes; > 0. Default 1 MiB.
  size_t max_manifest_bytes = size_t{1} << 20;
  // Largest frame payload, bytes; > 0. Default 8 MiB.
  size_t max_frame_bytes = size_t{8} << 20;
  // Largest map payload, bytes; > 0. Default 64 MiB.
  size_t max_map_bytes = size_t{64} << 20;
  // Most frames one clip may declare; >= 1. Default 100000 (~55 min at 30 Hz).
  int64_t max_frame_count = 100000;
  // Page size of GET /v1/clips when no limit is given, and the largest allowed; 1 <= default
  // <= max. Defaults 20 and 100.
  int default_page_size = 20;
  int max_page_size = 100;
  // Radius of GET /v1/clips when none is given, metres; (0, kMaxNearbyRadiusM]. Default 5 km.
  double default_radius_m = 5000.0;

  void Check() const;
};

struct ServiceContext {
  MetadataStore& metadata;
  BlobStore& blobs;
  Metrics& metrics;
  ServiceLimits limits;
};

}  // namespace reenact::server
