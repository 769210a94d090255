#include "mipgloss/ui/viewport.h"

#include "mipgloss/scene/picking.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/scene_document.h"

#include <QDropEvent>
#include <QKeyEvent>
#include <QMimeData>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QWheelEvent>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <limits>

namespace mipgloss::ui {

Viewport::Viewport(SceneDocument* document, EnvironmentManager* environments, QWidget* parent)
    : QOpenGLWidget(parent), document_(document), environments_(environments),
      renderer_(std::make_unique<Renderer>()) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(320, 240);
    setAcceptDrops(true);  // library materials; other drags (files) pass on to the window
    // On demand: any change that can alter the picture asks for one frame.
    connect(document_, &SceneDocument::changed, this, qOverload<>(&QWidget::update));
    connect(environments_, &EnvironmentManager::environmentReady, this, qOverload<>(&QWidget::update));
    connect(environments_, &EnvironmentManager::lobesReady, this, qOverload<>(&QWidget::update));
    connect(document_, &SceneDocument::objectsChanged, this, [this] {
        if (document_->objectCount() > 0 && !framedOnce_) frameAll();
    });
}

Viewport::~Viewport() {
    cleanup();
    // ~QOpenGLWidget destroys the context later and emits aboutToBeDestroyed: not to us any more.
    if (QOpenGLContext* c = context()) c->disconnect(this);
}

const RenderCounters& Viewport::counters() const { return renderer_->counters(); }

void Viewport::cleanup() {
    if (!renderer_ || !renderer_->isInitialized()) return;
    makeCurrent();
    renderer_->destroy();
    doneCurrent();
}

void Viewport::initializeGL() {
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &Viewport::cleanup);
    std::string error;
    if (!renderer_->initialize(&error)) {
        glError_ = QString::fromStdString(error);
        emit glFailed(glError_);
    }
}

void Viewport::resizeGL(int, int) {}

void Viewport::paintGL() {
    if (!renderer_->isInitialized()) return;
    if (!framedOnce_ && document_->objectCount() > 0) frameAll();
    renderer_->setEnvironment(environments_->current());
    renderer_->setLobes(environments_->lobes());
    const qreal ratio = devicePixelRatio();
    const int w = static_cast<int>(std::lround(width() * ratio));
    const int h = static_cast<int>(std::lround(height() * ratio));
    if (dragButton_ != Qt::NoButton && document_->scene().display.samples > 1) {
        // While the user drags, frames skip multisampling (4× costs about 4× on a software
        // rasteriser: 370 vs 94 ms for a million triangles on llvmpipe); the release redraws it.
        Scene interactive = document_->scene();
        interactive.display.samples = 0;
        renderer_->render(interactive, camera_, w, h, defaultFramebufferObject());
    } else {
        renderer_->render(document_->scene(), camera_, w, h, defaultFramebufferObject());
    }
    if (showCounters_) {
        const RenderCounters& c = renderer_->counters();
        const EnvironmentCounters& e = environments_->counters();
        QPainter painter(this);
        painter.setPen(Qt::white);
        painter.setFont(QFont(QStringLiteral("monospace"), 9));
        const QString text =
            QStringLiteral("frames %1  drawn %2  culled %3\nbuilds %4  irradiance %5  imports %6\n"
                           "base uploads %7  chain uploads %8  mesh uploads %9  samplers %10\n"
                           "lobe cubes built %11  on GPU %12\nsettled (own lobe) %13  from the chain %14")
                .arg(c.frames).arg(c.objectsDrawn).arg(c.objectsCulled)
                .arg(e.chainBuilds).arg(e.irradianceBuilds).arg(e.imports)
                .arg(c.baseUploads).arg(c.chainUploads).arg(c.meshUploads).arg(c.samplersCreated)
                .arg(e.lobeBuilds).arg(c.lobesResident).arg(c.objectsSettled).arg(c.objectsFromChain);
        painter.fillRect(QRect(6, 6, 400, 84), QColor(0, 0, 0, 140));
        painter.drawText(QRect(12, 8, 390, 82), Qt::AlignLeft | Qt::AlignTop, text);
    }
    emit frameDrawn(renderer_->counters().frames);
}

void Viewport::frameAll() {
    const float aspect = height() > 0 ? static_cast<float>(width()) / static_cast<float>(height()) : 1.0f;
    camera_.frame(sceneBounds(document_->scene()), aspect);
    framedOnce_ = true;
    update();
}

void Viewport::setShowCounters(bool show) {
    if (show == showCounters_) return;
    showCounters_ = show;
    update();
}

int Viewport::pickObject(QPoint position) const {
    const Scene& scene = document_->scene();
    return firstObjectHit(scene, pixelRay(camera_, scene, width(), height(), position.x(), position.y()));
}

void Viewport::mousePressEvent(QMouseEvent* event) {
    pressPos_ = lastPos_ = event->position().toPoint();
    dragButton_ = event->button();
    dragged_ = false;
}

void Viewport::mouseMoveEvent(QMouseEvent* event) {
    if (dragButton_ == Qt::NoButton) return;
    const QPoint pos = event->position().toPoint();
    const QPoint delta = pos - lastPos_;
    lastPos_ = pos;
    if ((pos - pressPos_).manhattanLength() > 3) dragged_ = true;
    const float h = static_cast<float>(std::max(height(), 1));
    const bool pan = dragButton_ == Qt::RightButton || dragButton_ == Qt::MiddleButton ||
                     (event->modifiers() & Qt::ShiftModifier);
    if (pan)
        camera_.pan(static_cast<float>(delta.x()) / h, static_cast<float>(delta.y()) / h);
    else
        camera_.orbit(-0.4f * static_cast<float>(delta.x()), 0.4f * static_cast<float>(delta.y()));
    update();
}

void Viewport::mouseReleaseEvent(QMouseEvent* event) {
    if (!dragged_ && event->button() == Qt::LeftButton) emit objectClicked(pickObject(event->position().toPoint()));
    const bool wasDragging = dragged_;
    dragButton_ = Qt::NoButton;
    if (wasDragging) update();  // the full-quality frame
}

void Viewport::wheelEvent(QWheelEvent* event) {
    const float steps = static_cast<float>(event->angleDelta().y()) / 120.0f;
    camera_.zoom(std::pow(0.85f, steps));
    update();
}

void Viewport::keyPressEvent(QKeyEvent* event) {
    switch (event->key()) {
        case Qt::Key_F: frameAll(); break;
        case Qt::Key_Home:
            camera_ = OrbitCamera{};
            frameAll();
            break;
        default: QOpenGLWidget::keyPressEvent(event);
    }
}

}  // namespace mipgloss::ui

namespace mipgloss::ui {

namespace {
bool carriesMaterial(const QMimeData* mime) {
    return mime && mime->hasFormat(QString::fromLatin1(kMaterialMimeType));
}
}  // namespace

void Viewport::dragEnterEvent(QDragEnterEvent* event) {
    if (carriesMaterial(event->mimeData()))
        event->acceptProposedAction();
    else
        event->ignore();  // files: the window opens them
}

void Viewport::dragMoveEvent(QDragMoveEvent* event) {
    // Only over an object does a drop do something; elsewhere the cursor says so.
    if (carriesMaterial(event->mimeData()) && pickObject(event->position().toPoint()) >= 0)
        event->acceptProposedAction();
    else
        event->ignore();
}

void Viewport::dropEvent(QDropEvent* event) {
    const std::optional<LibraryMaterial> entry = materialFromMimeData(event->mimeData());
    const int index = entry ? pickObject(event->position().toPoint()) : -1;
    if (index < 0) {
        event->ignore();
        return;
    }
    document_->applyLibraryMaterial(index, *entry);
    document_->setSelected(index);
    event->acceptProposedAction();
}

}  // namespace mipgloss::ui
