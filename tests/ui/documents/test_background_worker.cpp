// BackgroundWorker (background_worker.h): jobs run off the UI thread one after another; what they
// report, post and return arrives on the UI thread in the order they made it; a cancelled job
// stops and says so; a worker that goes away cancels its jobs, waits for them, and delivers
// nothing afterwards.
#include "mipgloss/ui/background_worker.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QThread>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace mipgloss::ui {
namespace {

// Processes events until `done()` or 10 s; false on timeout.
template <class Predicate>
bool processUntil(Predicate done) {
    QDeadlineTimer deadline(10000);
    while (!done() && !deadline.hasExpired()) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    return done();
}

// Spins until `job` is cancelled or 10 s pass; true when it was cancelled.
bool waitForCancel(const Job& job) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!job.cancelled() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return job.cancelled();
}

TEST(BackgroundWorker, RunsJobsOffTheUiThreadInOrderAndDeliversOnIt) {
    BackgroundWorker worker;
    QThread* const ui = QThread::currentThread();
    std::vector<int> delivered;
    std::vector<bool> ranOffUi, deliveredOnUi;
    for (int i = 0; i < 5; ++i)
        worker.start(
            [i, ui](Job&) {
                std::this_thread::sleep_for(std::chrono::milliseconds(5 - i));  // later ones are quicker
                return std::make_pair(i, QThread::currentThread() != ui);
            },
            [&](JobOutcome<std::pair<int, bool>>&& outcome, const Job&) {
                ASSERT_TRUE(outcome.value);
                delivered.push_back(outcome.value->first);
                ranOffUi.push_back(outcome.value->second);
                deliveredOnUi.push_back(QThread::currentThread() == ui);
            });
    EXPECT_EQ(worker.running(), 5);
    EXPECT_TRUE(worker.busy());
    ASSERT_TRUE(processUntil([&] { return !worker.busy(); }));
    EXPECT_EQ(delivered, (std::vector<int>{0, 1, 2, 3, 4}));
    EXPECT_EQ(ranOffUi, std::vector<bool>(5, true));
    EXPECT_EQ(deliveredOnUi, std::vector<bool>(5, true));
}

TEST(BackgroundWorker, ProgressAndPostsArriveInOrderBeforeTheResult) {
    BackgroundWorker worker;
    std::vector<std::string> seen;
    QObject::connect(&worker, &BackgroundWorker::progress, [&](const QString& stage, double fraction) {
        seen.push_back(stage.toStdString() + " " + std::to_string(static_cast<int>(fraction * 100)));
    });
    worker.start(
        [&seen](Job& job) {
            EXPECT_TRUE(job.progress("read", 0.0f));
            job.post([&seen] { seen.push_back("early"); });
            EXPECT_TRUE(job.progress("build", 0.5f));
            return 7;
        },
        [&](JobOutcome<int>&& outcome, const Job&) { seen.push_back("done " + std::to_string(outcome.value.value_or(-1))); });
    ASSERT_TRUE(processUntil([&] { return !worker.busy(); }));
    EXPECT_EQ(seen, (std::vector<std::string>{"read 0", "early", "build 50", "done 7"}));
}

TEST(BackgroundWorker, ACancelledJobStopsThroughItsProgressAndIsReportedCutShort) {
    BackgroundWorker worker;
    std::atomic<bool> started{false};
    bool progressAfterCancel = true;
    std::optional<JobOutcome<int>> got;
    bool sawCancelled = false;
    auto handle = worker.start(
        [&](Job& job) {
            started = true;
            EXPECT_TRUE(waitForCancel(job));
            progressAfterCancel = job.progress("late", 1.0f);
            reportProgress(job.asProgress(), "late", 1.0f);  // throws Cancelled
            return 1;
        },
        [&](JobOutcome<int>&& outcome, const Job& job) {
            got = std::move(outcome);
            sawCancelled = job.cancelled();
        });
    while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    handle->cancel();
    ASSERT_TRUE(processUntil([&] { return got.has_value(); }));
    EXPECT_FALSE(progressAfterCancel);
    EXPECT_TRUE(got->cutShort);
    EXPECT_FALSE(got->value);
    EXPECT_TRUE(got->error.isEmpty());
    EXPECT_TRUE(sawCancelled);
}

TEST(BackgroundWorker, WhatAJobThrowsBecomesItsErrorAndTheWorkerGoesOn) {
    BackgroundWorker worker;
    std::optional<JobOutcome<int>> failed, next;
    worker.start([](Job&) -> int { throw std::runtime_error("sky.hdr: truncated at byte 12"); },
                 [&](JobOutcome<int>&& outcome, const Job&) { failed = std::move(outcome); });
    worker.start([](Job&) { return 2; }, [&](JobOutcome<int>&& outcome, const Job&) { next = std::move(outcome); });
    ASSERT_TRUE(processUntil([&] { return next.has_value(); }));
    ASSERT_TRUE(failed);
    EXPECT_EQ(failed->error, QStringLiteral("sky.hdr: truncated at byte 12"));
    EXPECT_FALSE(failed->value);
    EXPECT_FALSE(failed->cutShort);
    EXPECT_EQ(next->value, 2);
}

TEST(BackgroundWorker, GoingAwayCancelsRunningAndQueuedJobsWaitsAndDeliversNothing) {
    std::atomic<bool> started{false}, sawCancel{false}, queuedRanUncancelled{false};
    int delivered = 0;
    {
        BackgroundWorker worker;
        worker.start(
            [&](Job& job) {
                started = true;
                sawCancel = waitForCancel(job);
                job.post([&delivered] { ++delivered; });
                return 0;
            },
            [&](JobOutcome<int>&&, const Job&) { ++delivered; });
        worker.start([&](Job& job) { queuedRanUncancelled = !job.cancelled(); return 0; },
                     [&](JobOutcome<int>&&, const Job&) { ++delivered; });
        while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }  // the destructor cancels both and waits for the thread
    EXPECT_TRUE(sawCancel);                // the running job was told, not waited out
    EXPECT_FALSE(queuedRanUncancelled);    // the queued one ran already cancelled
    QCoreApplication::processEvents();
    QCoreApplication::sendPostedEvents();
    EXPECT_EQ(delivered, 0);               // nothing reached the UI after the worker went
}

}  // namespace
}  // namespace mipgloss::ui
