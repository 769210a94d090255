// File → Export image: what the view shows, drawn again at any size through the renderer (not
// grabbed from the window). A .exr file holds the linear, scene-referred picture (float RGBA,
// before exposure and tone mapping), other formats (by suffix; none: PNG) the tone-mapped one;
// both carry the objects' coverage as alpha when the background is hidden.
#pragma once

#include <QSize>
#include <QString>

class QWidget;

namespace mipgloss::ui {

class Viewport;

// A widget's size in device pixels: what "the view's size" is for an export.
QSize devicePixelSize(const QWidget& widget);

struct ExportedImage {
    QSize size;
    bool linear = false;  // a float .exr
};

// Renders the view at `size` and writes it to `path` atomically (atomic_file.h). A folder that
// cannot take the file, a size beyond OpenGL's limits or a failed render throws FileError naming
// the file and the problem (a writer's own failure may throw another std::exception), and
// nothing is written. `showBackground`: the background is drawn, so the picture is opaque.
ExportedImage exportViewImage(Viewport& viewport, const QString& path, QSize size, bool showBackground);

}  // namespace mipgloss::ui
