#pragma once
// The unit cylinder mesh the renderer instances for every body part lives in common/ so
// that the CPU reference renderer draws the very same triangles; see
// common/render/cylinder_mesh.h for its definition.

#include "common/render/cylinder_mesh.h"

namespace reenact::viewer {

using reenact::CylinderMesh;
using reenact::MakeUnitCylinderMesh;

}  // namespace reenact::viewer
