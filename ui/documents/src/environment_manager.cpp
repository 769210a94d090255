#include "mipgloss/ui/environment_manager.h"

#include "mipgloss/ui/scene_document.h"

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QThread>

#include <algorithm>
#include <atomic>
#include <exception>
#include <iostream>

namespace mipgloss::ui {

namespace {
// True when a job for (a, na) makes what (b, nb) asks for: the same environment filtered at least
// as deep, with the irradiance map and the remainder's filter if b needs them.
bool covers(const EnvironmentSettings& a, const ChainNeeds& na, const EnvironmentSettings& b, const ChainNeeds& nb) {
    return a == b && na.lastFilteredLevel >= nb.lastFilteredLevel && (na.irradiance || !nb.irradiance) &&
           na.remainderReach >= nb.remainderReach;
}
}  // namespace

EnvironmentManager::EnvironmentManager(QObject* parent)
    : QObject(parent), worker_(new BackgroundWorker(this)), settle_(new QTimer(this)) {
    connect(worker_, &BackgroundWorker::progress, this, &EnvironmentManager::progress);
    settle_->setSingleShot(true);
    settle_->setInterval(kSettleMs);
    connect(settle_, &QTimer::timeout, this, [this] {
        lobesWanted_ = true;
        if (!busy_ && !lobeBusy_) startLobeJob();
    });
}

EnvironmentManager::~EnvironmentManager() {
    // Before members go: the worker's jobs call back into them.
    delete worker_;
}

std::vector<std::shared_ptr<const LobeStackEntry>> EnvironmentManager::lobes() const {
    std::vector<std::shared_ptr<const LobeStackEntry>> out;
    for (const auto& [key, lobe] : lobes_) out.push_back(lobe);
    return out;
}

void EnvironmentManager::scheduleLobes() {
    // λ moved (or the scene changed): a lobe job for the old values is obsolete; wait until
    // the values rest.
    if (lobeJob_) lobeJob_->cancel();
    settle_->start();
}

void EnvironmentManager::startLobeJob() {
    lobesWanted_ = false;
    if (!document_ || !current_ || !current_->filter) return;
    // Lobes of an environment that is no longer current go.
    const auto stale = std::erase_if(lobes_, [&](const auto& entry) { return entry.second->filter != current_->filter; });
    if (stale > 0) emit lobesReady();
    // The stack's entries the scene shows come first, in one job; then the rest of the stack,
    // nearest first, one per job, so moving λ again loses at most one.
    const int baseSize = current_->filter->baseSize();
    const std::vector<int> inUse = lobesInUse(document_->scene(), baseSize);
    const std::vector<int> near = lobesNear(inUse, baseSize);
    // Keys (lobes.h, stackKey): the whole environment's entries, then the remainder's the GGX
    // layers read (only those in use: none is made ahead).
    std::vector<int> inUseKeys = inUse;
    if (current_->remainderFilter)
        for (int index : remainderEntries(document_->scene(), baseSize, current_->lights))
            inUseKeys.push_back(stackKey(index, true));
    std::vector<int> missing;
    for (int key : inUseKeys)
        if (!lobes_.count(key)) missing.push_back(key);
    const bool forInUse = !missing.empty();
    if (!forInUse) {
        if (lobeJob_) return;  // an entry near them is being made; its end starts the next
        for (int index : near)
            if (!lobes_.count(index)) {
                missing.push_back(index);
                break;
            }
    } else if (lobeJob_) {
        lobeJob_->cancel();  // a near entry's job: what is in use goes first
    }
    // Keep what is in use or will be made next (the whole stack of faces up to 512), drop the
    // rest: sharp entries of a big base no lobe reads any more.
    const auto dropped = std::erase_if(lobes_, [&](const auto& entry) {
        return std::find(inUseKeys.begin(), inUseKeys.end(), entry.first) == inUseKeys.end() &&
               std::find(near.begin(), near.end(), entry.first) == near.end();
    });
    if (dropped > 0) emit lobesReady();
    if (missing.empty()) return;
    // Only the entries in use make the manager busy (the picture is not settled without them);
    // those near them are made quietly behind.
    if (forInUse) {
        lobeBusy_ = true;
        emit busyChanged(true);
    }
    const std::shared_ptr<const PreparedEnvironment> environment = current_;
    lobeJob_ = worker_->start(
        [environment, missing](Job& job) {
            std::vector<std::shared_ptr<const LobeStackEntry>> made;
            try {
                for (int key : missing) {
                    if (job.cancelled()) break;
                    made.push_back(std::make_shared<const LobeStackEntry>(
                        makeStackEntry(*environment, stackKeyIndex(key), isRemainderKey(key))));
                }
            } catch (const std::exception& e) {
                std::cerr << "mipgloss: lobe stack entry: " << e.what() << '\n';
            }
            return made;
        },
        [this, forInUse](JobOutcome<std::vector<std::shared_ptr<const LobeStackEntry>>>&& outcome, const Job& job) {
            if (forInUse) lobeBusy_ = false;
            if (lobeJob_.get() == &job) lobeJob_.reset();
            // Only lobes of the environment still current are kept.
            bool changed = false;
            for (const auto& lobe : outcome.value.value_or(std::vector<std::shared_ptr<const LobeStackEntry>>{}))
                if (current_ && lobe->filter == current_->filter) {
                    lobes_[stackKey(*lobe)] = lobe;
                    ++counters_.lobeBuilds;
                    changed = true;
                }
            // Entries near those in use change nothing on screen: the view takes them at its
            // next frame (it hands the renderer lobes() every frame), so no frame is drawn for
            // them while the user is idle.
            if (changed && forInUse) emit lobesReady();
            // Then the next entry (startLobeJob returns when none is missing), unless λ is moving
            // (the settle timer starts it when it rests).
            if (!busy_ && !lobeJob_ && !settle_->isActive() && (lobesWanted_ || !job.cancelled())) startLobeJob();
            if (!busy()) emit busyChanged(false);
        });
}

void EnvironmentManager::watch(SceneDocument* document) {
    document_ = document;
    auto update = [this] {
        if (!document_) return;
        const Scene& scene = document_->scene();
        request(scene.environment, chainNeeds(scene, scene.environment.faceSize));
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
    const EnvironmentSettings& wanted = settings;
    if (haveFailed_ && wanted == failedSettings_) return;  // do not retry a file that failed
    if (current_ && current_->satisfies(wanted, needs)) {
        haveRequest_ = false;
        if (runningJob_) runningJob_->cancel();  // a job for something else is obsolete
        return;
    }
    // The environment drawn before the running job's early one is asked for again (an open undone
    // while its chain is built): it is still here, drawn again at once.
    if (busy_ && jobStart_ && jobStart_ != current_ && jobStart_->satisfies(wanted, needs)) {
        haveRequest_ = false;
        if (runningJob_) runningJob_->cancel();
        current_ = jobStart_;
        emit environmentReady();
        return;
    }
    const bool running = busy_ && runningJob_ && !runningJob_->cancelled();
    if (running && covers(runningSettings_, runningNeeds_, wanted, needs)) {
        haveRequest_ = false;  // on its way (a scene edit that changes nothing the build needs)
        return;
    }
    if (haveRequest_ && wanted == wantedSettings_ && needs == wantedNeeds_ && busy_) return;
    wantedSettings_ = wanted;
    wantedNeeds_ = needs;
    haveRequest_ = true;
    if (busy_) {
        // The newest request wins (onJobFinished starts it), but a job still reading the same file
        // the same way goes on to its early environment, which the next job starts from: a λ or
        // builder change during a long import does not read the file again.
        const bool sameFileImporting = running && importing_ && sameImport(runningSettings_, wanted);
        if (runningJob_ && !sameFileImporting) runningJob_->cancel();
        return;
    }
    startJob();
}

void EnvironmentManager::startJob() {
    haveRequest_ = false;
    busy_ = true;
    emit busyChanged(true);
    const EnvironmentSettings settings = wantedSettings_;
    const ChainNeeds needs = wantedNeeds_;
    runningSettings_ = settings;
    runningNeeds_ = needs;
    const std::shared_ptr<const PreparedEnvironment> previous = current_;
    jobStart_ = current_;
    const bool imports = !previous || !previous->sameImport(settings);
    importing_ = imports;

    // Whether the job read its file before it stopped (set on the worker, read in `done`).
    auto imported = std::make_shared<std::atomic<bool>>(false);
    runningJob_ = worker_->start(
        [settings, needs, previous, imported, this](Job& job) {
            // Posted like progress, so the UI sees the early environment after the import's
            // reports and before the build's, and before onJobFinished.
            auto onImported = [&](const std::shared_ptr<const PreparedEnvironment>& early) {
                *imported = true;
                Job* posting = &job;
                job.post([this, early, posting] { this->onImported(early, posting); });
            };
            return std::make_shared<PreparedEnvironment>(
                prepareEnvironment(settings, needs, previous.get(), job.asProgress(), onImported));
        },
        [this, imports, imported](JobOutcome<std::shared_ptr<PreparedEnvironment>>&& outcome, const Job& job) {
            onJobFinished(outcome.value.value_or(nullptr), outcome.error, job.cancelled(),
                          outcome.cutShort && imports && !*imported);
        });
}

void EnvironmentManager::startFrom(std::shared_ptr<const PreparedEnvironment> environment) {
    if (current_ || busy_ || !environment) return;
    adopt(std::move(environment));
}

void EnvironmentManager::adopt(std::shared_ptr<const PreparedEnvironment> next) {
    current_ = std::move(next);
    emit environmentReady();
}

void EnvironmentManager::onImported(std::shared_ptr<const PreparedEnvironment> early, const Job* job) {
    ++counters_.imports;  // read, whether drawn or not
    // A job cancelled while it read its file (another file was asked for) is never drawn.
    if (job != runningJob_.get() || job->cancelled()) return;
    importing_ = false;
    adopt(std::move(early));
    ++counters_.earlyEnvironments;
    // A request for this same file with other needs or builder waited for the import (request):
    // this job's chain is not what it asks for, so the next job starts now, from this base.
    if (haveRequest_) runningJob_->cancel();
}

void EnvironmentManager::onJobFinished(std::shared_ptr<PreparedEnvironment> result, const QString& error,
                                       bool cancelled, bool importCutShort) {
    counters_.importsCancelled += importCutShort ? 1 : 0;
    if (result) {
        // What the job made rather than reused from the environment it started from, kept or not
        // (its import was counted in onImported).
        const PreparedEnvironment* from = jobStart_.get();
        counters_.chainBuilds += !from || result->chain != from->chain ? 1 : 0;
        counters_.irradianceBuilds += result->irradiance && (!from || result->irradiance != from->irradiance) ? 1 : 0;
    }
    if (!error.isEmpty()) {
        ++counters_.failures;
        failedSettings_ = runningSettings_;  // not wantedSettings_: a newer request may be queued
        haveFailed_ = true;
        // Its early environment, if it came, goes: what was drawn before is drawn again (before
        // `failed`, whose handlers read current()).
        if (current_ != jobStart_) {
            current_ = jobStart_;
            emit environmentReady();
        }
        std::cerr << "mipgloss: " << error.toStdString() << '\n';
        emit failed(error);
    } else if (result && (!cancelled || (haveRequest_ && result->satisfies(wantedSettings_, wantedNeeds_)))) {
        // A cancelled job that finished anyway is kept only when it is what the newest request
        // asks for.
        adopt(std::move(result));
        haveFailed_ = false;
        lobesWanted_ = true;  // the new environment's lobes
    }
    runningJob_.reset();
    jobStart_.reset();
    importing_ = false;
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
