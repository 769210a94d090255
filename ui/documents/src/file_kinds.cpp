#include "mipgloss/ui/file_kinds.h"

#include "mipgloss/assets/asset.h"

#include <QFileInfo>

namespace mipgloss::ui {

QStringList suffixesOf(FileKind kind) {
    switch (kind) {
        // .mipgloss first: what scenes are saved as; .json is what older versions saved.
        case FileKind::Scene: return {QString::fromLatin1(kSceneSuffix), QStringLiteral("json")};
        case FileKind::Library: return {QStringLiteral("mglib")};
        case FileKind::Mesh: {
            QStringList out;
            for (const char* ext : importExtensions()) out << QString::fromLatin1(ext + 1);  // ext is ".obj"
            return out;
        }
        // Image formats the environment import reads (OpenImageIO).
        case FileKind::Environment:
            return {QStringLiteral("exr"), QStringLiteral("hdr"),  QStringLiteral("png"),  QStringLiteral("jpg"),
                    QStringLiteral("jpeg"), QStringLiteral("tif"), QStringLiteral("tiff"), QStringLiteral("pfm")};
        case FileKind::Unknown: break;
    }
    return {};
}

FileKind fileKindOf(const QString& path) {
    const QFileInfo info(path);
    if (info.isDir()) return FileKind::Environment;
    const QString suffix = info.suffix().toLower();
    if (suffix.isEmpty()) return FileKind::Unknown;
    // Scenes before meshes and environments: no suffix is two kinds, but the order is the one the
    // window always had.
    for (FileKind kind : {FileKind::Scene, FileKind::Library, FileKind::Mesh, FileKind::Environment})
        if (suffixesOf(kind).contains(suffix)) return kind;
    return FileKind::Unknown;
}

FilesByKind sortByKind(const QStringList& paths) {
    FilesByKind sorted;
    for (const QString& path : paths) {
        switch (fileKindOf(path)) {
            case FileKind::Scene: if (sorted.scene.isEmpty()) sorted.scene = path; break;
            case FileKind::Library: sorted.libraries << path; break;
            case FileKind::Mesh: sorted.meshes << path; break;
            case FileKind::Environment: sorted.environment = path; break;
            case FileKind::Unknown: sorted.unknown << path; break;
        }
    }
    return sorted;
}

QString dialogPatternsOf(FileKind kind) {
    QStringList patterns;
    for (const QString& suffix : suffixesOf(kind)) patterns << QStringLiteral("*.") + suffix;
    return patterns.join(QLatin1Char(' '));
}

QString withSuffix(QString path, const QString& suffix) {
    if (!path.isEmpty() && QFileInfo(path).suffix().isEmpty()) path += QLatin1Char('.') + suffix;
    return path;
}

}  // namespace mipgloss::ui
