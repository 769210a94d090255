// What a file handed to the window is, told by its name alone: every way a file comes in (File →
// Open, Import mesh, drops, mipgloss-gui's command line) asks fileKindOf, so they agree.
//
//   Scene        .mipgloss, and .json, which older versions saved (scene_file.h)
//   Library      .mglib, a material library: its materials go into the user's library
//   Mesh         a mesh or an asset (mesh.h, asset.h: .obj .off .ply .stl .om .gltf .glb), imported
//                as objects
//   Environment  an image the environment import reads (.exr .hdr .png .jpg .jpeg .tif .tiff .pfm),
//                or a folder (a six-face set)
//   Unknown      anything else
//
// Extensions are compared without regard to case ("SKY.EXR" is an environment).
#pragma once

#include <QString>
#include <QStringList>

namespace mipgloss::ui {

enum class FileKind { Unknown, Scene, Library, Mesh, Environment };

// The suffix a scene is saved with (Save As adds it to a name typed without one).
inline constexpr const char* kSceneSuffix = "mipgloss";

// The kind of `path`. A folder is an environment whatever its name (the one look at the disk);
// otherwise only the name counts, so a file that does not exist yet has its kind.
FileKind fileKindOf(const QString& path);

// Files handed over together (a drop, the command line) sorted by kind. One scene is opened, the
// first given; one environment is drawn, the last given (each would replace the one before);
// every library and mesh is taken, in the order given; the rest are named in an error.
struct FilesByKind {
    QString scene;
    QString environment;
    QStringList libraries;
    QStringList meshes;
    QStringList unknown;
};
FilesByKind sortByKind(const QStringList& paths);

// The suffixes of a kind, lower case, without the dot, in the order dialogs list them (none for
// Unknown).
QStringList suffixesOf(FileKind kind);
// A file dialog's patterns for a kind: "*.exr *.hdr …".
QString dialogPatternsOf(FileKind kind);

// `path` with ".`suffix`" added when its file name has none (a name typed into a save dialog);
// an empty path (a dialog cancelled) stays empty.
QString withSuffix(QString path, const QString& suffix);

}  // namespace mipgloss::ui
