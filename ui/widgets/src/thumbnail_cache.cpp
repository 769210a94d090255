#include "mipgloss/ui/thumbnail_cache.h"

#include "mipgloss/ibl/irradiance.h"
#include "mipgloss/ibl/resample.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/offscreen.h"
#include "mipgloss/ui/thumbnail.h"

#include <QGuiApplication>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <set>

namespace mipgloss::ui {

namespace {

// The thumbnail environment: `source`'s base at `faceSize` (or smaller when it is smaller), its
// chain filtered through every level a λ reaches, and its irradiance map. Runs on the worker;
// throws Cancelled when `job` is cancelled.
std::shared_ptr<const PreparedEnvironment> prepareThumbnailEnvironment(const PreparedEnvironment& source,
                                                                       int faceSize, const Job& job) {
    auto out = std::make_shared<PreparedEnvironment>();
    out->settings = source.settings;
    out->report = source.report;
    const int size = std::min(faceSize, source.base->size());
    out->base = size == source.base->size() ? source.base
                                            : std::make_shared<const CubeMap>(resampleCube(*source.base, size));
    out->settings.faceSize = size;
    const ChainNeeds needs = thumbnailNeeds(size);
    BuildOptions options;
    options.lastFilteredLevel = needs.lastFilteredLevel;
    options.progress = [&job](const std::string&, float) { return !job.cancelled(); };
    out->chain = std::make_shared<const MipChain>(buildChain(*out->base, source.settings.builder, options));
    out->lastFilteredLevel = needs.lastFilteredLevel;
    if (job.cancelled()) throw Cancelled{};
    out->irradiance = std::make_shared<const CubeMap>(computeIrradiance(*out->base));
    return out;
}

}  // namespace

ThumbnailCache::ThumbnailCache(LibraryDocument* document, EnvironmentManager* environments, QObject* parent)
    : QObject(parent),
      document_(document),
      environments_(environments),
      worker_(new BackgroundWorker(this)),
      drawTimer_(new QTimer(this)) {
    // One thumbnail per turn of the event loop: input and repaints get their turn in between.
    drawTimer_->setSingleShot(true);
    drawTimer_->setInterval(0);
    connect(drawTimer_, &QTimer::timeout, this, &ThumbnailCache::drawNext);
    connect(environments_, &EnvironmentManager::environmentReady, this, &ThumbnailCache::onEnvironmentReady);
    connect(document_, &LibraryDocument::entryInserted, this, &ThumbnailCache::schedule);
    connect(document_, &LibraryDocument::entryChanged, this, &ThumbnailCache::schedule);
    connect(document_, &LibraryDocument::entryMoved, this, &ThumbnailCache::schedule);
    connect(document_, &LibraryDocument::reset, this, &ThumbnailCache::schedule);
    onEnvironmentReady();
}

ThumbnailCache::~ThumbnailCache() {
    // Before members go: the worker's job calls back into them.
    delete worker_;
}

void ThumbnailCache::setVisibleRows(std::function<std::vector<int>()> visibleRows) {
    visibleRows_ = std::move(visibleRows);
    schedule();
}

ThumbnailCache::Key ThumbnailCache::keyOf(const Material& m) {
    const Layers& l = m.layers;
    return {m.lambda,      static_cast<int>(m.mode), m.useIrradiance, m.tint.r,    m.tint.g,  m.tint.b,
            m.sharperAtGrazing, m.layered,         l.baseColor.r,   l.baseColor.g, l.baseColor.b, l.metallic,
            l.roughness,   l.specular,               l.coat,          l.coatRoughness,
            l.specularColor.r, l.specularColor.g, l.specularColor.b, l.specularWeight};
}

QPixmap ThumbnailCache::thumbnail(const Material& material) const {
    const auto it = pictures_.find(keyOf(material));
    return it == pictures_.end() ? QPixmap() : it->second.pixmap;
}

bool ThumbnailCache::isCurrent(const Material& material) const {
    const auto it = pictures_.find(keyOf(material));
    return it != pictures_.end() && environmentVersion_ != 0 && it->second.environmentVersion == environmentVersion_;
}

bool ThumbnailCache::busy() const {
    if (building_) return true;
    if (!environment_ || !error_.isEmpty()) return false;
    for (int row : visibleRows())
        if (!isCurrent(document_->entry(row).material)) return true;
    return false;
}

void ThumbnailCache::visibleRowsChanged() { schedule(); }

std::vector<int> ThumbnailCache::visibleRows() const {
    std::vector<int> rows;
    if (visibleRows_) {
        rows = visibleRows_();
        std::erase_if(rows, [this](int row) { return !document_->isValidRow(row); });
    } else {
        for (int row = 0; row < document_->count(); ++row) rows.push_back(row);
    }
    return rows;
}

bool ThumbnailCache::builtFrom(const PreparedEnvironment& source) const {
    return source.base == builtFromBase_ && source.settings.builder == builtWithBuilder_;
}

void ThumbnailCache::onEnvironmentReady() {
    const std::shared_ptr<const PreparedEnvironment> source = environments_->current();
    if (!source || !source->base) return;
    // The scene's chain grew deeper, or got an irradiance map: the thumbnails' already has both.
    if (builtFrom(*source)) {
        pendingSource_.reset();
        return;
    }
    if (building_) {
        pendingSource_ = source;  // the newest wins; started when the running build ends
        return;
    }
    startBuild(source);
}

void ThumbnailCache::startBuild(const std::shared_ptr<const PreparedEnvironment>& source) {
    builtFromBase_ = source->base;
    builtWithBuilder_ = source->settings.builder;
    building_ = true;
    worker_->start(
        [source](Job& job) {
            try {
                return prepareThumbnailEnvironment(*source, kThumbnailFaceSize, job);
            } catch (const Cancelled&) {
                throw;
            } catch (const std::exception& e) {
                std::cerr << "mipgloss: thumbnail environment: " << e.what() << '\n';
                return std::shared_ptr<const PreparedEnvironment>();
            }
        },
        [this](JobOutcome<std::shared_ptr<const PreparedEnvironment>>&& outcome, const Job&) {
            building_ = false;
            if (const std::shared_ptr<const PreparedEnvironment> made = outcome.value.value_or(nullptr)) {
                environment_ = made;
                ++environmentVersion_;
                ++counters_.environmentBuilds;
                // Pictures of parameters no entry has any more go; the others stay on show until
                // their rows are redrawn.
                std::set<Key> used;
                for (const LibraryMaterial& entry : document_->library().entries) used.insert(keyOf(entry.material));
                std::erase_if(pictures_, [&](const auto& picture) { return !used.count(picture.first); });
                emit environmentReady();
            }
            if (pendingSource_) {
                const auto next = std::move(pendingSource_);
                pendingSource_.reset();
                if (!builtFrom(*next)) startBuild(next);
            }
            schedule();
        });
}

void ThumbnailCache::schedule() {
    if (!drawTimer_->isActive()) drawTimer_->start();
}

void ThumbnailCache::drawNext() {
    if (!environment_ || !error_.isEmpty()) return;
    for (int row : visibleRows()) {
        const Material material = document_->entry(row).material;
        if (isCurrent(material)) continue;
        if (!rendererTried_) {
            rendererTried_ = true;
            auto renderer = std::make_unique<OffscreenRenderer>();
            std::string error;
            if (!renderer->initialize(&error)) {
                error_ = tr("Thumbnails cannot be drawn: %1").arg(QString::fromStdString(error));
                std::cerr << "mipgloss: " << error_.toStdString() << '\n';
                return;
            }
            renderer_ = std::move(renderer);
        }
        const qreal ratio = qGuiApp ? qGuiApp->devicePixelRatio() : 1.0;
        const int pixels = static_cast<int>(std::lround(kThumbnailSize * ratio));
        QPixmap pixmap = QPixmap::fromImage(renderThumbnail(*renderer_, textures_, material, environment_, pixels));
        pixmap.setDevicePixelRatio(ratio);
        pictures_[keyOf(material)] = {pixmap, environmentVersion_};
        ++counters_.renders;
        // Every entry with these parameters shows the new picture, visible or not.
        const Key key = keyOf(material);
        for (int r = 0; r < document_->count(); ++r)
            if (keyOf(document_->entry(r).material) == key) emit thumbnailChanged(r);
        schedule();  // the next one on the next turn
        return;
    }
}

}  // namespace mipgloss::ui
