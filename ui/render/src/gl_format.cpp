#include "mipgloss/ui/gl_format.h"

namespace mipgloss::ui {

QSurfaceFormat surfaceFormat() {
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGL);
    format.setVersion(4, 1);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(24);
    format.setSamples(0);
    return format;
}

void setDefaultSurfaceFormat() { QSurfaceFormat::setDefaultFormat(surfaceFormat()); }

}  // namespace mipgloss::ui
