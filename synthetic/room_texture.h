#pragma once
// Procedural albedo of the synthetic room's surfaces, as functions of surface coordinates
// (u, v) in metres: u to the right and v up as seen by someone facing the surface (on the
// floor u = world x, v = world y). Rich in corners and varied contrast so that ORB-style
// features find plenty to hold on to.

#include "synthetic/procedural.h"

namespace reenact::capture {

enum class RoomMaterial {
  kFloorPlanks,  // wooden planks with a patterned rug
  kPlasterWall,  // painted plaster, picture frames, a clock
  kBrickWall,    // bricks and mortar with a poster
  kWallpaper,    // damask-like wallpaper, a whiteboard with scribbles and a door
  kPaintedWall,  // blue-grey paint, a map-like poster and a door
  kCeiling,      // white with a light panel
  kBookshelf,    // front of a bookshelf: shelves of coloured book spines
  kWood,         // plain wood (sides and tops of furniture)
  kCabinet,      // drawers with handles
  kCardboard,    // a cardboard box with tape and a printed label
  kTablecloth,   // gingham
};

// Albedo at (u, v) of a surface of the given material and size (metres).
Color RoomAlbedo(RoomMaterial material, double u, double v, double width, double height);

}  // namespace reenact::capture
