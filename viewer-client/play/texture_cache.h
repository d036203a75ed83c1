#pragma once
// Uploads a stored frame's crop to the renderer the first time a draw needs it and remembers
// its texture index: the `texture_for_frame` of Reenactment::Build (pass std::ref(cache)).

#include <map>

#include "viewer-client/play/reenactment.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

class TextureCache {
 public:
  TextureCache(Renderer& renderer, const Reenactment& reenactment)
      : renderer_(renderer), reenactment_(reenactment) {}

  int operator()(int frame) {
    auto it = texture_of_frame_.find(frame);
    if (it == texture_of_frame_.end())
      it = texture_of_frame_.emplace(frame, renderer_.UploadTexture(reenactment_.Texture(frame)))
               .first;
    return it->second;
  }

 private:
  Renderer& renderer_;
  const Reenactment& reenactment_;
  std::map<int, int> texture_of_frame_;  // stored frame -> renderer texture index
};

}  // namespace reenact::viewer
