#pragma once
// The method selector (runnable methods from contourMethods(); planned ones
// listed but disabled, their reason as tooltip), the method's description,
// a preset selector and a parameter form generated from the selected
// method's ParameterSpecs: one collapsible section per parameter group
// (a header button and a body, object names "group-NAME-header" and
// "group-NAME"), bool -> check box, int / double -> spin box with the spec's
// range, choice -> combo box, help text as tooltip. Once a value differs
// from the chosen preset's, the selector shows the preset as modified
// ("paper (modified)"); choosing the preset again puts its values back.
#include "pipeline/Method.h"
#include "pipeline/Parameters.h"

#include <QString>
#include <QStringList>
#include <QWidget>
#include <map>
#include <string>
#include <utility>
#include <vector>

class QComboBox;
class QLabel;
class QToolButton;
class QVBoxLayout;

namespace contour {

class MethodPanel : public QWidget {
    Q_OBJECT

public:
    explicit MethodPanel(QWidget* parent = nullptr);

    // Name of the selected method ("mesh", "interpolated").
    QString methodName() const;
    const Method* method() const;
    // Selects a runnable method by name; false for unknown or planned
    // methods (the selection is then unchanged). Emits methodChanged when the
    // selection changes.
    bool setMethod(const QString& name);
    // Whether the selector lists a method, and whether it can be chosen.
    bool listsMethod(const QString& name) const;
    bool isMethodEnabled(const QString& name) const;
    QString methodToolTip(const QString& name) const;

    // The values in the form, complete for the selected method's schema.
    ParameterSet parameters() const;
    // Puts values into the form (unknown names are ignored; out-of-range
    // values are clamped by the widgets). Emits nothing.
    void setParameters(const ParameterSet& values);
    // The editor widget of a parameter, for tests; null if none.
    QWidget* editor(const QString& parameterName) const;

    QComboBox* methodSelector() const { return selector_; }
    QComboBox* presetSelector() const { return presetSelector_; }
    QLabel* descriptionLabel() const { return description_; }

    // Puts the selected method's preset into the form and emits
    // parametersChanged; false for an unknown name.
    bool setPreset(const QString& name);
    // Selects the preset the form's values started from without changing
    // them (a reopened session); emits nothing; false for an unknown name.
    bool setStartingPreset(const QString& name);
    // The preset last chosen ("default" after a method change).
    QString presetName() const;
    // Whether a value in the form differs from the chosen preset's.
    bool isPresetModified() const;

    // The selected method's parameter groups, in order.
    QStringList groups() const;
    QToolButton* groupHeader(const QString& group) const;
    QWidget* groupBody(const QString& group) const;
    bool isGroupExpanded(const QString& group) const;
    void setGroupExpanded(const QString& group, bool expanded);

signals:
    void methodChanged(const QString& name);
    void parametersChanged();

private:
    void onSelectorChanged(int index);
    void onPresetChanged(int index);
    void rebuildForm();
    // Shows the chosen preset as modified or not.
    void updatePresetMark();

    struct Section {
        QToolButton* header = nullptr;
        QWidget* body = nullptr;
    };

    QComboBox* selector_;
    QLabel* description_;
    QComboBox* presetSelector_;
    QVBoxLayout* sections_;
    QWidget* formHost_;
    std::map<std::string, QWidget*> editors_;
    std::vector<std::pair<std::string, Section>> groups_;
    QString current_;
    bool updating_ = false;
};

} // namespace contour
