// The status bar's permanent widgets, beside the message line (message_bar.h): a progress bar for
// environment builds and background mesh imports ("envProgress"), and the environment in use
// ("envStatusLabel": "studio.exr · 256² · Phong", with " (loading)" or " (building the chain)"
// until it is complete), whole when there is room and cut short (…) when not, so it never sets
// the window's least width. Both go straight into the status bar, so the message line's room is
// what they leave.
#pragma once

#include <QObject>

class QProgressBar;
class QStatusBar;

namespace mipgloss::ui {

class ElidedLabel;
class EnvironmentManager;
class MeshImporter;
class SceneDocument;

class StatusIndicators : public QObject {
    Q_OBJECT
public:
    StatusIndicators(QStatusBar* statusBar, const SceneDocument* document, EnvironmentManager* environments,
                     MeshImporter* importer, QObject* parent);

private:
    void showEnvironment();

    const SceneDocument* document_;
    EnvironmentManager* environments_;
    MeshImporter* importer_;
    QProgressBar* progress_ = nullptr;
    ElidedLabel* environment_ = nullptr;
};

}  // namespace mipgloss::ui
