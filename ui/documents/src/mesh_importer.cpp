#include "mipgloss/ui/mesh_importer.h"

#include "mipgloss/scene/mesh.h"
#include "mipgloss/scene/placement.h"
#include "mipgloss/ui/scene_document.h"

#include <QFileInfo>
#include <QFutureWatcher>
#include <QLocale>
#include <QUndoStack>
#include <QtConcurrent/QtConcurrentRun>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace mipgloss::ui {

// One loaded mesh file (or its error), handed from the loader to finish().
struct MeshImporter::Loaded {
    QString path;
    std::shared_ptr<const Mesh> mesh;
    QString error;
    std::vector<std::string> warnings;
};

namespace {

MeshImporter::Loaded loadOne(const QString& path) {
    MeshImporter::Loaded result;
    result.path = path;
    try {
        MeshReport report;
        Mesh mesh = loadMesh(path.toStdString(), &report);
        if (mesh.name.empty()) mesh.name = QFileInfo(path).completeBaseName().toStdString();
        result.mesh = std::make_shared<const Mesh>(std::move(mesh));
        result.warnings = std::move(report.warnings);
    } catch (const MeshError& e) {
        result.error = QString::fromStdString(e.what());
    } catch (const std::exception& e) {  // e.g. out of memory on a huge file
        result.error = path + QStringLiteral(": ") + QString::fromStdString(e.what());
    }
    return result;
}

}  // namespace

MeshImporter::MeshImporter(SceneDocument* document, QObject* parent) : QObject(parent), document_(document) {}

void MeshImporter::import(const QStringList& paths) {
    if (paths.isEmpty()) return;
    std::int64_t bytes = 0;
    for (const QString& path : paths) bytes += QFileInfo(path).size();
    auto loadAll = [paths] {
        std::vector<Loaded> results;
        for (const QString& path : paths) results.push_back(loadOne(path));
        return results;
    };
    if (bytes <= kBackgroundImportBytes) {
        finish(loadAll());
        return;
    }
    ++running_;
    emit backgroundStarted(static_cast<int>(paths.size()));
    auto* watcher = new QFutureWatcher<std::vector<Loaded>>(this);
    connect(watcher, &QFutureWatcher<std::vector<Loaded>>::finished, this, [this, watcher] {
        --running_;
        finish(watcher->result());
        watcher->deleteLater();
    });
    watcher->setFuture(QtConcurrent::run(loadAll));
}

void MeshImporter::finish(const std::vector<Loaded>& results) {
    QStringList errors, added, names;
    for (const Loaded& r : results) {
        for (const std::string& w : r.warnings) std::cerr << "mipgloss: " << w << '\n';
        if (r.mesh)
            names << QFileInfo(r.path).fileName();
        else
            errors << r.error;
    }
    // One undo step for the whole import.
    QUndoStack* stack = document_->undoStack();
    if (!names.isEmpty()) stack->beginMacro(tr("Import %1").arg(names.join(QStringLiteral(", "))));
    for (const Loaded& r : results) {
        if (!r.mesh) continue;
        SceneObject object;
        object.name = QFileInfo(r.path).completeBaseName().toStdString();
        object.meshSource = QFileInfo(r.path).absoluteFilePath().toStdString();
        object.mesh = r.mesh;
        Material material;
        material.lambda = kImportedLambda;
        material.mode = LookupMode::Reflect;
        object.transform = besideScene(document_->scene(), *r.mesh);
        document_->addObject(std::move(object), material);
        added << tr("%1 (%2 triangles)")
                     .arg(QFileInfo(r.path).fileName())
                     .arg(QLocale().toString(static_cast<qlonglong>(r.mesh->triangleCount())));
    }
    if (!names.isEmpty()) stack->endMacro();
    emit finished(added, errors);
}

}  // namespace mipgloss::ui
