#include "mipgloss/ui/environment_manager.h"

#include "mipgloss/ui/scene_document.h"

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QMetaObject>
#include <QPointer>
#include <QThread>
#include <QThreadPool>
#include <QtConcurrent/QtConcurrentRun>

#include <algorithm>
#include <exception>
#include <iostream>

namespace mipgloss::ui {

namespace {
// One worker: jobs run one after another, the newest request wins.
QThreadPool& workerPool() {
    static QThreadPool* pool = [] {
        auto* p = new QThreadPool;
        p->setMaxThreadCount(1);
        return p;
    }();
    return *pool;
}
}  // namespace

EnvironmentManager::EnvironmentManager(QObject* parent) : QObject(parent), settle_(new QTimer(this)) {
    settle_->setSingleShot(true);
    settle_->setInterval(kSettleMs);
    connect(settle_, &QTimer::timeout, this, [this] {
        lobesWanted_ = true;
        if (!busy_ && !lobeBusy_) startLobeJob();
    });
}

EnvironmentManager::~EnvironmentManager() {
    if (cancelRunning_) *cancelRunning_ = true;
    if (cancelLobes_) *cancelLobes_ = true;
    workerPool().waitForDone();
}

std::vector<std::shared_ptr<const LobeCube>> EnvironmentManager::lobes() const {
    std::vector<std::shared_ptr<const LobeCube>> out;
    for (const auto& [key, lobe] : lobes_) out.push_back(lobe);
    return out;
}

void EnvironmentManager::scheduleLobes() {
    // λ moved (or the scene changed): a lobe job for the old values is obsolete; wait until
    // the values rest.
    if (cancelLobes_) *cancelLobes_ = true;
    settle_->start();
}

void EnvironmentManager::startLobeJob() {
    lobesWanted_ = false;
    if (!document_ || !current_ || !current_->filter) return;
    // Lobes of an environment that is no longer current go.
    const auto stale = std::erase_if(lobes_, [&](const auto& entry) { return entry.second->filter != current_->filter; });
    if (stale > 0) emit lobesReady();
    const std::vector<int> inUse = lobesInUse(document_->scene());
    std::vector<int> missing;
    for (int key : inUse)
        if (!lobes_.count(key)) missing.push_back(key);
    // Keep what is in use and up to 8 others (a slider going back and forth), drop the rest.
    if (lobes_.size() > inUse.size() + 8) {
        for (auto it = lobes_.begin(); it != lobes_.end() && lobes_.size() > inUse.size() + 8;)
            it = std::find(inUse.begin(), inUse.end(), it->first) == inUse.end() ? lobes_.erase(it) : std::next(it);
        emit lobesReady();
    }
    if (missing.empty()) return;
    lobeBusy_ = true;
    emit busyChanged(true);
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    cancelLobes_ = cancel;
    const std::shared_ptr<const PreparedEnvironment> environment = current_;
    QPointer<EnvironmentManager> self(this);
    (void)QtConcurrent::run(&workerPool(), [=] {
        std::vector<std::shared_ptr<const LobeCube>> made;
        try {
            for (int key : missing) {
                if (*cancel) break;
                made.push_back(std::make_shared<const LobeCube>(makeLobeCube(*environment, key)));
            }
        } catch (const std::exception& e) {
            std::cerr << "mipgloss: lobe cube: " << e.what() << '\n';
        }
        QMetaObject::invokeMethod(
            self, [=] {
                if (!self) return;
                self->lobeBusy_ = false;
                if (self->cancelLobes_ == cancel) self->cancelLobes_.reset();
                // Only lobes of the environment still current are kept.
                bool changed = false;
                for (const auto& lobe : made)
                    if (self->current_ && lobe->filter == self->current_->filter) {
                        self->lobes_[lobe->key] = lobe;
                        ++self->counters_.lobeBuilds;
                        changed = true;
                    }
                if (changed) emit self->lobesReady();
                if (self->lobesWanted_ && !self->busy_) self->startLobeJob();
                if (!self->busy()) emit self->busyChanged(false);
            },
            Qt::QueuedConnection);
    });
}

void EnvironmentManager::watch(SceneDocument* document) {
    document_ = document;
    auto update = [this] {
        if (!document_) return;
        const Scene& scene = document_->scene();
        request(scene.environment, needsFor(scene, scene.environment.faceSize));
        scheduleLobes();
    };
    connect(document, &SceneDocument::environmentChanged, this, update);
    connect(document, &SceneDocument::materialChanged, this, update);
    connect(document, &SceneDocument::objectsChanged, this, update);
    connect(document, &SceneDocument::objectChanged, this, update);
    connect(document, &SceneDocument::displayChanged, this, update);
    update();
}

void EnvironmentManager::request(const EnvironmentSettings& settings, const ChainNeeds& needs) {
    // Rotation is applied when drawing; it never needs a build.
    EnvironmentSettings wanted = settings;
    wanted.rotationDegrees = 0.0f;
    if (haveFailed_ && wanted == failedSettings_) return;  // do not retry a file that failed
    if (current_ && current_->satisfies(wanted, needs)) {
        haveRequest_ = false;
        if (cancelRunning_) *cancelRunning_ = true;  // a job for something else is obsolete
        return;
    }
    if (haveRequest_ && wanted == wantedSettings_ && needs == wantedNeeds_ && busy_) return;
    wantedSettings_ = wanted;
    wantedNeeds_ = needs;
    haveRequest_ = true;
    if (busy_) {
        if (cancelRunning_) *cancelRunning_ = true;  // onJobFinished starts the new one
        return;
    }
    startJob();
}

void EnvironmentManager::startJob() {
    haveRequest_ = false;
    busy_ = true;
    emit busyChanged(true);
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    cancelRunning_ = cancel;
    const EnvironmentSettings settings = wantedSettings_;
    const ChainNeeds needs = wantedNeeds_;
    runningSettings_ = settings;
    const std::shared_ptr<const PreparedEnvironment> previous = current_;
    QPointer<EnvironmentManager> self(this);

    (void)QtConcurrent::run(&workerPool(), [=] {
        std::shared_ptr<PreparedEnvironment> result;
        QString error;
        try {
            auto progress = [&](const std::string& stage, float fraction) {
                if (*cancel) return false;
                QMetaObject::invokeMethod(
                    self, [self, stage, fraction] {
                        if (self) emit self->progress(QString::fromStdString(stage), fraction);
                    },
                    Qt::QueuedConnection);
                return true;
            };
            result = std::make_shared<PreparedEnvironment>(
                prepareEnvironment(settings, needs, previous.get(), progress));
        } catch (const Cancelled&) {
            result.reset();
        } catch (const std::exception& e) {
            error = QString::fromStdString(e.what());
            if (error.isEmpty()) error = QStringLiteral("unknown error");
        }
        QMetaObject::invokeMethod(
            self, [=] {
                if (self) self->onJobFinished(result, error);
            },
            Qt::QueuedConnection);
    });
}

void EnvironmentManager::onJobFinished(std::shared_ptr<PreparedEnvironment> result, const QString& error) {
    if (!error.isEmpty()) {
        ++counters_.failures;
        failedSettings_ = runningSettings_;  // not wantedSettings_: a newer request may be queued
        haveFailed_ = true;
        std::cerr << "mipgloss: " << error.toStdString() << '\n';
        emit failed(error);
    } else if (result) {
        // What the job made rather than reused from current_ (jobs run one at a time, and only
        // this function replaces current_, so current_ is what the job started from).
        const PreparedEnvironment* before = current_.get();
        counters_.imports += !before || result->base != before->base ? 1 : 0;
        counters_.chainBuilds += !before || result->chain != before->chain ? 1 : 0;
        counters_.irradianceBuilds += result->irradiance && (!before || result->irradiance != before->irradiance) ? 1 : 0;
        current_ = std::move(result);
        haveFailed_ = false;
        emit environmentReady();
        lobesWanted_ = true;  // the new environment's lobes
    }
    cancelRunning_.reset();
    if (haveRequest_) {
        // Something newer was asked for while this ran (or this one was cancelled for it).
        if (current_ && current_->satisfies(wantedSettings_, wantedNeeds_)) {
            haveRequest_ = false;
        } else {
            startJob();
            return;
        }
    }
    busy_ = false;
    if (lobesWanted_ && !settle_->isActive()) startLobeJob();
    if (!busy()) emit busyChanged(false);
}

bool EnvironmentManager::waitUntilIdle(int timeoutMs) {
    QDeadlineTimer deadline(timeoutMs);
    while ((busy() || settle_->isActive()) && !deadline.hasExpired()) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
        QThread::msleep(2);
    }
    return !busy() && !settle_->isActive();
}

}  // namespace mipgloss::ui
