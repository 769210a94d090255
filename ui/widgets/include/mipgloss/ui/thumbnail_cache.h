// The library's thumbnails (thumbnail.h), drawn under the environment the scene is shown in.
//
// The scene's own environment may have only the levels its materials reach filtered (chain_needs.h:
// "skip what the scene doesn't need"), while a library holds materials of any λ. So the cache
// prepares an environment of its own from the current one's base: resampled to a
// kThumbnailFaceSize² face, every level any λ reaches filtered by the scene's builder, with its
// irradiance map (thumbnailNeeds), on a worker thread. A new import or builder starts a new one;
// a chain that only grew deeper or a new irradiance map does not. Thumbnails show the environment
// unturned (the scene's rotation is a view setting, not the material's look).
//
// Drawing happens on the GUI thread with one OffscreenRenderer, one thumbnail per turn of the
// event loop (so the window stays responsive with hundreds of entries), and only for the rows the
// view shows (setVisibleRows). Each picture is kept by (the entry's parameters, the environment
// it was drawn under): an entry whose parameters did not change is never drawn twice, entries
// sharing parameters share one drawing, and an environment change redraws only the rows in view
// (the others keep their old picture until they are scrolled to).
#pragma once

#include "mipgloss/assets/textures.h"
#include "mipgloss/scene/environment.h"
#include "mipgloss/scene/scene.h"
#include "mipgloss/ui/background_worker.h"

#include <QObject>
#include <QPixmap>
#include <QString>
#include <QTimer>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace mipgloss::ui {

class EnvironmentManager;
class LibraryDocument;
class OffscreenRenderer;

struct ThumbnailCounters {
    std::uint64_t renders = 0;             // thumbnails drawn
    std::uint64_t environmentBuilds = 0;   // thumbnail environments prepared
};

class ThumbnailCache : public QObject {
    Q_OBJECT
public:
    static constexpr int kThumbnailSize = 96;      // logical pixels, square
    static constexpr int kThumbnailFaceSize = 64;  // the thumbnail environment's base face

    ThumbnailCache(LibraryDocument* document, EnvironmentManager* environments, QObject* parent = nullptr);
    ~ThumbnailCache() override;  // cancels and waits for the worker

    // The rows (of the document) a view shows now. Unset: every row counts as visible.
    void setVisibleRows(std::function<std::vector<int>()> visibleRows);

    // The picture for `material`: the one drawn under the current thumbnail environment, else an
    // older one (until it is redrawn), else a null pixmap.
    QPixmap thumbnail(const Material& material) const;
    // True when `material` has a picture drawn under the current thumbnail environment.
    bool isCurrent(const Material& material) const;

    // The environment thumbnails are drawn under (null until the first is ready).
    std::shared_ptr<const PreparedEnvironment> environment() const { return environment_; }
    const ThumbnailCounters& counters() const { return counters_; }
    // Why thumbnails cannot be drawn (no OpenGL context); empty when they can.
    const QString& error() const { return error_; }
    // True while an environment is prepared or visible thumbnails wait to be drawn.
    bool busy() const;

public slots:
    // The view scrolled, resized or filtered: draws whatever visible row lacks a current picture.
    void visibleRowsChanged();

signals:
    // Row `row` of the document has a new picture.
    void thumbnailChanged(int row);
    // A thumbnail environment is ready (environment() changed).
    void environmentReady();

private:
    // Material is compared field by field (colours as three floats): the cache's key.
    using Key = std::tuple<float, int, bool, float, float, float, bool, bool, float, float, float, float, float,
                           float, float, float, float, float, float, float>;
    static Key keyOf(const Material& material);
    struct Picture {
        QPixmap pixmap;
        std::uint64_t environmentVersion = 0;  // which thumbnail environment it was drawn under
    };

    void onEnvironmentReady();
    void startBuild(const std::shared_ptr<const PreparedEnvironment>& source);
    bool builtFrom(const PreparedEnvironment& source) const;
    void schedule();
    void drawNext();
    std::vector<int> visibleRows() const;

    LibraryDocument* document_;
    EnvironmentManager* environments_;
    std::function<std::vector<int>()> visibleRows_;
    std::unique_ptr<OffscreenRenderer> renderer_;
    // The thumbnails' own decoded maps (textures.h: a cache is its user's, never the process's).
    std::shared_ptr<TextureCache> textures_ = std::make_shared<TextureCache>();
    bool rendererTried_ = false;
    QString error_;

    std::shared_ptr<const PreparedEnvironment> environment_;
    std::uint64_t environmentVersion_ = 0;  // counts environments made; 0: none yet
    // What the current (or running) build was made from: its base and builder.
    std::shared_ptr<const CubeMap> builtFromBase_;
    Builder builtWithBuilder_ = kDefaultBuilder;
    std::shared_ptr<const PreparedEnvironment> pendingSource_;  // newest wanted while a build runs
    bool building_ = false;
    BackgroundWorker* worker_;  // builds thumbnail environments; cancelled by the destructor

    std::map<Key, Picture> pictures_;
    QTimer* drawTimer_ = nullptr;
    ThumbnailCounters counters_;
};

}  // namespace mipgloss::ui
