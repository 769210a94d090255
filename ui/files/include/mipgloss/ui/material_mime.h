// Dragging a library material (the library dock) onto an object (the viewport, the scene list):
// the entry travels as a one-entry library file (library_file.h) under its own MIME type, so a
// drop carries the parameters themselves, not a reference into a library that may change.
#pragma once

#include "mipgloss/scene/library.h"

#include <optional>

class QMimeData;

namespace mipgloss::ui {

inline constexpr const char* kMaterialMimeType = "application/x-mipgloss-material";

QMimeData* materialMimeData(const LibraryMaterial& entry);  // the caller (Qt's drag) owns it
// The entry a drop carries; nothing when the data has no valid entry.
std::optional<LibraryMaterial> materialFromMimeData(const QMimeData* mime);

}  // namespace mipgloss::ui
