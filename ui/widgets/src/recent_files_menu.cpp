#include "recent_files_menu.h"

#include "mipgloss/ui/scene_file_session.h"

#include <QAction>
#include <QFileInfo>

namespace mipgloss::ui {

RecentFilesMenu::RecentFilesMenu(SceneFileSession* session, QWidget* parent)
    : QMenu(tr("Open &recent"), parent), session_(session) {
    setObjectName(QStringLiteral("recentMenu"));
    for (QAction*& file : fileActions_) {
        file = addAction(QString());
        file->setObjectName(QStringLiteral("recentFileAction"));
        file->setVisible(false);
        connect(file, &QAction::triggered, this, [this, file] { emit fileChosen(file->data().toString()); });
    }
    addSeparator();
    clearAction_ = addAction(tr("&Clear list"));
    clearAction_->setObjectName(QStringLiteral("clearRecentAction"));
    connect(clearAction_, &QAction::triggered, session_, &SceneFileSession::clearRecentFiles);
    connect(session_, &SceneFileSession::recentFilesChanged, this, &RecentFilesMenu::showFiles);
    connect(this, &QMenu::aboutToShow, this, &RecentFilesMenu::showFiles);
    showFiles();
}

void RecentFilesMenu::showFiles() {
    const QStringList files = session_->recentFiles();
    for (std::size_t i = 0; i < fileActions_.size(); ++i) {
        QAction* action = fileActions_[i];
        const bool used = static_cast<qsizetype>(i) < files.size();
        action->setVisible(used);
        if (!used) continue;
        const QString& file = files.at(static_cast<qsizetype>(i));
        action->setText(tr("&%1 %2").arg(i + 1).arg(QFileInfo(file).fileName()));
        action->setToolTip(file);
        action->setStatusTip(file);
        action->setData(file);
    }
    clearAction_->setEnabled(!files.isEmpty());
    setEnabled(!files.isEmpty());
}

}  // namespace mipgloss::ui
