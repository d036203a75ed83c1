#include "viewer-client/play/texturing_presets.h"

#include <array>
#include <utility>

namespace reenact::viewer {
namespace {

// Ranked candidates per part of the visible modes.
constexpr int kRankedCandidates = 3;

constexpr std::array<std::pair<std::string_view, TexturingOptions>, 9> kPresets = {{
    {"thesis", {}},
    {"per-part", {.selection = TextureSelection::kPerPart}},
    {"occlusion",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kFirstVisible,
      .candidates = kRankedCandidates}},
    {"blend",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .hysteresis = 0.1}},
    {"shape",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kExtended}},
    {"profile",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kProfiled}},
    {"relit",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kProfiled,
      .relight = true}},
    {"fallback",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .fallback_candidates = kMaxTextureCandidates - kRankedCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kProfiled,
      .relight = true}},
    {"surface",
     {.selection = TextureSelection::kPerPart,
      .mode = TexturingMode::kBlendVisible,
      .candidates = kRankedCandidates,
      .fallback_candidates = kMaxTextureCandidates - kRankedCandidates,
      .hysteresis = 0.1,
      .shape = BodyShape::kSurface,
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
