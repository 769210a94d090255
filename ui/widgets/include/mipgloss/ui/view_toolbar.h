// The view's toolbar, above the viewport: framing, the field of view, the turntable and the
// comparison, in words an artist reads (what each does is in its tooltip). It edits the viewport's
// view (viewport.h), never the scene: none of it is an undo step or marks the scene modified.
#pragma once

#include <QToolBar>

class QAction;
class QComboBox;
class QDoubleSpinBox;
class QPushButton;
class QSpinBox;
class QStackedWidget;

namespace mipgloss::ui {

class LibraryDocument;
class SceneDocument;
class Viewport;

class ViewToolBar : public QToolBar {
    Q_OBJECT
public:
    // `frameActions` (frame selected, frame all, reset view) and `turntable` (checkable) are the
    // window's actions, shown here as buttons.
    ViewToolBar(Viewport* viewport, SceneDocument* document, LibraryDocument* library,
                const QList<QAction*>& frameActions, QAction* turntable, QWidget* parent = nullptr);

    QSpinBox* fieldOfView() const { return fov_; }
    QComboBox* turntableSpin() const { return spin_; }
    QDoubleSpinBox* turntableSpeed() const { return speed_; }
    QComboBox* compareKind() const { return compareKind_; }
    QComboBox* compareBuilder() const { return compareBuilder_; }
    QComboBox* compareMaterial() const { return compareMaterial_; }

signals:
    // The user asked to pick the right half's environment (a file dialog is the window's).
    void chooseComparedEnvironment();

public slots:
    // Compares with environment `source` (a file or folder path).
    void compareEnvironment(const QString& source);

private:
    void applyComparison();
    void fillMaterials();
    void refreshFromCamera();

    Viewport* viewport_;
    SceneDocument* document_;
    LibraryDocument* library_;
    QSpinBox* fov_ = nullptr;
    QComboBox* spin_ = nullptr;
    QDoubleSpinBox* speed_ = nullptr;
    QComboBox* compareKind_ = nullptr;
    QStackedWidget* compareChoice_ = nullptr;
    QComboBox* compareBuilder_ = nullptr;
    QPushButton* compareEnvironment_ = nullptr;
    QComboBox* compareMaterial_ = nullptr;
    QString comparedEnvironment_;
};

}  // namespace mipgloss::ui
