#include "mipgloss/ui/background_worker.h"

#include <algorithm>

namespace mipgloss::ui {

bool Job::progress(const std::string& stage, float fraction) {
    if (cancelled()) return false;
    BackgroundWorker* worker = worker_;
    post([worker, stage = QString::fromStdString(stage), fraction] { emit worker->progress(stage, fraction); });
    return true;
}

void Job::post(std::function<void()> f) {
    // Queued to the worker object: run on its thread, in order, and dropped if it is deleted first.
    QMetaObject::invokeMethod(worker_, std::move(f), Qt::QueuedConnection);
}

BackgroundWorker::BackgroundWorker(QObject* parent) : QObject(parent) {
    // One thread: jobs run one after another, in the order they were started.
    pool_.setMaxThreadCount(1);
}

BackgroundWorker::~BackgroundWorker() {
    cancelAll();
    pool_.waitForDone();
}

void BackgroundWorker::cancelAll() {
    for (const std::weak_ptr<Job>& weak : jobs_)
        if (const std::shared_ptr<Job> job = weak.lock()) job->cancel();
}

void BackgroundWorker::forget(const Job* job) {
    std::erase_if(jobs_, [job](const std::weak_ptr<Job>& weak) {
        const std::shared_ptr<Job> held = weak.lock();
        return !held || held.get() == job;
    });
}

}  // namespace mipgloss::ui
