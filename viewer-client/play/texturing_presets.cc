#include "viewer-client/play/texturing_presets.h"

#include <array>
#include <utility>

namespace reenact::viewer {
namespace {

constexpr std::array<std::pair<std::string_view, TexturingOptions>, 7> kPresets = {{
    {"thesis", {}},
    {"per-part", {.selection = TextureSelection::kPerPart}},
    {"occlusion",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kFirstVisible,
      .candidates = kMaxTextureCandidates}},
    {"blend",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kMaxTextureCandidates,
      .hysteresis = 0.1}},
    {"shape",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kMaxTextureCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kExtended}},
    {"profile",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kMaxTextureCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kProfiled}},
    {"relit",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kMaxTextureCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kProfiled,
      .relight = true}},
}};

}  // namespace

std::string TexturingPresetNames() {
  std::string names;
  for (const auto& [name, options] : kPresets)
    names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

Expected<TexturingOptions> TexturingPreset(std::string_view name) {
  for (const auto& [preset, options] : kPresets)
    if (preset == name) return options;
  return MakeError(
      "usage", "unknown texturing '" + std::string(name) + "'; known: " + TexturingPresetNames());
}

}  // namespace reenact::viewer
