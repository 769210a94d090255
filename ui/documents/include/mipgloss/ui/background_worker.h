// The one way mipgloss runs work off the UI thread: the environment manager's imports, chain and
// lobe builds, the thumbnail cache's environments and the mesh importer's large files all go
// through a BackgroundWorker.
//
// A worker owns one thread, so its jobs run one after another in the order they were started.
// Each job gets a Job: the worker side reads cancelled() (and passes progress() to core's builders
// as their Progress: it answers false once cancelled, and the builder throws Cancelled), and posts
// what the UI should see before the end (an early environment) with post(). The job's result,
// progress reports and posts all arrive on the worker's (the UI) thread, queued, in the order the
// job made them, and never after the worker is gone: its destructor cancels every job and waits
// for them, so a window closed mid-build neither waits for a whole build nor receives a result.
#pragma once

#include "mipgloss/ibl/progress.h"

#include <QMetaObject>
#include <QObject>
#include <QString>
#include <QThreadPool>

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mipgloss::ui {

class BackgroundWorker;

// One job's shared state: the cancel flag and the door back to the UI thread. Held by the running
// work and by whoever may cancel it; jobs are told apart by their address.
class Job {
public:
    explicit Job(BackgroundWorker* worker) : worker_(worker) {}

    bool cancelled() const noexcept { return cancelled_.load(std::memory_order_relaxed); }
    void cancel() noexcept { cancelled_.store(true, std::memory_order_relaxed); }

    // From the job: reports progress to the worker's progress handler (queued to the UI thread).
    // False once the job is cancelled, so `[&job](auto& s, float f) { return job.progress(s, f); }`
    // is a core Progress that stops the work.
    bool progress(const std::string& stage, float fraction);
    // From the job: runs `f` on the UI thread, after what the job posted before and before its
    // result, unless the worker is gone by then.
    void post(std::function<void()> f);

    // A core Progress reporting through this job.
    Progress asProgress() {
        return [this](const std::string& stage, float fraction) { return progress(stage, fraction); };
    }

private:
    std::atomic<bool> cancelled_{false};
    // Set at construction on the UI thread; the worker outlives every job (its destructor waits).
    BackgroundWorker* worker_;
};

// What a job's work came to, handed to its `done` on the UI thread.
template <class Result>
struct JobOutcome {
    std::optional<Result> value;  // what the work returned
    bool cutShort = false;        // the work threw Cancelled (it was cancelled and stopped)
    QString error;                // what it threw otherwise (the exception's message)
};

class BackgroundWorker : public QObject {
    Q_OBJECT
public:
    explicit BackgroundWorker(QObject* parent = nullptr);
    ~BackgroundWorker() override;  // cancels every job and waits for them

    // Runs `work(Job&)` on the worker's thread, then `done(JobOutcome<Result>&&, const Job&)` on
    // this object's thread. Exceptions the work lets through become the outcome's cutShort (for
    // Cancelled) or error; none reaches the thread pool.
    template <class Work, class Done>
    std::shared_ptr<Job> start(Work work, Done done);

    // Jobs started and not yet done (their `done` not yet run).
    int running() const { return running_; }
    bool busy() const { return running_ > 0; }
    void cancelAll();

signals:
    // A job's progress (Job::progress), on this object's thread.
    void progress(const QString& stage, double fraction);

private:
    friend class Job;
    QThreadPool pool_;
    int running_ = 0;
    // Every job not yet done, so the destructor can cancel them (a job removes itself when done).
    std::vector<std::weak_ptr<Job>> jobs_;
    void forget(const Job* job);
};

template <class Work, class Done>
std::shared_ptr<Job> BackgroundWorker::start(Work work, Done done) {
    using Result = std::invoke_result_t<Work&, Job&>;
    auto job = std::make_shared<Job>(this);
    jobs_.push_back(job);
    ++running_;
    pool_.start([this, job, work = std::move(work), done = std::move(done)]() mutable {
        JobOutcome<Result> outcome;
        try {
            outcome.value.emplace(work(*job));
        } catch (const Cancelled&) {
            outcome.cutShort = true;
        } catch (const std::exception& e) {
            outcome.error = QString::fromStdString(e.what());
            if (outcome.error.isEmpty()) outcome.error = QStringLiteral("unknown error");
        } catch (...) {
            outcome.error = QStringLiteral("unknown error");
        }
        // Queued to this object: Qt drops it if the worker is deleted before it runs.
        QMetaObject::invokeMethod(
            this,
            [this, job, outcome = std::move(outcome), done = std::move(done)]() mutable {
                --running_;
                forget(job.get());
                done(std::move(outcome), static_cast<const Job&>(*job));
            },
            Qt::QueuedConnection);
    });
    return job;
}

}  // namespace mipgloss::ui
