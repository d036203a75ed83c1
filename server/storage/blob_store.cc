#include "server/storage/blob_store.h"

#include "server/storage/metadata_store.h"

namespace reenact::server {

std::string BlobKey(const std::string& clip_id, int part_index) {
  if (part_index == kMapPart) return clip_id + "/map";
  return clip_id + "/frames/" + std::to_string(part_index);
}

}  // namespace reenact::server
