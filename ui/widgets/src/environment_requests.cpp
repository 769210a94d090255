#include "environment_requests.h"

#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/message_bar.h"
#include "mipgloss/ui/scene_document.h"

#include <QFileInfo>

namespace mipgloss::ui {

EnvironmentRequests::EnvironmentRequests(SceneDocument* document, EnvironmentManager* environments,
                                         MessageBar* messages, QObject* parent)
    : QObject(parent), document_(document), environments_(environments), messages_(messages) {
    connect(document_, &SceneDocument::environmentChanged, this, &EnvironmentRequests::noteOpened);
    connect(environments_, &EnvironmentManager::environmentReady, this, &EnvironmentRequests::noteOpened);
    connect(environments_, &EnvironmentManager::failed, this, &EnvironmentRequests::onFailed);
}

bool EnvironmentRequests::open(const QString& path) {
    const QFileInfo info(path);
    if (!info.exists()) {
        messages_->showMessageOf(MessageBar::Kind::Environment, tr("%1: no such file or folder").arg(path), true);
        return false;
    }
    EnvironmentSettings settings = document_->scene().environment;
    settings.source = info.absoluteFilePath().toStdString();
    settings.layout = EnvLayout::Auto;
    environments_->forgetFailure();  // an explicit open reads the file again, fixed or not
    opening_ = settings.source;
    // Said until it is loaded or fails (noteOpened, onFailed).
    messages_->showUntilNextMessage(tr("Opening environment %1…").arg(info.fileName()));
    document_->setEnvironment(settings);
    noteOpened();  // the file drawn already: loaded at once
    return true;
}

void EnvironmentRequests::noteOpened() {
    // The environment open() asked for: loaded (drawn, perhaps before its chain), or the document
    // no longer asks for it (undone, another scene opened; a failure is onFailed's). Either way
    // the status line stops saying it is being opened.
    if (opening_.empty()) return;
    const auto current = environments_->current();
    const QString name = QFileInfo(QString::fromStdString(opening_)).fileName();
    if (current && current->settings.source == opening_) {
        opening_.clear();
        messages_->showMessageOf(MessageBar::Kind::Environment, tr("Loaded %1").arg(name), false);
    } else if (document_->scene().environment.source != opening_) {
        opening_.clear();
        if (messages_->statusText() == tr("Opening environment %1…").arg(name)) messages_->clearStatus();
    }
}

void EnvironmentRequests::onFailed(const QString& message) {
    opening_.clear();
    // The manager logs its failures.
    messages_->showMessageOf(MessageBar::Kind::Environment, message, true, /*log=*/false);
    // Keep drawing what was there, and make the document say so again; the step that asked for
    // the file is withdrawn rather than answered by a step of its own (scene_document.h).
    EnvironmentSettings fallback;  // nothing drawn yet: the embedded default
    if (const auto current = environments_->current()) fallback = current->settings;
    document_->withdrawFailedEnvironment(environments_->lastFailure(), fallback);
}

}  // namespace mipgloss::ui
