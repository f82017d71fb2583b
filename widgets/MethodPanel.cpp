#include "MethodPanel.h"

#include "contours/Methods.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QRegularExpression>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QVBoxLayout>
#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>

namespace contour {

namespace {

constexpr int kNameRole = Qt::UserRole + 1;

double numeric(const ParameterValue& value) {
    if (const double* d = std::get_if<double>(&value))
        return *d;
    if (const int* i = std::get_if<int>(&value))
        return *i;
    if (const bool* b = std::get_if<bool>(&value))
        return *b ? 1.0 : 0.0;
    return 0.0;
}

bool hasRange(const ParameterSpec& spec) {
    return spec.minimum < spec.maximum;
}

// A spin box for doubles of any magnitude: tolerances such as 1e-9 or 1e-20
// would round to 0 at a fixed number of decimals and fail the method's range
// check. Shows and parses %g; on a positive range spanning decades a step
// multiplies or divides by 10^(1/4).
class DoubleEdit : public QDoubleSpinBox {
public:
    explicit DoubleEdit(QWidget* parent) : QDoubleSpinBox(parent) {
        setDecimals(DBL_MAX_10_EXP + DBL_DIG); // the most Qt allows: no rounding
    }

    QString textFromValue(double value) const override { return QString::number(value, 'g', 6); }

    double valueFromText(const QString& text) const override { return text.trimmed().toDouble(); }

    QValidator::State validate(QString& text, int&) const override {
        bool ok = false;
        const double value = text.trimmed().toDouble(&ok);
        if (ok)
            return value >= minimum() && value <= maximum() ? QValidator::Acceptable
                                                            : QValidator::Intermediate;
        // The start of a number ("", "-", "1e", "1e-").
        static const QRegularExpression partial(
            QStringLiteral("^\\s*[+-]?(\\d*\\.?\\d*)([eE][+-]?\\d*)?\\s*$"));
        return partial.match(text).hasMatch() ? QValidator::Intermediate : QValidator::Invalid;
    }

    void stepBy(int steps) override {
        if (minimum() > 0.0 && maximum() / minimum() > 1e3 && value() > 0.0)
            setValue(std::clamp(value() * std::pow(10.0, 0.25 * steps), minimum(), maximum()));
        else
            QDoubleSpinBox::stepBy(steps);
    }
};

} // namespace

MethodPanel::MethodPanel(QWidget* parent) : QWidget(parent) {
    selector_ = new QComboBox(this);
    selector_->setToolTip(tr("Contour method"));
    auto* model = qobject_cast<QStandardItemModel*>(selector_->model());
    for (const Method& m : contourMethods()) {
        auto* item = new QStandardItem(QString::fromStdString(m.label));
        item->setData(QString::fromStdString(m.name), kNameRole);
        item->setToolTip(QString::fromStdString(m.description));
        model->appendRow(item);
    }
    for (const PlannedMethod& m : plannedMethods()) {
        auto* item = new QStandardItem(tr("%1 (planned)").arg(QString::fromStdString(m.label)));
        item->setData(QString::fromStdString(m.name), kNameRole);
        item->setToolTip(QString::fromStdString(m.reason));
        item->setEnabled(false);
        model->appendRow(item);
    }

    description_ = new QLabel(this);
    description_->setWordWrap(true);
    description_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    formHost_ = new QWidget(this);
    form_ = new QFormLayout(formHost_);
    form_->setContentsMargins(0, 0, 0, 0);
    form_->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(selector_);
    layout->addWidget(description_);
    layout->addWidget(formHost_);

    current_ = selector_->itemData(0, kNameRole).toString();
    rebuildForm();
    connect(selector_, &QComboBox::currentIndexChanged, this, &MethodPanel::onSelectorChanged);
}

QString MethodPanel::methodName() const {
    return current_;
}

const Method* MethodPanel::method() const {
    return findMethod(current_.toStdString());
}

bool MethodPanel::setMethod(const QString& name) {
    if (!findMethod(name.toStdString()))
        return false;
    const int index = selector_->findData(name, kNameRole);
    if (index < 0)
        return false;
    selector_->setCurrentIndex(index); // emits through onSelectorChanged
    return true;
}

bool MethodPanel::listsMethod(const QString& name) const {
    return selector_->findData(name, kNameRole) >= 0;
}

bool MethodPanel::isMethodEnabled(const QString& name) const {
    const int index = selector_->findData(name, kNameRole);
    const auto* model = qobject_cast<const QStandardItemModel*>(selector_->model());
    return index >= 0 && model->item(index)->isEnabled();
}

QString MethodPanel::methodToolTip(const QString& name) const {
    const int index = selector_->findData(name, kNameRole);
    return index < 0 ? QString() : selector_->itemData(index, Qt::ToolTipRole).toString();
}

void MethodPanel::onSelectorChanged(int index) {
    const QString name = selector_->itemData(index, kNameRole).toString();
    if (name == current_ || !findMethod(name.toStdString()))
        return;
    current_ = name;
    rebuildForm();
    emit methodChanged(current_);
}

void MethodPanel::rebuildForm() {
    while (form_->rowCount() > 0)
        form_->removeRow(0);
    editors_.clear();
    const Method* m = method();
    description_->setText(m ? QString::fromStdString(m->description) : QString());
    if (!m)
        return;
    const auto changed = [this] {
        if (!updating_)
            emit parametersChanged();
    };
    for (const ParameterSpec& spec : m->parameters) {
        const QString help = QString::fromStdString(spec.help);
        QWidget* editor = nullptr;
        switch (spec.type) {
        case ParameterType::Bool: {
            auto* box = new QCheckBox(formHost_);
            box->setChecked(numeric(spec.defaultValue) != 0.0);
            connect(box, &QCheckBox::toggled, this, changed);
            editor = box;
            break;
        }
        case ParameterType::Int: {
            auto* box = new QSpinBox(formHost_);
            if (hasRange(spec))
                box->setRange(static_cast<int>(std::ceil(spec.minimum)),
                              static_cast<int>(std::floor(spec.maximum)));
            else
                box->setRange(INT_MIN, INT_MAX);
            box->setValue(static_cast<int>(numeric(spec.defaultValue)));
            box->setKeyboardTracking(false); // one change per commit, not per key
            connect(box, &QSpinBox::valueChanged, this, changed);
            editor = box;
            break;
        }
        case ParameterType::Double: {
            auto* box = new DoubleEdit(formHost_);
            if (hasRange(spec)) {
                box->setRange(spec.minimum, spec.maximum);
                box->setSingleStep((spec.maximum - spec.minimum) / 100.0);
            } else {
                box->setRange(-1e12, 1e12);
            }
            box->setValue(numeric(spec.defaultValue));
            box->setKeyboardTracking(false);
            connect(box, &QDoubleSpinBox::valueChanged, this, changed);
            editor = box;
            break;
        }
        case ParameterType::Choice: {
            auto* box = new QComboBox(formHost_);
            for (const std::string& choice : spec.choices)
                box->addItem(QString::fromStdString(choice));
            if (const auto* value = std::get_if<std::string>(&spec.defaultValue))
                box->setCurrentText(QString::fromStdString(*value));
            connect(box, &QComboBox::currentIndexChanged, this, changed);
            editor = box;
            break;
        }
        }
        editor->setToolTip(help);
        editor->setObjectName(QString::fromStdString(spec.name));
        auto* label = new QLabel(QString::fromStdString(spec.label), formHost_);
        label->setToolTip(help);
        label->setBuddy(editor);
        form_->addRow(label, editor);
        editors_[spec.name] = editor;
    }
}

ParameterSet MethodPanel::parameters() const {
    const Method* m = method();
    if (!m)
        return {};
    ParameterSet values = ParameterSet::defaults(m->parameters);
    for (const ParameterSpec& spec : m->parameters) {
        const auto it = editors_.find(spec.name);
        if (it == editors_.end())
            continue;
        QWidget* editor = it->second;
        switch (spec.type) {
        case ParameterType::Bool:
            values.set(spec.name, qobject_cast<QCheckBox*>(editor)->isChecked());
            break;
        case ParameterType::Int:
            values.set(spec.name, qobject_cast<QSpinBox*>(editor)->value());
            break;
        case ParameterType::Double:
            values.set(spec.name, qobject_cast<QDoubleSpinBox*>(editor)->value());
            break;
        case ParameterType::Choice:
            values.set(spec.name, qobject_cast<QComboBox*>(editor)->currentText().toStdString());
            break;
        }
    }
    return values;
}

void MethodPanel::setParameters(const ParameterSet& values) {
    const Method* m = method();
    if (!m)
        return;
    updating_ = true;
    for (const ParameterSpec& spec : m->parameters) {
        const auto it = editors_.find(spec.name);
        if (it == editors_.end() || !values.has(spec.name))
            continue;
        const ParameterValue& value = values.value(spec.name);
        switch (spec.type) {
        case ParameterType::Bool:
            qobject_cast<QCheckBox*>(it->second)->setChecked(numeric(value) != 0.0);
            break;
        case ParameterType::Int:
            qobject_cast<QSpinBox*>(it->second)->setValue(static_cast<int>(numeric(value)));
            break;
        case ParameterType::Double:
            qobject_cast<QDoubleSpinBox*>(it->second)->setValue(numeric(value));
            break;
        case ParameterType::Choice:
            if (const auto* text = std::get_if<std::string>(&value))
                qobject_cast<QComboBox*>(it->second)->setCurrentText(QString::fromStdString(*text));
            break;
        }
    }
    updating_ = false;
}

QWidget* MethodPanel::editor(const QString& parameterName) const {
    const auto it = editors_.find(parameterName.toStdString());
    return it == editors_.end() ? nullptr : it->second;
}

} // namespace contour
