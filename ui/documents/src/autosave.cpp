#include "mipgloss/ui/autosave.h"

#include "mipgloss/ui/atomic_file.h"
#include "mipgloss/ui/scene_file.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
#include <QStandardPaths>
#include <QUuid>

#include <algorithm>

namespace mipgloss::ui {

namespace {

QString lockFileFor(const QString& autosaveFile) {
    const QFileInfo info(autosaveFile);
    return info.dir().filePath(info.completeBaseName() + QStringLiteral(".lock"));
}

// The scene file's JSON with every file referred to by its absolute path: sceneToJson writes
// paths relative to the file when they are near it, and nothing is near the autosave folder.
QByteArray autosaveJson(const Scene& scene, const QString& file, const QString& sceneFile) {
    QJsonObject root = QJsonDocument::fromJson(sceneToJson(scene, file.toStdString())).object();
    QJsonObject environment = root.value(QStringLiteral("environment")).toObject();
    environment.insert(QStringLiteral("source"), QString::fromStdString(scene.environment.source));
    root.insert(QStringLiteral("environment"), environment);
    QJsonArray objects = root.value(QStringLiteral("objects")).toArray();
    for (qsizetype i = 0; i < objects.size() && i < static_cast<qsizetype>(scene.objects.size()); ++i) {
        QJsonObject o = objects.at(i).toObject();
        const SceneObject& object = scene.objects[static_cast<std::size_t>(i)];
        o.insert(QStringLiteral("mesh"), QString::fromStdString(object.meshSource));
        objects.replace(i, o);
    }
    root.insert(QStringLiteral("objects"), objects);
    root.insert(QStringLiteral("autosave"),
                QJsonObject{{QStringLiteral("sceneFile"), sceneFile},
                            {QStringLiteral("written"), QDateTime::currentDateTime().toString(Qt::ISODate)}});
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

}  // namespace

Autosave::Autosave()
    : file_(QDir(folder()).filePath(QUuid::createUuid().toString(QUuid::WithoutBraces) +
                                    QStringLiteral(".json"))) {}

Autosave::~Autosave() = default;  // ~QLockFile releases the lock

QString Autosave::folder() {
    const QDir data(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation));
    return data.filePath(QStringLiteral("autosave"));
}

void Autosave::write(const Scene& scene, const QString& sceneFile) {
    if (!lock_) {
        QDir().mkpath(folder());
        lock_ = std::make_unique<QLockFile>(lockFileFor(file_));
        // A fresh id: nobody else holds it. Without the lock, the file would only look like a
        // crash's leftover to a session starting meanwhile, so writing goes on either way.
        lock_->tryLock(0);
    }
    writeFileAtomically(file_.toStdString(), autosaveJson(scene, file_, sceneFile));
}

void Autosave::discard() {
    QFile::remove(file_);
}

std::vector<Autosave::Leftover> Autosave::leftovers() {
    std::vector<Leftover> found;
    const QDir dir(folder());
    for (const QFileInfo& info : dir.entryInfoList({QStringLiteral("*.json")}, QDir::Files)) {
        // A live session holds its lock; one that ended (even killed) does not: QLockFile sees
        // its process gone. Age alone must not count (the default stale time is 30 s).
        QLockFile probe(lockFileFor(info.filePath()));
        probe.setStaleLockTime(0);
        if (!probe.tryLock(0)) continue;
        probe.unlock();
        Leftover leftover;
        leftover.file = info.filePath();
        leftover.written = info.lastModified();
        QFile in(info.filePath());
        if (in.open(QIODevice::ReadOnly)) {
            const QJsonObject about =
                QJsonDocument::fromJson(in.readAll()).object().value(QStringLiteral("autosave")).toObject();
            leftover.sceneFile = about.value(QStringLiteral("sceneFile")).toString();
            const QDateTime written =
                QDateTime::fromString(about.value(QStringLiteral("written")).toString(), Qt::ISODate);
            if (written.isValid()) leftover.written = written;
        }
        found.push_back(leftover);
    }
    std::sort(found.begin(), found.end(),
              [](const Leftover& a, const Leftover& b) { return a.written > b.written; });
    return found;
}

void Autosave::remove(const Leftover& leftover) {
    QFile::remove(leftover.file);
    QFile::remove(lockFileFor(leftover.file));
}

}  // namespace mipgloss::ui
