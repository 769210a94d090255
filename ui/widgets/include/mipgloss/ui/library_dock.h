// The material library dock: the user's library as a grid of thumbnails (library_model.h,
// thumbnail_cache.h), a search field that filters by name (case-insensitive), and the actions
//   Add from selected object  the selected object's material under its name (made unique)
//   Apply to selected object  also a double-click on an entry (SceneDocument::applyLibraryMaterial)
//   Rename (F2, inline), Duplicate, Delete (Del)
//   Import library…, Export library…  for the window's File menu (importLibraryAction(),
//                             exportLibraryAction())
// in a tool bar and the entries' context menu. Entries drag out as kMaterialMimeType onto the
// viewport or the scene list.
//
// A library file that could not be read shows a banner naming the file and the reason, with the
// two ways on: save the library in memory as another file, or overwrite the unreadable one. Errors
// and results (a failed save, an import) are also sent as messageShown for the window's banner.
//
// The grid draws each entry itself (library_dock.cpp): the thumbnail as it is, also when selected
// (the selection is a background and frame around it, never a tint over it), and the name below
// on up to two lines (nameLines); the tooltip names the entry whole above its parameters.
//
// Object names for tests: libraryDock, librarySearch, libraryList, libraryProblem,
// libraryProblemText, librarySaveAsButton, libraryReplaceButton, libraryAddAction,
// libraryApplyAction, libraryRenameAction, libraryDuplicateAction, libraryDeleteAction,
// libraryImportAction, libraryExportAction.
#pragma once

#include <QDockWidget>
#include <QString>
#include <QStringList>

class QAction;
class QFont;
class QLabel;
class QLineEdit;
class QListView;
class QModelIndex;
class QSortFilterProxyModel;
class QWidget;

namespace mipgloss::ui {

class EnvironmentManager;
class LibraryDocument;
class LibraryModel;
class SceneDocument;
class ThumbnailCache;

class LibraryDock : public QDockWidget {
    Q_OBJECT
public:
    LibraryDock(LibraryDocument* library, SceneDocument* scene, EnvironmentManager* environments,
                QWidget* parent = nullptr);
    ~LibraryDock() override;

    LibraryDocument* library() const { return library_; }
    LibraryModel* model() const { return model_; }
    QSortFilterProxyModel* filterModel() const { return proxy_; }
    ThumbnailCache* thumbnails() const { return thumbnails_; }
    QListView* view() const { return list_; }

    QAction* addEntryAction() const { return addEntryAction_; }
    QAction* applyEntryAction() const { return applyEntryAction_; }
    QAction* renameEntryAction() const { return renameEntryAction_; }
    QAction* duplicateEntryAction() const { return duplicateEntryAction_; }
    QAction* deleteEntryAction() const { return deleteEntryAction_; }
    QAction* importLibraryAction() const { return importLibraryAction_; }
    QAction* exportLibraryAction() const { return exportLibraryAction_; }

    // The library row of the view's current entry; -1 when none.
    int currentRow() const;
    // Makes library row `row` the view's current entry (when the filter shows it).
    void setCurrentRow(int row);

    // A name as the grid shows it in `font`, `width` pixels wide: wrapped at word boundaries (or
    // anywhere in a word too long for a line) onto at most two lines; past two, the second line
    // holds the rest cut short in the middle (…), so the name's end still shows.
    static QStringList nameLines(const QString& name, const QFont& font, int width);

public slots:
    // The actions' work, without dialogs (the tests and the window call these too).
    int addFromSelectedObject();       // the new row, or -1 (nothing selected)
    bool applyToSelectedObject();      // false when no object or no entry is selected
    bool applyRow(int row);            // library row `row` to the selected object
    void renameCurrent();              // starts the inline editor
    int duplicateCurrent();
    void deleteCurrent();
    bool importLibrary(const QString& path);
    bool exportLibrary(const QString& path);

    void importLibraryDialog();
    void exportLibraryDialog();
    void saveLibraryAsDialog();        // a detached library: keep it in another file
    void replaceUnreadableFileDialog();  // a detached library: overwrite the file (asks first)

signals:
    void messageShown(const QString& message, bool error);

private:
    void createActions();
    QWidget* buildProblemBanner();
    void updateActions();
    void refreshProblem();
    void showMessage(const QString& message, bool error);
    void showContextMenu(const QPoint& position);
    bool eventFilter(QObject* watched, QEvent* event) override;

    LibraryDocument* library_;
    SceneDocument* scene_;
    LibraryModel* model_ = nullptr;
    QSortFilterProxyModel* proxy_ = nullptr;
    ThumbnailCache* thumbnails_ = nullptr;

    QLineEdit* search_ = nullptr;
    QListView* list_ = nullptr;
    QWidget* problem_ = nullptr;
    QLabel* problemText_ = nullptr;

    QAction* addEntryAction_ = nullptr;
    QAction* applyEntryAction_ = nullptr;
    QAction* renameEntryAction_ = nullptr;
    QAction* duplicateEntryAction_ = nullptr;
    QAction* deleteEntryAction_ = nullptr;
    QAction* importLibraryAction_ = nullptr;
    QAction* exportLibraryAction_ = nullptr;

    QString lastDirectory_;
    QString saveError_;  // the last failed save, shown in the banner until a save succeeds
};

}  // namespace mipgloss::ui
