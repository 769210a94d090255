#include "status_indicators.h"

#include "elided_label.h"
#include "mipgloss/ibl/builders.h"
#include "mipgloss/ui/environment_manager.h"
#include "mipgloss/ui/environment_panel.h"
#include "mipgloss/ui/mesh_importer.h"
#include "mipgloss/ui/scene_document.h"

#include <QProgressBar>
#include <QStatusBar>

#include <cmath>

namespace mipgloss::ui {

namespace {

int percent(double fraction) { return static_cast<int>(std::lround(100.0 * fraction)); }

}  // namespace

StatusIndicators::StatusIndicators(QStatusBar* statusBar, const SceneDocument* document,
                                   EnvironmentManager* environments, MeshImporter* importer, QObject* parent)
    : QObject(parent), document_(document), environments_(environments), importer_(importer) {
    environment_ = new ElidedLabel(QStringLiteral("envStatusLabel"), statusBar);
    progress_ = new QProgressBar(statusBar);
    progress_->setObjectName(QStringLiteral("envProgress"));
    progress_->setRange(0, 100);
    progress_->setMaximumWidth(220);
    progress_->setTextVisible(true);
    progress_->hide();
    statusBar->addPermanentWidget(progress_);
    statusBar->addPermanentWidget(environment_);

    connect(document_, &SceneDocument::environmentChanged, this, &StatusIndicators::showEnvironment);
    connect(environments_, &EnvironmentManager::environmentReady, this, &StatusIndicators::showEnvironment);
    // Shown while either works; each sets its own range and format.
    connect(environments_, &EnvironmentManager::busyChanged, this, [this](bool busy) {
        progress_->setVisible(busy || importer_->busy());
        if (busy) {
            progress_->setRange(0, 100);
            progress_->setValue(0);
        }
    });
    connect(environments_, &EnvironmentManager::progress, this, [this](const QString& stage, double fraction) {
        progress_->setRange(0, 100);
        progress_->setFormat(stage + QStringLiteral(" %p%"));
        progress_->setValue(percent(fraction));
    });
    connect(importer_, &MeshImporter::backgroundStarted, this, [this](int files) {
        // One file: a busy indicator (a file is read whole, with no progress of its own); several:
        // the fraction of files read.
        progress_->setRange(0, files > 1 ? 100 : 0);
        progress_->setValue(0);
        progress_->setFormat(tr("importing"));
        progress_->show();
    });
    connect(importer_, &MeshImporter::progress, this, [this](const QString& stage, double fraction) {
        if (progress_->maximum() == 0) return;
        progress_->setFormat(stage + QStringLiteral(" %p%"));
        progress_->setValue(percent(fraction));
    });
    connect(importer_, &MeshImporter::finished, this, [this] {
        progress_->setVisible(importer_->busy() || environments_->busy());
        progress_->setRange(0, 100);
    });
    showEnvironment();
}

void StatusIndicators::showEnvironment() {
    const auto current = environments_->current();
    const EnvironmentSettings& s = current ? current->settings : document_->scene().environment;
    QString text = QStringLiteral("%1 · %2 · %3")
                       .arg(environmentDisplayName(s.source))
                       .arg(squaredSize(current && current->base ? current->base->size() : s.faceSize))
                       .arg(QString::fromLatin1(builderName(s.builder)));
    if (!current) text += tr(" (loading)");
    else if (!current->complete()) text += tr(" (building the chain)");
    environment_->setWholeText(text);
}

}  // namespace mipgloss::ui
