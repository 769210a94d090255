// The interactive view: a QOpenGLWidget that draws the document's scene with the Renderer. Frames
// are drawn on demand (a change in the document, the environment, the camera or the size calls
// update()); nothing redraws in a loop.
//
// Mouse: left drag orbits, right or middle drag (or shift + left) pans, the wheel zooms, a click
// selects the object under the cursor; F frames all; Home resets the view. A library material
// (material_mime.h) dropped on an object is applied to it and selects it.
#pragma once

#include "mipgloss/scene/camera.h"
#include "mipgloss/ui/renderer.h"

#include <QImage>
#include <QOpenGLWidget>
#include <QPoint>

#include <memory>

namespace mipgloss::ui {

class SceneDocument;
class EnvironmentManager;

class Viewport : public QOpenGLWidget {
    Q_OBJECT
public:
    Viewport(SceneDocument* document, EnvironmentManager* environments, QWidget* parent = nullptr);
    ~Viewport() override;

    OrbitCamera& camera() { return camera_; }
    const RenderCounters& counters() const;
    // Why GL could not start (empty when it did).
    const QString& glError() const { return glError_; }

public slots:
    void frameAll();
    void setShowCounters(bool show);

signals:
    void frameDrawn(quint64 frameNumber);
    void objectClicked(int index);  // -1: empty space
    void glFailed(const QString& message);

protected:
    void initializeGL() override;
    void paintGL() override;
    void resizeGL(int w, int h) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dragMoveEvent(QDragMoveEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void cleanup();
    int pickObject(QPoint position) const;

    SceneDocument* document_;
    EnvironmentManager* environments_;
    std::unique_ptr<Renderer> renderer_;
    OrbitCamera camera_;
    bool framedOnce_ = false;
    bool showCounters_ = false;
    QString glError_;
    QPoint pressPos_, lastPos_;
    Qt::MouseButton dragButton_ = Qt::NoButton;
    bool dragged_ = false;
};

}  // namespace mipgloss::ui
