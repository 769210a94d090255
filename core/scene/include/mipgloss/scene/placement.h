// Where mipgloss puts an object when it places one (never where the user has moved it): every
// placement rule, in one place. Pure functions of the meshes' bounds and the scene.
#pragma once

#include "mipgloss/scene/scene.h"

namespace mipgloss {

// Figure 1's row: copy i of `count` of a mesh with bounds `b`, spaced by 1.15 × its width along x,
// the row centred on the origin.
Transform inCentredRow(const Bounds& b, int i, int count);

// A row along +x, each object after the last (`mipgloss render --mesh`): its bounds' centre on the
// x axis, the first touching the origin, a gap of 0.2 of each one's bounding radius after it.
// `cursor` is where the row has got to (0 for the first); it moves past the placed object and gap.
Transform nextInRow(const Bounds& b, float& cursor);

// A square grid of `count` equal objects in the xy plane (`mipgloss bench-render --objects`),
// 2.3 bounding radii apart, copy 0 at the origin.
Transform inGrid(const Bounds& b, int i, int count);

// An imported mesh (the window's File → Import):
//   - size: R = the median world radius of the visible objects. A mesh whose radius r is more than
//     4× larger or smaller than R is scaled by R / r (so a 0.2-unit scan and a 120-unit one both
//     sit beside teapots); otherwise it keeps its own size. With no visible objects it keeps it.
//   - place: to the right (+x) of the visible scene's bounds with a gap of 0.2 R (0.2 r when
//     alone), its centre at the height and depth of the bounds' centre.
Transform besideScene(const Scene& scene, const Mesh& mesh);

// A duplicate: the original's placement moved along +x by 1.2 of its world bounding diameter, so
// the two never overlap.
Transform besideOriginal(const SceneObject& original);

}  // namespace mipgloss
