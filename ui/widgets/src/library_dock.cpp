#include "mipgloss/ui/library_dock.h"

#include "mipgloss/ui/library_document.h"
#include "mipgloss/ui/library_model.h"
#include "mipgloss/ui/scene_document.h"
#include "mipgloss/ui/thumbnail_cache.h"

#include <QAction>
#include <QEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHelpEvent>
#include <QItemSelectionModel>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QMenu>
#include <QMessageBox>
#include <QPainter>
#include <QPushButton>
#include <QScrollBar>
#include <QSortFilterProxyModel>
#include <QStyledItemDelegate>
#include <QTextLayout>
#include <QToolBar>
#include <QToolTip>
#include <QVBoxLayout>

#include <algorithm>
#include <filesystem>

namespace mipgloss::ui {

namespace {

std::filesystem::path toPath(const QString& path) { return std::filesystem::path(path.toStdU16String()); }
QString fromPath(const std::filesystem::path& path) { return QString::fromStdU16String(path.u16string()); }

// Libraries are saved as .mglib (the type the desktop's MIME database knows); older ones are .json.
QString libraryOpenFilter() {
    return QObject::tr("Material libraries and assets (*.mglib *.json *.gltf *.glb *.obj);;Material libraries "
                       "(*.mglib *.json);;Assets' materials (*.gltf *.glb *.obj);;All files (*)");
}
QString librarySaveFilter() { return QObject::tr("Material libraries (*.mglib);;All files (*)"); }
QString withLibrarySuffix(QString path) {
    if (!path.isEmpty() && QFileInfo(path).suffix().isEmpty()) path += QStringLiteral(".mglib");
    return path;
}

// How the grid draws an entry. Not the style's item drawing: it shows a selected item's icon in
// QIcon::Selected mode, the picture tinted by the selection colour (an orange material looked
// olive), and its cells took their size from the first entry's one line of text (names were cut
// to about 8 characters). Here the thumbnail is drawn as it is; the selection is the highlight
// behind the cell, which frames the thumbnail and lies under the name; the name takes up to two
// lines (LibraryDock::nameLines), every cell the same size.
class LibraryItemDelegate : public QStyledItemDelegate {
public:
    using QStyledItemDelegate::QStyledItemDelegate;

    static constexpr int kPadding = 5;     // the highlight's frame around the thumbnail
    static constexpr int kTextMargin = 3;  // between the name and the cell's sides
    static constexpr int kNameLines = 2;

    static QSize cellSize(const QFontMetrics& metrics) {
        const int thumbnail = ThumbnailCache::kThumbnailSize;
        return {thumbnail + 24, kPadding + thumbnail + kPadding + kNameLines * metrics.lineSpacing() + kPadding};
    }

    QSize sizeHint(const QStyleOptionViewItem& option, const QModelIndex&) const override {
        return cellSize(option.fontMetrics);
    }

    void paint(QPainter* painter, const QStyleOptionViewItem& option, const QModelIndex& index) const override {
        QStyleOptionViewItem opt = option;
        initStyleOption(&opt, index);
        const bool enabled = opt.state & QStyle::State_Enabled;
        const QPalette::ColorGroup group =
            !enabled ? QPalette::Disabled : (opt.state & QStyle::State_Active ? QPalette::Normal : QPalette::Inactive);
        const bool selected = opt.state & QStyle::State_Selected;
        const QRect cell = opt.rect.adjusted(1, 1, -1, -1);

        painter->save();
        painter->setRenderHint(QPainter::Antialiasing);
        if (selected || (opt.state & QStyle::State_MouseOver)) {
            QColor back = opt.palette.color(group, QPalette::Highlight);
            if (!selected) back.setAlphaF(0.25f);  // hovered
            painter->setPen(Qt::NoPen);
            painter->setBrush(back);
            painter->drawRoundedRect(cell, 4, 4);
        }
        const QRect picture = thumbnailRect(opt.rect);
        const QPixmap pixmap = index.data(Qt::DecorationRole).value<QPixmap>();
        if (!pixmap.isNull()) {
            if (!enabled) painter->setOpacity(0.5);
            painter->drawPixmap(picture, pixmap);
            painter->setOpacity(1.0);
        }
        if ((opt.state & QStyle::State_HasFocus) && !selected) {
            QColor focus = opt.palette.color(group, QPalette::Highlight);
            painter->setPen(QPen(focus, 1.0, Qt::DotLine));
            painter->setBrush(Qt::NoBrush);
            painter->drawRoundedRect(QRectF(cell).adjusted(0.5, 0.5, -0.5, -0.5), 4, 4);
        }
        painter->setPen(opt.palette.color(group, selected ? QPalette::HighlightedText : QPalette::Text));
        painter->setFont(opt.font);
        QRect line = nameRect(opt.rect);
        line.setHeight(opt.fontMetrics.lineSpacing());
        for (const QString& text : LibraryDock::nameLines(opt.text, opt.font, line.width())) {
            painter->drawText(line, Qt::AlignHCenter | Qt::AlignTop | Qt::TextSingleLine, text);
            line.translate(0, opt.fontMetrics.lineSpacing());
        }
        painter->restore();
    }

    // Renaming in place: the editor over the name.
    void updateEditorGeometry(QWidget* editor, const QStyleOptionViewItem& option, const QModelIndex&) const override {
        QRect area = nameRect(option.rect);
        area.setHeight(std::max(editor->sizeHint().height(), option.fontMetrics.lineSpacing()));
        editor->setGeometry(area);
    }

    // The tooltip names the entry whole (the grid may cut it short), above what the model says.
    bool helpEvent(QHelpEvent* event, QAbstractItemView* view, const QStyleOptionViewItem& option,
                   const QModelIndex& index) override {
        if (event->type() != QEvent::ToolTip || !index.isValid())
            return QStyledItemDelegate::helpEvent(event, view, option, index);
        QString text = index.data(Qt::DisplayRole).toString();
        const QString details = index.data(Qt::ToolTipRole).toString();
        if (!details.isEmpty()) text += QLatin1Char('\n') + details;
        QToolTip::showText(event->globalPos(), text, view, view->visualRect(index));
        return true;
    }

private:
    static QRect thumbnailRect(const QRect& cell) {
        const int side = ThumbnailCache::kThumbnailSize;
        return {cell.left() + (cell.width() - side) / 2, cell.top() + kPadding, side, side};
    }
    static QRect nameRect(const QRect& cell) {
        const int top = thumbnailRect(cell).bottom() + 1 + kPadding;
        return QRect(QPoint(cell.left() + kTextMargin, top), QPoint(cell.right() - kTextMargin, cell.bottom()));
    }
};

}  // namespace

QStringList LibraryDock::nameLines(const QString& name, const QFont& font, int width) {
    if (name.isEmpty() || width <= 0) return {};
    QTextLayout layout(name, font);
    QTextOption wrap;
    wrap.setWrapMode(QTextOption::WrapAtWordBoundaryOrAnywhere);
    layout.setTextOption(wrap);
    QStringList lines;
    int rest = 0;  // where the text after the first line starts
    layout.beginLayout();
    for (QTextLine line = layout.createLine(); line.isValid(); line = layout.createLine()) {
        line.setLineWidth(width);
        lines << name.mid(line.textStart(), line.textLength()).trimmed();
        if (lines.size() == 1) rest = line.textStart() + line.textLength();
    }
    layout.endLayout();
    if (lines.size() <= 2) return lines;
    const QFontMetrics metrics(font);
    return {lines.front(), metrics.elidedText(name.mid(rest).trimmed(), Qt::ElideMiddle, width)};
}

LibraryDock::LibraryDock(LibraryDocument* library, SceneDocument* scene, EnvironmentManager* environments,
                         QWidget* parent)
    : QDockWidget(tr("Library"), parent), library_(library), scene_(scene) {
    setObjectName(QStringLiteral("libraryDock"));

    model_ = new LibraryModel(library_, this);
    thumbnails_ = new ThumbnailCache(library_, environments, this);
    model_->setThumbnails(thumbnails_);
    proxy_ = new QSortFilterProxyModel(this);
    proxy_->setSourceModel(model_);
    proxy_->setFilterCaseSensitivity(Qt::CaseInsensitive);
    proxy_->setFilterRole(Qt::DisplayRole);

    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(4, 4, 4, 4);
    layout->addWidget(buildProblemBanner());

    search_ = new QLineEdit(body);
    search_->setObjectName(QStringLiteral("librarySearch"));
    search_->setPlaceholderText(tr("Search materials"));
    search_->setClearButtonEnabled(true);
    layout->addWidget(search_);

    list_ = new QListView(body);
    list_->setObjectName(QStringLiteral("libraryList"));
    list_->setModel(proxy_);
    list_->setViewMode(QListView::IconMode);
    list_->setIconSize(QSize(ThumbnailCache::kThumbnailSize, ThumbnailCache::kThumbnailSize));
    list_->setItemDelegate(new LibraryItemDelegate(list_));
    list_->setGridSize(LibraryItemDelegate::cellSize(list_->fontMetrics()));
    list_->setUniformItemSizes(true);  // the delegate's cells are all one size
    list_->setResizeMode(QListView::Adjust);
    list_->setMovement(QListView::Static);  // the user's order; entries drag out, not around
    list_->setWordWrap(true);
    list_->setSelectionMode(QAbstractItemView::SingleSelection);
    list_->setEditTriggers(QAbstractItemView::EditKeyPressed | QAbstractItemView::SelectedClicked);
    list_->setDragEnabled(true);
    list_->setDragDropMode(QAbstractItemView::DragOnly);
    list_->setDefaultDropAction(Qt::CopyAction);
    list_->setContextMenuPolicy(Qt::CustomContextMenu);
    layout->addWidget(list_, 1);

    createActions();
    auto* tools = new QToolBar(body);
    tools->setToolButtonStyle(Qt::ToolButtonTextOnly);
    tools->addAction(addEntryAction_);
    tools->addAction(applyEntryAction_);
    tools->addSeparator();
    tools->addAction(duplicateEntryAction_);
    tools->addAction(deleteEntryAction_);
    layout->addWidget(tools);
    setWidget(body);

    connect(search_, &QLineEdit::textChanged, proxy_, &QSortFilterProxyModel::setFilterFixedString);
    connect(list_, &QListView::doubleClicked, this,
            [this](const QModelIndex& index) { applyRow(proxy_->mapToSource(index).row()); });
    connect(list_, &QWidget::customContextMenuRequested, this, &LibraryDock::showContextMenu);
    connect(list_->selectionModel(), &QItemSelectionModel::currentChanged, this, &LibraryDock::updateActions);
    connect(proxy_, &QAbstractItemModel::rowsInserted, this, &LibraryDock::updateActions);
    connect(proxy_, &QAbstractItemModel::rowsRemoved, this, &LibraryDock::updateActions);
    connect(proxy_, &QAbstractItemModel::modelReset, this, &LibraryDock::updateActions);
    connect(scene_, &SceneDocument::selectionChanged, this, &LibraryDock::updateActions);
    connect(scene_, &SceneDocument::objectsChanged, this, &LibraryDock::updateActions);

    // Thumbnails only for what the view shows: the rows whose cells meet its viewport.
    thumbnails_->setVisibleRows([this] {
        std::vector<int> rows;
        if (!list_->isVisible()) return rows;
        const QRect area = list_->viewport()->rect();
        for (int r = 0; r < proxy_->rowCount(); ++r) {
            const QModelIndex i = proxy_->index(r, 0);
            if (list_->visualRect(i).intersects(area)) rows.push_back(proxy_->mapToSource(i).row());
        }
        return rows;
    });
    auto visibleChanged = [this] { thumbnails_->visibleRowsChanged(); };
    connect(list_->verticalScrollBar(), &QScrollBar::valueChanged, this, visibleChanged);
    connect(list_->horizontalScrollBar(), &QScrollBar::valueChanged, this, visibleChanged);
    connect(proxy_, &QAbstractItemModel::layoutChanged, this, visibleChanged);
    connect(proxy_, &QAbstractItemModel::rowsInserted, this, visibleChanged);
    connect(proxy_, &QAbstractItemModel::rowsRemoved, this, visibleChanged);
    connect(proxy_, &QAbstractItemModel::modelReset, this, visibleChanged);
    list_->viewport()->installEventFilter(this);  // shown, resized

    connect(library_, &LibraryDocument::fileChanged, this, &LibraryDock::refreshProblem);
    connect(library_, &LibraryDocument::saveFailed, this, [this](const QString& message) {
        saveError_ = message;
        refreshProblem();
        showMessage(tr("The library could not be saved (your changes are kept in memory): %1").arg(message), true);
    });
    connect(library_, &LibraryDocument::saved, this, [this] {
        if (saveError_.isEmpty()) return;
        saveError_.clear();
        refreshProblem();
    });
    refreshProblem();
    updateActions();
}

LibraryDock::~LibraryDock() = default;

void LibraryDock::createActions() {
    auto make = [this](const QString& text, const char* name, const QString& tip) {
        auto* action = new QAction(text, this);
        action->setObjectName(QString::fromLatin1(name));
        action->setToolTip(tip);
        action->setStatusTip(tip);
        return action;
    };
    addEntryAction_ = make(tr("Add"), "libraryAddAction",
                           tr("Add the selected object's material to the library"));
    applyEntryAction_ = make(tr("Apply"), "libraryApplyAction",
                             tr("Give the selected object this material (or double-click it)"));
    renameEntryAction_ = make(tr("Rename"), "libraryRenameAction", tr("Rename the material"));
    duplicateEntryAction_ = make(tr("Duplicate"), "libraryDuplicateAction", tr("Copy the material under a new name"));
    deleteEntryAction_ = make(tr("Delete"), "libraryDeleteAction", tr("Remove the material from the library"));
    importLibraryAction_ = make(tr("Import Library…"), "libraryImportAction",
                                tr("Add the materials of a library file, or of a glTF or OBJ asset, to your library"));
    exportLibraryAction_ = make(tr("Export Library…"), "libraryExportAction",
                                tr("Write your library to a file to share it"));

    // Keys act while the list has focus (an inline editor takes F2 and Delete for itself).
    renameEntryAction_->setShortcut(QKeySequence(Qt::Key_F2));
    deleteEntryAction_->setShortcut(QKeySequence::Delete);
    for (QAction* action : {renameEntryAction_, deleteEntryAction_}) {
        action->setShortcutContext(Qt::WidgetWithChildrenShortcut);
        list_->addAction(action);
    }

    connect(addEntryAction_, &QAction::triggered, this, &LibraryDock::addFromSelectedObject);
    connect(applyEntryAction_, &QAction::triggered, this, &LibraryDock::applyToSelectedObject);
    connect(renameEntryAction_, &QAction::triggered, this, &LibraryDock::renameCurrent);
    connect(duplicateEntryAction_, &QAction::triggered, this, &LibraryDock::duplicateCurrent);
    connect(deleteEntryAction_, &QAction::triggered, this, &LibraryDock::deleteCurrent);
    connect(importLibraryAction_, &QAction::triggered, this, &LibraryDock::importLibraryDialog);
    connect(exportLibraryAction_, &QAction::triggered, this, &LibraryDock::exportLibraryDialog);
}

QWidget* LibraryDock::buildProblemBanner() {
    problem_ = new QWidget(this);
    problem_->setObjectName(QStringLiteral("libraryProblem"));
    problem_->setAutoFillBackground(true);
    QPalette palette = problem_->palette();
    palette.setColor(QPalette::Window, QColor(120, 40, 40));
    palette.setColor(QPalette::WindowText, Qt::white);
    problem_->setPalette(palette);
    auto* layout = new QVBoxLayout(problem_);
    layout->setContentsMargins(6, 4, 6, 4);
    problemText_ = new QLabel(problem_);
    problemText_->setObjectName(QStringLiteral("libraryProblemText"));
    problemText_->setWordWrap(true);
    problemText_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    layout->addWidget(problemText_);
    auto* buttons = new QHBoxLayout;
    auto* saveAs = new QPushButton(tr("Save Library As…"), problem_);
    saveAs->setObjectName(QStringLiteral("librarySaveAsButton"));
    auto* replace = new QPushButton(tr("Replace the File…"), problem_);
    replace->setObjectName(QStringLiteral("libraryReplaceButton"));
    buttons->addWidget(saveAs);
    buttons->addWidget(replace);
    buttons->addStretch(1);
    layout->addLayout(buttons);
    connect(saveAs, &QPushButton::clicked, this, &LibraryDock::saveLibraryAsDialog);
    connect(replace, &QPushButton::clicked, this, &LibraryDock::replaceUnreadableFileDialog);
    return problem_;
}

void LibraryDock::refreshProblem() {
    QStringList lines;
    if (library_->isDetached())
        lines << tr("The library “%1” could not be read: %2\nYou are working on an empty library in "
                    "memory; the file is left as it is until you save the library elsewhere or "
                    "replace the file.")
                     .arg(fromPath(library_->file()), library_->lastError());
    if (!saveError_.isEmpty()) lines << tr("The library could not be saved: %1").arg(saveError_);
    problemText_->setText(lines.join(QStringLiteral("\n")));
    for (QPushButton* button : problem_->findChildren<QPushButton*>()) button->setVisible(library_->isDetached());
    problem_->setVisible(!lines.isEmpty());
}

void LibraryDock::updateActions() {
    const bool haveEntry = currentRow() >= 0;
    const bool haveObject = scene_->isValidIndex(scene_->selected());
    addEntryAction_->setEnabled(haveObject);
    applyEntryAction_->setEnabled(haveEntry && haveObject);
    renameEntryAction_->setEnabled(haveEntry);
    duplicateEntryAction_->setEnabled(haveEntry);
    deleteEntryAction_->setEnabled(haveEntry);
}

int LibraryDock::currentRow() const {
    const QModelIndex current = list_->currentIndex();
    return current.isValid() ? proxy_->mapToSource(current).row() : -1;
}

void LibraryDock::setCurrentRow(int row) {
    if (!library_->isValidRow(row)) return;
    const QModelIndex index = proxy_->mapFromSource(model_->index(row));
    if (!index.isValid()) return;
    list_->setCurrentIndex(index);
    list_->scrollTo(index);
}

int LibraryDock::addFromSelectedObject() {
    const int object = scene_->selected();
    if (!scene_->isValidIndex(object)) return -1;
    const NamedMaterial* named = scene_->namedMaterialOf(object);
    LibraryMaterial entry;
    entry.name = named ? named->name : scene_->object(object).name;
    entry.material = scene_->materialOf(object);
    const int row = library_->add(entry);
    if (row < 0) {
        showMessage(tr("“%1” cannot be a material's name").arg(QString::fromStdString(entry.name)), true);
        return -1;
    }
    setCurrentRow(row);
    return row;
}

bool LibraryDock::applyToSelectedObject() { return applyRow(currentRow()); }

bool LibraryDock::applyRow(int row) {
    const int object = scene_->selected();
    if (!library_->isValidRow(row) || !scene_->isValidIndex(object)) return false;
    scene_->applyLibraryMaterial(object, library_->entry(row));
    return true;
}

void LibraryDock::renameCurrent() {
    const QModelIndex current = list_->currentIndex();
    if (current.isValid()) list_->edit(current);
}

int LibraryDock::duplicateCurrent() {
    const int row = library_->duplicate(currentRow());
    if (row >= 0) setCurrentRow(row);
    return row;
}

void LibraryDock::deleteCurrent() { library_->remove(currentRow()); }

bool LibraryDock::importLibrary(const QString& path) {
    const int added = library_->importFrom(toPath(path));
    if (added < 0) {
        showMessage(tr("Could not import the library: %1").arg(library_->lastError()), true);
        return false;
    }
    showMessage(tr("Imported %n material(s) from %1", nullptr, added).arg(path), false);
    return true;
}

bool LibraryDock::exportLibrary(const QString& path) {
    if (!library_->exportTo(toPath(path))) {
        showMessage(tr("Could not export the library: %1").arg(library_->lastError()), true);
        return false;
    }
    showMessage(tr("Exported %n material(s) to %1", nullptr, library_->count()).arg(path), false);
    return true;
}

void LibraryDock::importLibraryDialog() {
    const QString path = QFileDialog::getOpenFileName(this, tr("Import Library"), lastDirectory_, libraryOpenFilter());
    if (path.isEmpty()) return;
    lastDirectory_ = QFileInfo(path).absolutePath();
    importLibrary(path);
}

void LibraryDock::exportLibraryDialog() {
    const QString path = withLibrarySuffix(
        QFileDialog::getSaveFileName(this, tr("Export Library"), lastDirectory_, librarySaveFilter()));
    if (path.isEmpty()) return;
    lastDirectory_ = QFileInfo(path).absolutePath();
    exportLibrary(path);
}

void LibraryDock::saveLibraryAsDialog() {
    const QString path = withLibrarySuffix(
        QFileDialog::getSaveFileName(this, tr("Save Library As"), lastDirectory_, librarySaveFilter()));
    if (path.isEmpty()) return;
    lastDirectory_ = QFileInfo(path).absolutePath();
    if (toPath(path) == library_->file() && library_->isDetached()) {
        replaceUnreadableFileDialog();  // the same file: the explicit question first
        return;
    }
    if (!library_->saveAs(toPath(path)))
        showMessage(tr("Could not save the library: %1").arg(library_->lastError()), true);
}

void LibraryDock::replaceUnreadableFileDialog() {
    if (!library_->isDetached()) return;
    const QString file = fromPath(library_->file());
    const auto answer = QMessageBox::warning(
        this, tr("Replace the Library File"),
        tr("“%1” could not be read. Replace it with the library in memory (%n material(s))? "
           "What the file holds now is lost.",
           nullptr, library_->count())
            .arg(file),
        QMessageBox::Yes | QMessageBox::Cancel, QMessageBox::Cancel);
    if (answer != QMessageBox::Yes) return;
    if (!library_->replaceUnreadableFile())
        showMessage(tr("Could not replace the library file: %1").arg(library_->lastError()), true);
}

void LibraryDock::showMessage(const QString& message, bool error) { emit messageShown(message, error); }

void LibraryDock::showContextMenu(const QPoint& position) {
    const QModelIndex index = list_->indexAt(position);
    if (index.isValid()) list_->setCurrentIndex(index);
    QMenu menu(this);
    menu.addAction(applyEntryAction_);
    menu.addAction(addEntryAction_);
    menu.addSeparator();
    menu.addAction(renameEntryAction_);
    menu.addAction(duplicateEntryAction_);
    menu.addAction(deleteEntryAction_);
    menu.addSeparator();
    menu.addAction(importLibraryAction_);
    menu.addAction(exportLibraryAction_);
    menu.exec(list_->viewport()->mapToGlobal(position));
}

bool LibraryDock::eventFilter(QObject* watched, QEvent* event) {
    if (watched == list_->viewport() && (event->type() == QEvent::Show || event->type() == QEvent::Resize))
        thumbnails_->visibleRowsChanged();
    return QDockWidget::eventFilter(watched, event);
}

}  // namespace mipgloss::ui
