// File → Open Recent: the session's recent files (scene_file_session.h), newest first, as
// "&1 gold.mipgloss" with the whole path in the tooltip and status tip, then Clear list; disabled
// while the list is empty. It follows the list as it changes (and again as it is opened, as
// another window may have changed the settings). Named "recentMenu"; its entries
// "recentFileAction", Clear list "clearRecentAction".
#pragma once

#include "mipgloss/ui/recent_files.h"

#include <QMenu>

#include <array>

class QAction;

namespace mipgloss::ui {

class SceneFileSession;

class RecentFilesMenu : public QMenu {
    Q_OBJECT
public:
    RecentFilesMenu(SceneFileSession* session, QWidget* parent);

signals:
    void fileChosen(const QString& path);

private:
    void showFiles();

    SceneFileSession* session_;
    std::array<QAction*, kMaxRecentFiles> fileActions_{};
    QAction* clearAction_ = nullptr;
};

}  // namespace mipgloss::ui
