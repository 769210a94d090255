// The desktop window: the viewport in the middle, docks for the scene list, the material and the
// environment, menus, drag and drop, and a status bar with the environment and its progress.
//
// Errors a user can cause (a broken mesh, environment or scene file) never change the scene: a
// failed mesh adds nothing, a failed environment leaves the old one drawn (and the document's
// environment settings are put back to it), a failed scene file leaves the open scene. Each is
// shown in a dismissable banner above the viewport, kept in lastMessage() and logged to stderr.
//
// Imported meshes (importMeshes): loaded off the UI thread when the files are large
// (kBackgroundImportBytes in all), otherwise at once; importFinished() follows either way. Each
// becomes an object named after the file stem with λ = 3 looked up by the reflection vector (a
// plainly glossy start, well inside the filtered levels of any chain of 16² or more), placed by
// this rule:
//   - size: R = the median world radius of the visible objects. A mesh whose radius r is more than
//     4× larger or smaller than R is scaled by R / r (so a 0.2-unit scan and a 120-unit one both
//     sit beside teapots); otherwise it keeps its own size. With no visible objects it keeps it.
//   - place: to the right (+x) of the visible scene's bounds with a gap of 0.2 R (0.2 r when
//     alone), its centre at the height and depth of the bounds' centre.
// Then the view frames all.
#pragma once

#include <QMainWindow>
#include <QString>
#include <QStringList>

#include <cstdint>
#include <vector>

class QComboBox;
class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QListView;
class QProgressBar;
class QSlider;
class QWidget;

namespace mipgloss::ui {

class SceneDocument;
class EnvironmentManager;
class Viewport;
class MaterialPanel;
class SceneListModel;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    // Mesh imports whose files add up to more than this run on a worker thread.
    static constexpr std::int64_t kBackgroundImportBytes = 4 * 1024 * 1024;
    // The λ an imported object starts with (reflect mode).
    static constexpr float kImportedLambda = 3.0f;

    // One loaded mesh file (or its error), handed from the loader to finishImport.
    struct ImportResult;

    SceneDocument* document() const { return document_; }
    EnvironmentManager* environments() const { return environments_; }
    Viewport* viewport() const { return viewport_; }
    MaterialPanel* materialPanel() const { return materialPanel_; }
    QListView* sceneList() const { return sceneList_; }

    // The last message shown (error or information) and whether it was an error.
    const QString& lastMessage() const { return lastMessage_; }
    bool lastMessageIsError() const { return lastMessageIsError_; }
    // The scene file the document was last opened from or saved to; empty for a new scene.
    const QString& sceneFile() const { return sceneFile_; }
    // True while a background mesh import runs.
    bool importing() const { return importsRunning_ > 0; }

public slots:
    void newScene();
    // Sets the document's environment source to `path` (a file, a face of a six-face set or a
    // directory); the EnvironmentManager imports it. False (with a message) if it does not exist;
    // a file that exists but cannot be read fails later through EnvironmentManager::failed.
    bool openEnvironment(const QString& path);
    void importMeshes(const QStringList& paths);
    bool openScene(const QString& path);
    bool saveScene(const QString& path);
    bool exportImage(const QString& path);
    // What dropping files does, also for command-line arguments: a .json scene opens (first),
    // mesh files import, an image or a folder becomes the environment (the last one given).
    void openFiles(const QStringList& paths);
    void frameAll();
    void removeSelected();
    void duplicateSelected();

signals:
    void messageShown(const QString& message, bool error);
    // After importMeshes: how many objects were added (failures have their own messages).
    void importFinished(int added);

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void buildMenus();
    QWidget* buildSceneDock();
    QWidget* buildEnvironmentDock();
    void buildStatusBar();
    void refreshEnvironmentWidgets();
    void refreshStatus();
    void refreshTitle();
    void syncListSelection();
    void showMessage(const QString& message, bool error, bool log = true);
    void finishImport(const std::vector<ImportResult>& results);
    void onEnvironmentFailed(const QString& message);

    void openSceneDialog();
    void saveSceneDialog();
    void openEnvironmentDialog();
    void importMeshDialog();
    void exportImageDialog();

    SceneDocument* document_ = nullptr;
    EnvironmentManager* environments_ = nullptr;
    Viewport* viewport_ = nullptr;
    MaterialPanel* materialPanel_ = nullptr;
    SceneListModel* sceneModel_ = nullptr;
    QListView* sceneList_ = nullptr;

    QWidget* banner_ = nullptr;
    QLabel* bannerText_ = nullptr;
    QLabel* envStatus_ = nullptr;
    QProgressBar* progress_ = nullptr;

    // Environment dock.
    QLabel* envSource_ = nullptr;
    QLabel* envInfo_ = nullptr;
    QComboBox* builder_ = nullptr;
    QComboBox* faceSize_ = nullptr;
    QComboBox* handedness_ = nullptr;
    QSlider* rotation_ = nullptr;
    QCheckBox* showBackground_ = nullptr;
    QDoubleSpinBox* backgroundBlur_ = nullptr;
    QDoubleSpinBox* exposure_ = nullptr;
    QComboBox* toneMap_ = nullptr;
    QComboBox* samples_ = nullptr;

    QString lastMessage_;
    bool lastMessageIsError_ = false;
    QString sceneFile_;
    QString lastDirectory_;
    int importsRunning_ = 0;
    bool syncingSelection_ = false;
};

}  // namespace mipgloss::ui
