#include "mipgloss/ui/view_dialogs.h"

#include <QAction>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>

namespace mipgloss::ui {

ExportImageDialog::ExportImageDialog(QSize viewSize, int maxSize, QWidget* parent) : QDialog(parent) {
    setObjectName(QStringLiteral("exportImageDialog"));
    setWindowTitle(tr("Export image"));
    auto* form = new QFormLayout;
    // Spin boxes stop at what this OpenGL can draw; MainWindow::exportImage checks again.
    const int top = std::max(maxSize, 1);
    width_ = new QSpinBox(this);
    width_->setObjectName(QStringLiteral("exportWidthSpin"));
    height_ = new QSpinBox(this);
    height_->setObjectName(QStringLiteral("exportHeightSpin"));
    for (QSpinBox* spin : {width_, height_}) {
        spin->setRange(1, top);
        spin->setSuffix(tr(" px"));
        spin->setAccelerated(true);
    }
    width_->setValue(std::clamp(viewSize.width(), 1, top));
    height_->setValue(std::clamp(viewSize.height(), 1, top));
    auto* sizeRow = new QHBoxLayout;
    sizeRow->addWidget(width_);
    sizeRow->addWidget(new QLabel(QStringLiteral("×"), this));
    sizeRow->addWidget(height_);
    form->addRow(tr("Size"), sizeRow);

    auto* presets = new QComboBox(this);
    presets->setObjectName(QStringLiteral("exportPresetCombo"));
    presets->addItem(tr("the view's size (%1×%2)").arg(viewSize.width()).arg(viewSize.height()), viewSize);
    for (const QSize s : {QSize(1920, 1080), QSize(2560, 1440), QSize(3840, 2160), QSize(2048, 2048),
                          QSize(4096, 4096)})
        if (s.width() <= top && s.height() <= top)
            presets->addItem(QStringLiteral("%1×%2").arg(s.width()).arg(s.height()), s);
    connect(presets, &QComboBox::activated, this, [this, presets](int index) {
        const QSize s = presets->itemData(index).toSize();
        width_->setValue(s.width());
        height_->setValue(s.height());
    });
    form->addRow(tr("Preset"), presets);

    format_ = new QComboBox(this);
    format_->setObjectName(QStringLiteral("exportFormatCombo"));
    format_->addItem(tr("PNG: as shown (exposure, tone map), alpha where the background is hidden"));
    format_->addItem(tr("OpenEXR: linear, scene-referred float (before exposure and tone map)"));
    form->addRow(tr("Format"), format_);
    form->addRow(QString(), new QLabel(tr("Largest side this OpenGL draws: %1 px").arg(top), this));

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    buttons->button(QDialogButtonBox::Ok)->setText(tr("Export…"));
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(buttons);
}

QSize ExportImageDialog::imageSize() const { return {width_->value(), height_->value()}; }

ExportImageDialog::Format ExportImageDialog::format() const {
    return format_->currentIndex() == 1 ? Format::Exr : Format::Png;
}

ShortcutsDialog::ShortcutsDialog(const QList<QAction*>& actions, QWidget* parent) : QDialog(parent) {
    setObjectName(QStringLiteral("shortcutsDialog"));
    setWindowTitle(tr("Keyboard and mouse shortcuts"));
    for (const QAction* action : actions) {
        if (!action || action->shortcuts().isEmpty()) continue;
        QStringList keys;
        for (const QKeySequence& k : action->shortcuts()) keys << k.toString(QKeySequence::NativeText);
        QString text = action->text();
        text.remove(QLatin1Char('&'));
        rows_.append({text, keys.join(tr(" or "))});
    }
    // The view's mouse gestures (viewport.h).
    rows_.append({tr("Orbit the camera"), tr("Left drag in the view")});
    rows_.append({tr("Pan"), tr("Right or middle drag, or Shift + left drag")});
    rows_.append({tr("Zoom toward the cursor"), tr("Mouse wheel")});
    rows_.append({tr("Turn the environment"), tr("Ctrl + left drag, or Shift + right drag")});
    rows_.append({tr("Select an object"), tr("Click it")});
    rows_.append({tr("Move the comparison's divider"), tr("Drag the divider")});
    rows_.append({tr("Apply a library material"), tr("Drag its thumbnail onto an object")});

    auto* table = new QTableWidget(static_cast<int>(rows_.size()), 2, this);
    table->setObjectName(QStringLiteral("shortcutsTable"));
    table->setHorizontalHeaderLabels({tr("Action"), tr("Keys or mouse")});
    table->verticalHeader()->hide();
    table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table->setSelectionMode(QAbstractItemView::NoSelection);
    for (int row = 0; row < rows_.size(); ++row) {
        table->setItem(row, 0, new QTableWidgetItem(rows_[row].first));
        table->setItem(row, 1, new QTableWidgetItem(rows_[row].second));
    }
    table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    table->horizontalHeader()->setStretchLastSection(true);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(table);
    layout->addWidget(buttons);
    resize(560, 520);
}

}  // namespace mipgloss::ui
