// The interactive view: a QOpenGLWidget that draws the document's scene with the Renderer. Frames
// are drawn on demand (a change in the document, the environment, the camera or the size calls
// update()); nothing redraws in a loop, except while the turntable turns.
//
// Mouse: left drag orbits, right or middle drag (or shift + left) pans, the wheel zooms toward the
// point under the cursor (view_gestures.h), a click selects the object under the cursor. Ctrl +
// left drag (or shift + right drag, as in Toolbag) turns the environment: one undo step per drag.
// The window's actions frame the selection, frame all and reset the view (main_window.h). A library
// material (material_mime.h) dropped on an object is applied to it and selects it.
//
// The turntable (turntable.h) turns the object(s) or the environment at a chosen speed; its angle
// is a view of the scene, never an edit. The comparison splits the view at a draggable divider:
// left the scene as it is, right the same scene and camera with another builder, environment or
// material on the selected object. The right half has a document, environment manager and
// renderer of its own (a shadow of the scene, never edited by the user), so each half is built
// exactly and settled on its own lobes.
#pragma once

#include "mipgloss/ibl/builders.h"
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/scene/turntable.h"
#include "mipgloss/ui/renderer.h"

#include <QElapsedTimer>
#include <QImage>
#include <QOpenGLWidget>
#include <QPoint>
#include <QString>

#include <memory>
#include <string>
#include <optional>

class QTimer;

namespace mipgloss::ui {

class SceneDocument;
class EnvironmentManager;

// What the right half of a split view shows.
struct Comparison {
    enum class Kind { Off, Builder, Environment, Material };
    Kind kind = Kind::Off;
    Builder builder = Builder::Box;  // Kind::Builder: the right half's chain builder
    std::string environment;         // Kind::Environment: the right half's environment source
    Material material;               // Kind::Material: worn by the selected object on the right
    QString materialName;            // its name, for the label
};

class Viewport : public QOpenGLWidget {
    Q_OBJECT
public:
    Viewport(SceneDocument* document, EnvironmentManager* environments, QWidget* parent = nullptr);
    ~Viewport() override;

    OrbitCamera& camera() { return camera_; }
    const OrbitCamera& camera() const { return camera_; }
    const RenderCounters& counters() const;
    // Why GL could not start (empty when it did).
    const QString& glError() const { return glError_; }

    // The turntable: running, what turns, its speed (degrees per second) and its angle now.
    bool turntableRunning() const;
    // Texture maps the scene's materials read that are being decoded now (on the document's
    // worker: a scene opened, a library material applied); the view redraws when they arrive.
    bool decodingTextures() const;
    TurntableSpin turntableSpin() const { return turntableSpin_; }
    float turntableSpeed() const { return turntableSpeed_; }
    float turntableDegrees() const { return turntableDegrees_; }
    // The camera and environment rotation the view draws with now (the turntable applied).
    TurnedView shownView() const;

    const Comparison& comparison() const { return comparison_; }
    float dividerFraction() const { return divider_; }
    // The right half's environment manager, while a comparison is on (null otherwise).
    EnvironmentManager* comparisonEnvironments() const { return compareEnvironments_.get(); }
    // The label over each half ("phong · courtyard" / "box · courtyard").
    QString leftLabel() const;
    QString rightLabel() const;

    // What the view shows, drawn again offscreen at width × height (either may differ from the
    // widget's), with the comparison if one is on. With `transparent` and the background hidden,
    // the image's alpha is the objects' coverage. `hdr` (optional) receives the linear picture
    // (RGBA, top row first; the comparison's right part from its own render). Null image and
    // `error` set when the size is beyond what this OpenGL can draw or the render fails.
    QImage renderImage(int width, int height, bool transparent, std::vector<float>* hdr, QString* error);
    // The largest width and height this OpenGL draws (the renderer's targets); 0 before GL starts.
    int maxRenderSize() const { return maxRenderSize_; }

public slots:
    void frameAll();
    // Frames the selected object (all objects when none is selected).
    void frameSelected();
    // The default view angle and field of view, framing all, the turntable back at 0°.
    void resetView();
    void setShowCounters(bool show);
    void setFieldOfView(float degrees);  // clamped to [kMinFov, kMaxFov]
    void setCamera(const OrbitCamera& camera);
    void setTurntableRunning(bool running);
    void setTurntableSpin(TurntableSpin spin);
    void setTurntableSpeed(float degreesPerSecond);
    void setComparison(const Comparison& comparison);
    void setDividerFraction(float fraction);  // clamped to [0.05, 0.95]

signals:
    void frameDrawn(quint64 frameNumber);
    // Texture maps decoded on demand (decodeTextures) that could not be read, each naming its file.
    void textureWarnings(const QStringList& warnings);
    void objectClicked(int index);  // -1: empty space
    void glFailed(const QString& message);
    void cameraChanged();  // any gesture, framing or setCamera
    void comparisonChanged();
    void comparisonFailed(const QString& message);  // the right half's environment could not be read

public:
    static constexpr float kMinFov = 10.0f, kMaxFov = 90.0f;
    // Degrees of environment turn per pixel dragged (as an orbit's).
    static constexpr float kEnvironmentDegreesPerPixel = 0.4f;

protected:
    void initializeGL() override;
    void paintGL() override;
    void resizeGL(int w, int h) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dragMoveEvent(QDragMoveEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    enum class Drag { None, Orbit, Pan, Environment, Divider };

    void cleanup();
    int pickObject(QPoint position) const;
    // The scene as drawn: the turntable's environment angle and, while dragging, no multisampling.
    // The document's own when neither applies; else a copy, held in `changed` (a frame copies the
    // scene only when it must).
    const Scene& shownScene(bool interactive, std::optional<Scene>& changed) const;
    // The right half's scene: the shown scene with the comparison's change.
    Scene comparedScene(const Scene& shown) const;
    void syncComparison();  // the shadow document follows the scene
    // Draws the whole picture (both halves) into `fbo`; `outline`: the selection outlined.
    void drawInto(unsigned fbo, int width, int height, bool interactive, bool transparent, bool outline);
    bool comparing() const;
    int dividerX() const;
    void advanceTurntable();

    SceneDocument* document_;
    EnvironmentManager* environments_;
    std::unique_ptr<Renderer> renderer_;
    // Decodes the maps `scene` reads that the document's texture cache lacks: at once when `now`
    // (a picture exported), else on the document's worker, with a redraw when they are there.
    void decodeTextures(const Scene& scene, bool now);
    OrbitCamera camera_;
    bool framedOnce_ = false;
    bool showCounters_ = false;
    QString glError_;
    QPoint pressPos_, lastPos_;
    Qt::MouseButton dragButton_ = Qt::NoButton;
    Drag drag_ = Drag::None;
    bool dragged_ = false;
    std::uint64_t environmentDragKey_ = 0;
    int maxRenderSize_ = 0;

    QTimer* turntableTimer_ = nullptr;
    QElapsedTimer turntableClock_;
    TurntableSpin turntableSpin_ = TurntableSpin::Object;
    float turntableSpeed_ = 30.0f;
    float turntableDegrees_ = 0.0f;

    Comparison comparison_;
    float divider_ = 0.5f;
    std::unique_ptr<SceneDocument> compareDocument_;
    std::unique_ptr<EnvironmentManager> compareEnvironments_;
    std::unique_ptr<Renderer> compareRenderer_;
};

}  // namespace mipgloss::ui
