#include "mipgloss/ui/environment_manager.h"

#include "mipgloss/ui/scene_document.h"

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QMetaObject>
#include <QPointer>
#include <QThread>
#include <QThreadPool>
#include <QtConcurrent/QtConcurrentRun>

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

EnvironmentManager::EnvironmentManager(QObject* parent) : QObject(parent) {}

EnvironmentManager::~EnvironmentManager() {
    if (cancelRunning_) *cancelRunning_ = true;
    workerPool().waitForDone();
}

void EnvironmentManager::watch(SceneDocument* document) {
    document_ = document;
    auto update = [this] {
        if (!document_) return;
        const Scene& scene = document_->scene();
        request(scene.environment, needsFor(scene, scene.environment.faceSize));
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
    emit busyChanged(false);
}

bool EnvironmentManager::waitUntilIdle(int timeoutMs) {
    QDeadlineTimer deadline(timeoutMs);
    while (busy_ && !deadline.hasExpired()) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
        QThread::msleep(2);
    }
    return !busy_;
}

}  // namespace mipgloss::ui
