#include "mipgloss/ui/viewport.h"

#include "mipgloss/scene/picking.h"
#include "mipgloss/scene/view_gestures.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/environment_panel.h"
#include "mipgloss/ui/material_mime.h"
#include "mipgloss/ui/scene_document.h"

#include <QDropEvent>
#include <QMimeData>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QPainter>
#include <QTimer>
#include <QWheelEvent>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mipgloss::ui {

namespace {
// How close (pixels) to the divider a press grabs it.
constexpr int kDividerGrab = 6;
// The turntable's frame interval: about 30 frames a second where the renderer keeps up.
constexpr int kTurntableIntervalMs = 33;
}  // namespace

Viewport::Viewport(SceneDocument* document, EnvironmentManager* environments, QWidget* parent)
    : QOpenGLWidget(parent), document_(document), environments_(environments),
      renderer_(std::make_unique<Renderer>()) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(160, 120);
    setMouseTracking(true);  // the divider's cursor
    setAcceptDrops(true);  // library materials; other drags (files) pass on to the window
    // On demand: any change that can alter the picture asks for one frame.
    connect(document_, &SceneDocument::changed, this, qOverload<>(&QWidget::update));
    connect(environments_, &EnvironmentManager::environmentReady, this, qOverload<>(&QWidget::update));
    connect(environments_, &EnvironmentManager::lobesReady, this, qOverload<>(&QWidget::update));
    connect(document_, &SceneDocument::objectsChanged, this, [this] {
        if (document_->objectCount() > 0 && !framedOnce_) frameAll();
    });
    connect(document_, &SceneDocument::changed, this, &Viewport::syncComparison);
    connect(document_, &SceneDocument::selectionChanged, this, &Viewport::syncComparison);
    connect(document_, &SceneDocument::selectionChanged, this, qOverload<>(&QWidget::update));  // the outline
    // Maps decoded on the document's worker: drawn from the next frame, the unreadable ones named.
    connect(document_, &SceneDocument::texturesDecoded, this, [this](const QStringList& warnings) {
        if (!warnings.isEmpty()) emit textureWarnings(warnings);
        update();
    });
    turntableTimer_ = new QTimer(this);
    turntableTimer_->setInterval(kTurntableIntervalMs);
    connect(turntableTimer_, &QTimer::timeout, this, &Viewport::advanceTurntable);
}

Viewport::~Viewport() {
    cleanup();
    // ~QOpenGLWidget destroys the context later and emits aboutToBeDestroyed: not to us any more.
    if (QOpenGLContext* c = context()) c->disconnect(this);
}

const RenderCounters& Viewport::counters() const { return renderer_->counters(); }

void Viewport::cleanup() {
    const bool main = renderer_ && renderer_->isInitialized();
    const bool compared = compareRenderer_ && compareRenderer_->isInitialized();
    if (!main && !compared) return;
    makeCurrent();
    if (main) renderer_->destroy();
    if (compared) compareRenderer_->destroy();
    doneCurrent();
}

void Viewport::initializeGL() {
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &Viewport::cleanup);
    std::string error;
    if (!renderer_->initialize(&error)) {
        glError_ = QString::fromStdString(error);
        emit glFailed(glError_);
        return;
    }
    const RenderSizeLimits limits = renderer_->maxRenderSize();
    maxRenderSize_ = std::min(limits.maxWidth, limits.maxHeight);
}

void Viewport::resizeGL(int, int) {}

const Scene& Viewport::shownScene(bool interactive, std::optional<Scene>& changed) const {
    const Scene& scene = document_->scene();
    const float rotation = shownView().environmentRotationDegrees;
    // While the user drags, frames skip multisampling (4× costs about 4× on a software rasteriser:
    // 370 vs 94 ms for a million triangles on llvmpipe); the release redraws it.
    const bool dropSamples = interactive && scene.display.samples > 1;
    // And the taps along each pixel's footprint (DisplaySettings::footprintTaps: several times a
    // polished material's frame on llvmpipe, `mipgloss bench-render`).
    const bool dropTaps = interactive && scene.display.footprintTaps;
    if (rotation == scene.display.environmentRotationDegrees && !dropSamples && !dropTaps) return scene;
    changed = scene;
    changed->display.environmentRotationDegrees = rotation;
    if (dropSamples) changed->display.samples = 0;
    if (dropTaps) changed->display.footprintTaps = false;
    return *changed;
}

TurnedView Viewport::shownView() const {
    return turnedView(camera_, document_->scene().display.environmentRotationDegrees, turntableSpin_,
                      turntableDegrees_);
}

bool Viewport::comparing() const {
    return comparison_.kind != Comparison::Kind::Off && compareDocument_ && compareEnvironments_;
}

int Viewport::dividerX() const { return static_cast<int>(std::lround(divider_ * static_cast<float>(width()))); }

bool Viewport::decodingTextures() const { return document_->decodingTextures(); }

void Viewport::decodeTextures(const Scene& scene, bool now) {
    if (!now) {
        document_->decodeTexturesLater(scene);  // texturesDecoded redraws
        return;
    }
    const QStringList warnings = document_->decodeTexturesNow(scene);
    if (!warnings.isEmpty()) emit textureWarnings(warnings);
}

void Viewport::drawInto(unsigned fbo, int w, int h, bool interactive, bool transparent, bool outline) {
    std::optional<Scene> changed;
    const Scene& shown = shownScene(interactive, changed);
    // The maps a scene opened or a material applied reads: drawn without them until they arrive,
    // except in an exported picture, which waits for them.
    decodeTextures(shown, fbo != defaultFramebufferObject());
    const OrbitCamera camera = shownView().camera;
    const int highlighted = outline ? document_->selected() : -1;
    renderer_->setEnvironment(environments_->current());
    renderer_->setLobes(environments_->lobes());
    renderer_->setTransparentBackground(transparent);
    renderer_->setHighlightedObject(highlighted);
    renderer_->setTextures(document_->textures());
    renderer_->render(shown, camera, w, h, fbo);
    if (!comparing() || !compareEnvironments_->current()) return;
    if (!compareRenderer_) {
        compareRenderer_ = std::make_unique<Renderer>();
        std::string error;
        if (!compareRenderer_->initialize(&error)) {
            compareRenderer_.reset();
            return;
        }
    }
    compareRenderer_->setEnvironment(compareEnvironments_->current());
    compareRenderer_->setLobes(compareEnvironments_->lobes());
    compareRenderer_->setTransparentBackground(transparent);
    compareRenderer_->setHighlightedObject(highlighted);
    compareRenderer_->setTextures(document_->textures());
    const int split = static_cast<int>(std::lround(divider_ * static_cast<float>(w)));
    compareRenderer_->setOutputRect(split, 0, w - split, h);
    compareRenderer_->render(comparedScene(shown), camera, w, h, fbo);
    compareRenderer_->clearOutputRect();
}

void Viewport::paintGL() {
    if (!renderer_->isInitialized()) return;
    if (!framedOnce_ && document_->objectCount() > 0) frameAll();
    const qreal ratio = devicePixelRatio();
    const int w = static_cast<int>(std::lround(width() * ratio));
    const int h = static_cast<int>(std::lround(height() * ratio));
    const bool interactive = dragButton_ != Qt::NoButton || turntableRunning();
    drawInto(defaultFramebufferObject(), w, h, interactive, false, /*outline=*/true);
    if (!showCounters_ && !comparing()) {
        emit frameDrawn(renderer_->counters().frames);
        return;
    }
    QPainter painter(this);
    if (comparing()) {
        // The divider and what each side shows.
        const int x = dividerX();
        painter.setPen(QPen(QColor(255, 255, 255, 220), 1));
        painter.drawLine(x, 0, x, height());
        painter.setBrush(QColor(255, 255, 255, 220));
        painter.drawEllipse(QPoint(x, height() / 2), 5, 5);
        QFont font = painter.font();
        font.setBold(true);
        painter.setFont(font);
        const QFontMetrics metrics(font);
        auto label = [&](const QString& text, int left, int right, Qt::Alignment align) {
            const QString shown = metrics.elidedText(text, Qt::ElideMiddle, std::max(right - left - 16, 20));
            QRect box = metrics.boundingRect(shown).adjusted(-6, -3, 6, 3);
            box.moveTop(8);
            if (align & Qt::AlignLeft) box.moveLeft(left + 8);
            else box.moveRight(right - 8);
            painter.fillRect(box, QColor(0, 0, 0, 150));
            painter.setPen(Qt::white);
            painter.drawText(box, Qt::AlignCenter, shown);
        };
        label(leftLabel(), 0, x, Qt::AlignLeft);
        QString right = rightLabel();
        if (!compareEnvironments_->current() || !compareEnvironments_->current()->complete() ||
            compareEnvironments_->busy())
            right += tr(" (building…)");
        label(right, x, width(), Qt::AlignRight);
    }
    if (showCounters_) {
        const RenderCounters& c = renderer_->counters();
        const EnvironmentCounters& e = environments_->counters();
        painter.setPen(Qt::white);
        painter.setFont(QFont(QStringLiteral("monospace"), 9));
        const QString text =
            QStringLiteral("frames %1  drawn %2  culled %3\nbuilds %4  irradiance %5  imports %6\n"
                           "base uploads %7  chain uploads %8  mesh uploads %9  samplers %10\n"
                           "stack entries built %11  on GPU %12 (%15 MB)\nsettled (stack) %13  from the chain %14")
                .arg(c.frames).arg(c.objectsDrawn).arg(c.objectsCulled)
                .arg(e.chainBuilds).arg(e.irradianceBuilds).arg(e.imports)
                .arg(c.baseUploads).arg(c.chainUploads).arg(c.meshUploads).arg(c.samplersCreated)
                .arg(e.lobeBuilds).arg(c.lobesResident).arg(c.objectsSettled).arg(c.objectsFromChain)
                .arg(static_cast<double>(c.stackBytes) / 1e6, 0, 'f', 1);
        const int top = comparing() ? 40 : 6;
        painter.fillRect(QRect(6, top, 400, 84), QColor(0, 0, 0, 140));
        painter.drawText(QRect(12, top + 2, 390, 82), Qt::AlignLeft | Qt::AlignTop, text);
    }
    painter.end();
    emit frameDrawn(renderer_->counters().frames);
}

QImage Viewport::renderImage(int w, int h, bool transparent, std::vector<float>* hdr, QString* error) {
    auto fail = [&](const QString& why) {
        if (error) *error = why;
        return QImage();
    };
    if (!renderer_->isInitialized()) return fail(tr("OpenGL did not start: %1").arg(glError_));
    if (w < 1 || h < 1) return fail(tr("%1×%2 has no pixels").arg(w).arg(h));
    makeCurrent();  // the limits are the context's
    const RenderSizeLimits limits = renderer_->maxRenderSize();
    doneCurrent();
    if (w > limits.maxWidth)
        return fail(tr("a width of %1 px is beyond this OpenGL's %2 of %3 px").arg(w).arg(QLatin1String(limits.widthLimit)).arg(limits.maxWidth));
    if (h > limits.maxHeight)
        return fail(tr("a height of %1 px is beyond this OpenGL's %2 of %3 px").arg(h).arg(QLatin1String(limits.heightLimit)).arg(limits.maxHeight));
    makeCurrent();
    QImage image;
    {
        QOpenGLFramebufferObject fbo(w, h, QOpenGLFramebufferObject::NoAttachment, GL_TEXTURE_2D, GL_RGBA8);
        if (!fbo.isValid()) {
            doneCurrent();
            return fail(tr("OpenGL could not make a %1×%2 picture").arg(w).arg(h));
        }
        drawInto(fbo.handle(), w, h, false, transparent, /*outline=*/false);
        image = fbo.toImage(/*flipped=*/true);
        if (hdr) {
            // The linear picture: the left render's, with the right part from the comparison's.
            int hw = 0, hh = 0;
            const std::vector<glm::vec4> left = renderer_->readHdr(hw, hh);
            std::vector<glm::vec4> right;
            int rw = 0, rh = 0;
            if (comparing() && compareRenderer_ && compareEnvironments_->current())
                right = compareRenderer_->readHdr(rw, rh);
            const int split = static_cast<int>(std::lround(divider_ * static_cast<float>(w)));
            hdr->assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0.0f);
            if (hw == w && hh == h) {
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        // readHdr is bottom row first; the picture top row first.
                        const std::size_t from = static_cast<std::size_t>(h - 1 - y) * static_cast<std::size_t>(w) +
                                                 static_cast<std::size_t>(x);
                        const glm::vec4& p = (x >= split && rw == w && rh == h) ? right[from] : left[from];
                        float* out = hdr->data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                                    static_cast<std::size_t>(x)) * 4;
                        out[0] = p.r;
                        out[1] = p.g;
                        out[2] = p.b;
                        out[3] = transparent && !document_->scene().display.showBackground ? p.a : 1.0f;
                    }
            }
        }
    }
    doneCurrent();
    if (image.isNull()) return fail(tr("the %1×%2 picture could not be read back").arg(w).arg(h));
    return image;
}

void Viewport::frameAll() {
    const float aspect = height() > 0 ? static_cast<float>(width()) / static_cast<float>(height()) : 1.0f;
    camera_.frame(sceneBounds(document_->scene()), aspect);
    framedOnce_ = true;
    emit cameraChanged();
    update();
}

void Viewport::frameSelected() {
    const int index = document_->selected();
    const std::optional<Bounds> bounds =
        document_->isValidIndex(index) ? objectBounds(document_->object(index)) : std::nullopt;
    if (!bounds) {
        frameAll();
        return;
    }
    const float aspect = height() > 0 ? static_cast<float>(width()) / static_cast<float>(height()) : 1.0f;
    camera_.frame(*bounds, aspect);
    framedOnce_ = true;
    emit cameraChanged();
    update();
}

void Viewport::resetView() {
    camera_ = OrbitCamera{};
    turntableDegrees_ = 0.0f;
    frameAll();
}

void Viewport::setCamera(const OrbitCamera& camera) {
    camera_ = camera;
    camera_.fovYDegrees = std::clamp(camera_.fovYDegrees, kMinFov, kMaxFov);
    framedOnce_ = true;
    emit cameraChanged();
    update();
}

void Viewport::setFieldOfView(float degrees) {
    if (!std::isfinite(degrees)) return;
    degrees = std::clamp(degrees, kMinFov, kMaxFov);
    if (degrees == camera_.fovYDegrees) return;
    camera_.fovYDegrees = degrees;
    emit cameraChanged();
    update();
}

void Viewport::setShowCounters(bool show) {
    if (show == showCounters_) return;
    showCounters_ = show;
    update();
}

// ---------------------------------------------------------------------------------------------
// The turntable

bool Viewport::turntableRunning() const { return turntableTimer_->isActive(); }

void Viewport::setTurntableRunning(bool running) {
    if (running == turntableRunning()) return;
    if (running) {
        turntableClock_.start();
        turntableTimer_->start();
    } else {
        turntableTimer_->stop();
        update();  // the full-quality frame
    }
}

void Viewport::setTurntableSpin(TurntableSpin spin) {
    if (spin == turntableSpin_) return;
    // The new spin starts where the view is now: no jump.
    if (turntableDegrees_ != 0.0f) {
        const TurnedView now = shownView();
        if (turntableSpin_ == TurntableSpin::Object) camera_ = now.camera;
        DisplaySettings d = document_->scene().display;
        d.environmentRotationDegrees = now.environmentRotationDegrees;
        turntableDegrees_ = 0.0f;
        if (!(d == document_->scene().display)) document_->setDisplay(d);
    }
    turntableSpin_ = spin;
    update();
}

void Viewport::setTurntableSpeed(float degreesPerSecond) {
    if (std::isfinite(degreesPerSecond)) turntableSpeed_ = std::clamp(degreesPerSecond, -720.0f, 720.0f);
}

void Viewport::advanceTurntable() {
    // By the time elapsed, not per tick: a slow frame turns the same angle per second.
    const double seconds = static_cast<double>(turntableClock_.restart()) * 1e-3;
    turntableDegrees_ = static_cast<float>(std::remainder(
        static_cast<double>(turntableDegrees_) + static_cast<double>(turntableSpeed_) * seconds, 360.0));
    update();
}

// ---------------------------------------------------------------------------------------------
// The comparison

void Viewport::setComparison(const Comparison& comparison) {
    comparison_ = comparison;
    if (comparison_.kind == Comparison::Kind::Off) {
        compareEnvironments_.reset();
        compareDocument_.reset();
        if (compareRenderer_ && compareRenderer_->isInitialized()) {
            makeCurrent();
            compareRenderer_->destroy();
            doneCurrent();
        }
        compareRenderer_.reset();
    } else {
        if (!compareDocument_) {
            compareDocument_ = std::make_unique<SceneDocument>();
            compareEnvironments_ = std::make_unique<EnvironmentManager>();
            connect(compareEnvironments_.get(), &EnvironmentManager::environmentReady, this,
                    qOverload<>(&QWidget::update));
            connect(compareEnvironments_.get(), &EnvironmentManager::lobesReady, this,
                    qOverload<>(&QWidget::update));
            connect(compareEnvironments_.get(), &EnvironmentManager::failed, this, &Viewport::comparisonFailed);
            // The same file (a builder or a material compared): no second read of it; the right
            // half draws the left's environment until its own is built ("building…" over it).
            const std::shared_ptr<const PreparedEnvironment> shared = environments_->current();
            if (shared && comparison_.kind != Comparison::Kind::Environment)
                compareEnvironments_->startFrom(shared);
            compareDocument_->resetScene(comparedScene(document_->scene()));
            compareEnvironments_->watch(compareDocument_.get());
        }
        syncComparison();
    }
    emit comparisonChanged();
    update();
}

void Viewport::setDividerFraction(float fraction) {
    if (!std::isfinite(fraction)) return;
    divider_ = std::clamp(fraction, 0.05f, 0.95f);
    update();
}

Scene Viewport::comparedScene(const Scene& shown) const {
    Scene scene = shown;
    switch (comparison_.kind) {
        case Comparison::Kind::Off: break;
        case Comparison::Kind::Builder: scene.environment.builder = comparison_.builder; break;
        case Comparison::Kind::Environment:
            scene.environment.source = comparison_.environment;
            scene.environment.layout = EnvLayout::Auto;
            break;
        case Comparison::Kind::Material: {
            const int index = document_->selected();
            if (!document_->isValidIndex(index)) break;
            const std::string name = comparison_.materialName.toStdString();
            const MaterialId id = scene.addMaterial(name.empty() ? std::string("compared") : name, comparison_.material);
            scene.objects[static_cast<std::size_t>(index)].material = id;
            break;
        }
    }
    return scene;
}

void Viewport::syncComparison() {
    if (!compareDocument_) return;
    // The shadow follows the scene; its environment manager asks for what it needs (a change of
    // λ or of the selection builds no chain, only stack entries).
    Scene scene = comparedScene(document_->scene());
    if (scene == compareDocument_->scene()) return;
    compareDocument_->resetScene(std::move(scene));
}

QString Viewport::leftLabel() const {
    const EnvironmentSettings& s = document_->scene().environment;
    QString text = QStringLiteral("%1 · %2").arg(QString::fromLatin1(builderName(s.builder)),
                                                environmentDisplayName(s.source));
    if (comparison_.kind == Comparison::Kind::Material && document_->isValidIndex(document_->selected())) {
        if (const NamedMaterial* m = document_->namedMaterialOf(document_->selected()))
            text = QString::fromStdString(m->name);
    }
    return text;
}

QString Viewport::rightLabel() const {
    const EnvironmentSettings& s = document_->scene().environment;
    switch (comparison_.kind) {
        case Comparison::Kind::Off: return {};
        case Comparison::Kind::Builder:
            return QStringLiteral("%1 · %2").arg(QString::fromLatin1(builderName(comparison_.builder)),
                                                environmentDisplayName(s.source));
        case Comparison::Kind::Environment:
            return QStringLiteral("%1 · %2").arg(QString::fromLatin1(builderName(s.builder)),
                                                environmentDisplayName(comparison_.environment));
        case Comparison::Kind::Material:
            return document_->isValidIndex(document_->selected()) ? comparison_.materialName
                                                                  : tr("select an object to compare");
    }
    return {};
}

// ---------------------------------------------------------------------------------------------
// Mouse

int Viewport::pickObject(QPoint position) const {
    const Scene& scene = document_->scene();
    return firstObjectHit(scene, pixelRay(shownView().camera, scene, width(), height(), position.x(), position.y()));
}

void Viewport::mousePressEvent(QMouseEvent* event) {
    pressPos_ = lastPos_ = event->position().toPoint();
    dragButton_ = event->button();
    dragged_ = false;
    const Qt::KeyboardModifiers mods = event->modifiers();
    if (comparing() && dragButton_ == Qt::LeftButton && std::abs(pressPos_.x() - dividerX()) <= kDividerGrab)
        drag_ = Drag::Divider;
    else if ((dragButton_ == Qt::LeftButton && (mods & Qt::ControlModifier)) ||
             (dragButton_ == Qt::RightButton && (mods & Qt::ShiftModifier)))
        drag_ = Drag::Environment;
    else if (dragButton_ == Qt::RightButton || dragButton_ == Qt::MiddleButton ||
             (dragButton_ == Qt::LeftButton && (mods & Qt::ShiftModifier)))
        drag_ = Drag::Pan;
    else if (dragButton_ == Qt::LeftButton)
        drag_ = Drag::Orbit;
    else
        drag_ = Drag::None;
    if (drag_ == Drag::Environment) environmentDragKey_ = SceneDocument::newMergeKey();
}

void Viewport::mouseMoveEvent(QMouseEvent* event) {
    const QPoint pos = event->position().toPoint();
    if (dragButton_ == Qt::NoButton) {
        const bool overDivider = comparing() && std::abs(pos.x() - dividerX()) <= kDividerGrab;
        setCursor(overDivider ? Qt::SplitHCursor : Qt::ArrowCursor);
        return;
    }
    const QPoint delta = pos - lastPos_;
    lastPos_ = pos;
    if ((pos - pressPos_).manhattanLength() > 3) dragged_ = true;
    const float h = static_cast<float>(std::max(height(), 1));
    switch (drag_) {
        case Drag::None: return;
        case Drag::Divider:
            setDividerFraction(static_cast<float>(pos.x()) / static_cast<float>(std::max(width(), 1)));
            return;
        case Drag::Environment: {
            // The environment follows the cursor as the view does when orbiting: drag right, it
            // turns right. One undo step per drag ("Rotate environment").
            DisplaySettings d = document_->scene().display;
            d.environmentRotationDegrees = static_cast<float>(std::remainder(
                static_cast<double>(d.environmentRotationDegrees) +
                    static_cast<double>(kEnvironmentDegreesPerPixel) * delta.x(), 360.0));
            document_->setDisplay(d, environmentDragKey_);
            return;
        }
        case Drag::Pan:
            camera_.pan(static_cast<float>(delta.x()) / h, static_cast<float>(delta.y()) / h);
            break;
        case Drag::Orbit:
            camera_.orbit(-0.4f * static_cast<float>(delta.x()), 0.4f * static_cast<float>(delta.y()));
            break;
    }
    emit cameraChanged();
    update();
}

void Viewport::mouseReleaseEvent(QMouseEvent* event) {
    if (!dragged_ && event->button() == Qt::LeftButton && drag_ != Drag::Divider)
        emit objectClicked(pickObject(event->position().toPoint()));
    const bool wasDragging = dragged_;
    dragButton_ = Qt::NoButton;
    drag_ = Drag::None;
    if (wasDragging) update();  // the full-quality frame
}

void Viewport::wheelEvent(QWheelEvent* event) {
    const float steps = static_cast<float>(event->angleDelta().y()) / 120.0f;
    const float factor = std::pow(0.85f, steps);
    // Toward what is under the cursor (view_gestures.h), as in Blender and Toolbag.
    const QPoint at = event->position().toPoint();
    const Scene& scene = document_->scene();
    const OrbitCamera shown = shownView().camera;
    const Ray ray = pixelRay(shown, scene, std::max(width(), 1), std::max(height(), 1), at.x(), at.y());
    // The turntable's turn (about the target's vertical axis) commutes with a scaling about any
    // point, so scaling the unturned camera about the pivot seen in the turned view is right.
    if (const std::optional<glm::vec3> pivot = zoomPivot(scene, shown, ray))
        zoomToward(camera_, *pivot, factor);
    else
        camera_.zoom(factor);
    emit cameraChanged();
    update();
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
