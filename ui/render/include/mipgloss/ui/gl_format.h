// The one OpenGL surface format every context uses: 4.1 core, 24-bit depth, no default MSAA (the
// renderer multisamples its own HDR target). Set as the default before any widget exists.
#pragma once

#include <QSurfaceFormat>

namespace mipgloss::ui {

QSurfaceFormat surfaceFormat();
void setDefaultSurfaceFormat();

}  // namespace mipgloss::ui
