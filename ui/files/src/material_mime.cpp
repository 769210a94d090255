#include "mipgloss/ui/material_mime.h"

#include "mipgloss/ui/library_file.h"

#include <QMimeData>
#include <QString>

namespace mipgloss::ui {

QMimeData* materialMimeData(const LibraryMaterial& entry) {
    MaterialLibrary one;
    one.entries.push_back(entry);
    auto* mime = new QMimeData;
    mime->setData(QString::fromLatin1(kMaterialMimeType), libraryToJson(one));
    // Dropped on a text field (a search box, an editor) it reads as the material's name.
    mime->setText(QString::fromStdString(entry.name));
    return mime;
}

std::optional<LibraryMaterial> materialFromMimeData(const QMimeData* mime) {
    const QString type = QString::fromLatin1(kMaterialMimeType);
    if (!mime || !mime->hasFormat(type)) return std::nullopt;
    try {
        // The same checks as a library file (names, λ range, tint), so a drop from another
        // program, or another version of this one, cannot bring in a value a file could not.
        MaterialLibrary library = libraryFromJson(mime->data(type), "the dropped material");
        if (library.entries.size() != 1) return std::nullopt;
        return std::move(library.entries.front());
    } catch (const LibraryFileError&) {
        return std::nullopt;
    }
}

}  // namespace mipgloss::ui
