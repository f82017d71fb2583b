#pragma once
// The method selector (runnable methods from contourMethods(); planned ones
// listed but disabled, their reason as tooltip) and a parameter form
// generated from the selected method's ParameterSpecs: bool -> check box,
// int / double -> spin box with the spec's range, choice -> combo box, help
// text as tooltip.
#include "pipeline/Method.h"
#include "pipeline/Parameters.h"

#include <QString>
#include <QWidget>
#include <map>
#include <string>

class QComboBox;
class QFormLayout;
class QLabel;

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

signals:
    void methodChanged(const QString& name);
    void parametersChanged();

private:
    void onSelectorChanged(int index);
    void rebuildForm();

    QComboBox* selector_;
    QLabel* description_;
    QFormLayout* form_;
    QWidget* formHost_;
    std::map<std::string, QWidget*> editors_;
    QString current_;
    bool updating_ = false;
};

} // namespace contour
