// Helpers for the tests of the scene-file session, with a window (tests/ui/widgets) and without
// (tests/ui/documents): the test's own autosave folder and recent list, scenes compared as the
// files they write, and small files.
#pragma once

#include "mipgloss/ui/autosave.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_file.h"

#include <gtest/gtest.h>

#include <QByteArray>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>
#include <QString>
#include <QTemporaryDir>

namespace mipgloss::test {

// QStandardPaths test mode, an empty autosave folder and an empty recent list.
inline void useTestFolders() {
    QStandardPaths::setTestModeEnabled(true);
    QDir(ui::Autosave::folder()).removeRecursively();
    ui::RecentFiles::clear();
}

// Two scenes are the same scene when they write the same file (meshes loaded twice are other
// pointers, and ids may differ; sceneToJson writes neither).
inline QByteArray asFile(const Scene& scene) { return ui::sceneToJson(scene, "/tmp/compare/scene.json"); }

inline QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// A one-triangle OBJ in `dir`, so a scene has a mesh that is a file.
inline QString writeTriangle(const QTemporaryDir& dir) {
    const QString path = dir.filePath(QStringLiteral("meshes/triangle.obj"));
    QDir().mkpath(QFileInfo(path).absolutePath());
    QFile f(path);
    EXPECT_TRUE(f.open(QIODevice::WriteOnly));
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    return path;
}

}  // namespace mipgloss::test
