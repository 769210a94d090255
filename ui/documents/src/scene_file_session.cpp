#include "mipgloss/ui/scene_file_session.h"

#include "mipgloss/ui/file_kinds.h"
#include "mipgloss/ui/recent_files.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/scene_file.h"

#include <QDir>
#include <QFileInfo>
#include <QLocale>
#include <QTimer>

#include <iostream>
#include <string>
#include <vector>

namespace mipgloss::ui {

namespace {

void logWarnings(const SceneFileReport& report) {
    for (const std::string& w : report.warnings) std::cerr << "mipgloss: " << w << '\n';
}

}  // namespace

SceneFileSession::SceneFileSession(SceneDocument* document, QObject* parent)
    : QObject(parent), document_(document), autosave_(std::make_unique<Autosave>()) {
    connect(document_, &SceneDocument::changed, this, &SceneFileSession::updateModified);
    autosaveTimer_ = new QTimer(this);
    autosaveTimer_->setInterval(kDefaultAutosaveIntervalMs);
    connect(autosaveTimer_, &QTimer::timeout, this, &SceneFileSession::autosaveNow);
    autosaveTimer_->start();
    markSaved();
}

SceneFileSession::~SceneFileSession() {
    // Unsaved work the user never chose to drop keeps its autosave (offered at the next start).
    if (!modified_) autosave_->discard();
}

void SceneFileSession::setSceneToSave(std::function<Scene()> sceneToSave) { sceneToSave_ = std::move(sceneToSave); }

QString SceneFileSession::displayName() const {
    return file_.isEmpty() ? tr("Untitled") : QFileInfo(file_).fileName();
}

QString SceneFileSession::windowTitle() const { return QStringLiteral("%1[*] — mipgloss").arg(displayName()); }

void SceneFileSession::noteDirectoryOf(const QString& path) { lastDirectory_ = QFileInfo(path).absolutePath(); }

QString SceneFileSession::saveAsSuggestion() const {
    return file_.isEmpty() ? QFileInfo(QDir(lastDirectory_), tr("untitled.mipgloss")).filePath() : file_;
}

// ---------------------------------------------------------------------------------------------
// New, open, save

void SceneFileSession::replaceScene(Scene scene, FileCameras cameras) {
    document_->resetScene(std::move(scene), std::move(cameras));
    emit sceneReplaced();
}

void SceneFileSession::setFile(const QString& file) {
    file_ = file;
    emit titleChanged(windowTitle());
}

void SceneFileSession::startNew(Scene scene) {
    replaceScene(std::move(scene));
    setFile(QString());
    markSaved();
    forgetAutosave();
}

bool SceneFileSession::open(const QString& path) {
    try {
        SceneFileReport report;
        Scene scene = loadScene(path.toStdString(), &report);
        replaceScene(std::move(scene), std::move(report.cameras));
        matchesFile(path);
        logWarnings(report);
        const QString name = QFileInfo(path).fileName();
        if (report.warnings.empty())
            emit openReported(tr("Opened %1").arg(name), false);
        else
            emit openReported(
                tr("Opened %1 with warnings:\n%2").arg(name, QString::fromStdString(report.warnings.front())), false);
        return true;
    } catch (const SceneFileError& e) {
        emit openReported(QString::fromStdString(e.what()), true);
    } catch (const std::exception& e) {
        emit openReported(path + QStringLiteral(": ") + QString::fromStdString(e.what()), true);
    }
    return false;
}

bool SceneFileSession::saveTo(const QString& path) {
    try {
        saveScene(sceneToSave_ ? sceneToSave_() : document_->scene(), path.toStdString());
    } catch (const SceneFileError& e) {
        emit messageShown(QString::fromStdString(e.what()), true);
        return false;
    }
    matchesFile(path);
    emit messageShown(tr("Saved %1").arg(QFileInfo(path).fileName()), false);
    return true;
}

void SceneFileSession::detachFromFile() { setFile(QString()); }

void SceneFileSession::markSaved() {
    savedScene_ = document_->scene();
    updateModified();
}

void SceneFileSession::matchesFile(const QString& path) {
    setFile(QFileInfo(path).absoluteFilePath());
    noteDirectoryOf(path);
    markSaved();
    forgetAutosave();
    RecentFiles::add(file_);
    emit recentFilesChanged();
}

void SceneFileSession::updateModified() {
    const bool modified = !savedScene_ || document_->scene() != *savedScene_;
    // Back at the saved state (undone to it): the autosave holds nothing worth restoring.
    if (!modified && modified_) forgetAutosave();
    if (modified == modified_) return;
    modified_ = modified;
    emit modifiedChanged(modified_);
}

// ---------------------------------------------------------------------------------------------
// Recent files

QStringList SceneFileSession::recentFiles() const { return RecentFiles::files(); }

void SceneFileSession::clearRecentFiles() {
    RecentFiles::clear();
    emit recentFilesChanged();
}

bool SceneFileSession::recentFileExists(const QString& path) {
    if (QFileInfo::exists(path)) return true;
    RecentFiles::remove(path);
    emit recentFilesChanged();
    emit messageShown(tr("%1: no longer exists; removed from Open Recent").arg(path), true);
    return false;
}

void SceneFileSession::pruneRecentFiles() {
    const QStringList gone = RecentFiles::prune();
    if (gone.isEmpty()) return;
    emit recentFilesChanged();
    emit messageShown(tr("No longer found, removed from Open Recent: %1").arg(gone.join(QStringLiteral(", "))), false);
}

// ---------------------------------------------------------------------------------------------
// Autosave

int SceneFileSession::autosaveInterval() const { return autosaveTimer_->interval(); }

void SceneFileSession::setAutosaveInterval(int milliseconds) { autosaveTimer_->setInterval(milliseconds); }

bool SceneFileSession::autosaveNow() {
    if (!modified_) return false;
    if (lastAutosaved_ && *lastAutosaved_ == document_->scene()) return false;
    try {
        autosave_->write(document_->scene(), file_);
    } catch (const FileError& e) {
        // Once per reason, not every minute.
        const QString message = tr("Autosave failed: %1").arg(QString::fromStdString(e.what()));
        if (message != lastAutosaveError_) emit messageShown(message, true);
        lastAutosaveError_ = message;
        return false;
    }
    lastAutosaved_ = document_->scene();
    lastAutosaveError_.clear();
    return true;
}

void SceneFileSession::forgetAutosave() {
    autosave_->discard();
    lastAutosaved_.reset();
}

void SceneFileSession::endCleanly() {
    autosaveTimer_->stop();
    forgetAutosave();
}

std::optional<Autosave::Leftover> SceneFileSession::newestLeftover() {
    const std::vector<Autosave::Leftover> leftovers = Autosave::leftovers();
    if (leftovers.empty()) return std::nullopt;
    return leftovers.front();
}

QString SceneFileSession::restoreQuestion(const Autosave::Leftover& leftover) {
    const QString work = leftover.sceneFile.isEmpty() ? tr("a scene that was never saved")
                                                      : QFileInfo(leftover.sceneFile).fileName();
    return tr("mipgloss did not close properly last time. Restore the changes to %1 autosaved %2?")
        .arg(work, QLocale().toString(leftover.written, QLocale::ShortFormat));
}

bool SceneFileSession::restore(const Autosave::Leftover& leftover) {
    try {
        SceneFileReport report;
        Scene scene = loadScene(leftover.file.toStdString(), &report);
        logWarnings(report);
        replaceScene(std::move(scene), std::move(report.cameras));
    } catch (const SceneFileError& e) {
        // Kept: the user may still rescue it by hand, and the message says where it is.
        emit messageShown(tr("Could not restore the autosave: %1").arg(QString::fromStdString(e.what())), true);
        return false;
    }
    Autosave::remove(leftover);
    savedScene_.reset();  // what is on disk is unknown: modified until saved
    forgetAutosave();
    updateModified();
    setFile(leftover.sceneFile);
    emit messageShown(tr("Restored the autosaved changes to %1").arg(displayName()), false);
    return true;
}

}  // namespace mipgloss::ui
