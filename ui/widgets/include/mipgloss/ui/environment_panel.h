// The environment dock's contents: the environment's source and what was built from it, the build
// settings (mip builder, face size, face image orientation), its rotation, and the display
// settings (background and its blur λ, exposure, tone map, multisampling). Edits go through the
// SceneDocument, one undo step per interaction (edit_sessions.h: a drag of the rotation slider,
// the steps made in one box while it has the focus); widgets are refreshed from the document and
// the EnvironmentManager with their signals blocked, so a refresh never writes back.
//
// Object names for tests: envSourceLabel, envInfoLabel, openEnvironmentButton, builderCombo,
// faceSizeCombo, handednessCombo, envRotationSlider, showBackgroundCheck, backgroundBlurSpin,
// exposureSpin, toneMapCombo, samplesCombo.
#pragma once

#include "mipgloss/scene/scene.h"

#include <QString>
#include <QWidget>

#include <functional>

class QCheckBox;
class QColorDialog;
class QPushButton;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSlider;

namespace mipgloss::ui {

class EditSessions;
class EnvironmentManager;
class SceneDocument;

// The name an environment source is shown by: "courtyard" for the embedded one, else the file's.
QString environmentDisplayName(const std::string& source);
// "128²".
QString squaredSize(int size);

class EnvironmentPanel : public QWidget {
    Q_OBJECT
public:
    EnvironmentPanel(SceneDocument* document, EnvironmentManager* environments, QWidget* parent = nullptr);

signals:
    // The "Open…" button: the window asks for a file.
    void openRequested();

private:
    void refresh();
    void editEnvironment(const std::function<void(EnvironmentSettings&)>& edit, const QObject* from = nullptr);
    void editDisplay(const std::function<void(DisplaySettings&)>& edit, const QObject* from = nullptr);

    SceneDocument* document_;
    EnvironmentManager* environments_;
    EditSessions* sessions_ = nullptr;
    QLabel* source_ = nullptr;
    QLabel* info_ = nullptr;
    QComboBox* builder_ = nullptr;
    QComboBox* faceSize_ = nullptr;
    QComboBox* handedness_ = nullptr;
    QSlider* rotation_ = nullptr;
    QDoubleSpinBox* rotationDegrees_ = nullptr;  // the same angle, in degrees
    QCheckBox* showBackground_ = nullptr;
    QDoubleSpinBox* backgroundBlur_ = nullptr;
    // The backdrop behind the objects while the background is hidden (DisplaySettings::backdrop):
    // a swatch that opens a colour dialog (made when first asked for, window-modal).
    QPushButton* backdrop_ = nullptr;
    QColorDialog* backdropDialog_ = nullptr;
    void showBackdropSwatch(const Rgb& colour);
    QDoubleSpinBox* exposure_ = nullptr;
    QComboBox* toneMap_ = nullptr;
    QComboBox* samples_ = nullptr;
    QCheckBox* keepBouncedLight_ = nullptr;
};

}  // namespace mipgloss::ui
