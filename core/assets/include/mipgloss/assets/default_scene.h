// The default scene as the window and `mipgloss render` open it: the paper's Figure 1 (scene.h,
// makeFigure1Scene) on the embedded Utah teapot, read from its OBJ bytes compiled into the binary.
#pragma once

#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/scene.h"

namespace mipgloss {

// The embedded Utah teapot of the default scene (resources/meshes/teapot.obj, see NOTICE.md).
Mesh defaultTeapot();

// makeFigure1Scene on defaultTeapot(), one teapot shared by the four objects.
Scene makeFigure1Scene();

}  // namespace mipgloss
