#include "MethodPanel.h"

#include "contours/Methods.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QRegularExpression>
#include <QSizePolicy>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QToolButton>
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

// "cusp-detection" -> "Cusp detection".
QString groupTitle(const std::string& group) {
    QString title = QString::fromStdString(group).replace(QLatin1Char('-'), QLatin1Char(' '));
    if (!title.isEmpty())
        title[0] = title[0].toUpper();
    return title;
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
    // Long method names are elided in the closed box so the dock can stay
    // narrow; the popup shows them whole.
    selector_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    selector_->setMinimumContentsLength(16);
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
    description_->setObjectName(QStringLiteral("methodDescription"));
    description_->setWordWrap(true);
    description_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    // Wraps to the dock's width instead of widening the panel.
    QSizePolicy wrapping(QSizePolicy::Ignored, QSizePolicy::Preferred);
    wrapping.setHeightForWidth(true);
    description_->setSizePolicy(wrapping);

    presetSelector_ = new QComboBox(this);
    presetSelector_->setObjectName(QStringLiteral("presetSelector"));
    auto* presetLabel = new QLabel(tr("Preset"), this);
    presetLabel->setBuddy(presetSelector_);
    auto* presetRow = new QHBoxLayout;
    presetRow->addWidget(presetLabel);
    presetRow->addWidget(presetSelector_, 1);

    formHost_ = new QWidget(this);
    sections_ = new QVBoxLayout(formHost_);
    sections_->setContentsMargins(0, 0, 0, 0);
    sections_->setSpacing(2);

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(selector_);
    layout->addWidget(description_);
    layout->addLayout(presetRow);
    layout->addWidget(formHost_);
    layout->addStretch(1);

    current_ = selector_->itemData(0, kNameRole).toString();
    rebuildForm();
    connect(selector_, &QComboBox::currentIndexChanged, this, &MethodPanel::onSelectorChanged);
    connect(presetSelector_, &QComboBox::activated, this, &MethodPanel::onPresetChanged);
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

bool MethodPanel::setPreset(const QString& name) {
    const int index = presetSelector_->findData(name);
    if (index < 0)
        return false;
    presetSelector_->setCurrentIndex(index);
    onPresetChanged(index);
    return true;
}

bool MethodPanel::setStartingPreset(const QString& name) {
    const int index = presetSelector_->findData(name);
    if (index < 0)
        return false;
    presetSelector_->setCurrentIndex(index);
    updatePresetMark();
    return true;
}

QString MethodPanel::presetName() const {
    return presetSelector_->currentData().toString();
}

bool MethodPanel::isPresetModified() const {
    const Method* m = method();
    const ParameterPreset* preset = m ? m->preset(presetName().toStdString()) : nullptr;
    return preset && !changedFromPreset(m->parameters, *preset, parameters()).values().empty();
}

void MethodPanel::updatePresetMark() {
    const int current = presetSelector_->currentIndex();
    const bool modified = isPresetModified();
    for (int i = 0; i < presetSelector_->count(); ++i) {
        const QString name = presetSelector_->itemData(i).toString();
        presetSelector_->setItemText(i, i == current && modified ? tr("%1 (modified)").arg(name)
                                                                 : name);
    }
}

void MethodPanel::onPresetChanged(int index) {
    const Method* m = method();
    const ParameterPreset* preset =
        m ? m->preset(presetSelector_->itemData(index).toString().toStdString()) : nullptr;
    if (!preset)
        return;
    setParameters(presetValues(m->parameters, *preset)); // clears the modified mark
    emit parametersChanged();
}

QStringList MethodPanel::groups() const {
    QStringList names;
    for (const auto& [name, section] : groups_)
        names.push_back(QString::fromStdString(name));
    return names;
}

QToolButton* MethodPanel::groupHeader(const QString& group) const {
    for (const auto& [name, section] : groups_)
        if (name == group.toStdString())
            return section.header;
    return nullptr;
}

QWidget* MethodPanel::groupBody(const QString& group) const {
    for (const auto& [name, section] : groups_)
        if (name == group.toStdString())
            return section.body;
    return nullptr;
}

bool MethodPanel::isGroupExpanded(const QString& group) const {
    const QToolButton* header = groupHeader(group);
    return header && header->isChecked();
}

void MethodPanel::setGroupExpanded(const QString& group, bool expanded) {
    if (QToolButton* header = groupHeader(group))
        header->setChecked(expanded); // toggled shows or hides the body
}

void MethodPanel::rebuildForm() {
    for (auto& [name, section] : groups_) {
        delete section.header;
        delete section.body;
    }
    groups_.clear();
    editors_.clear();
    presetSelector_->clear();
    const Method* m = method();
    description_->setText(m ? QString::fromStdString(m->description) : QString());
    if (!m)
        return;
    for (const ParameterPreset& preset : m->presets) {
        presetSelector_->addItem(QString::fromStdString(preset.name),
                                 QString::fromStdString(preset.name));
        presetSelector_->setItemData(presetSelector_->count() - 1,
                                     QString::fromStdString(preset.description), Qt::ToolTipRole);
    }
    presetSelector_->setEnabled(presetSelector_->count() > 1);
    // One section per group; a short form opens them all, a long one only
    // the first.
    const bool expandAll = m->parameters.size() <= 12;
    std::map<std::string, QFormLayout*> forms;
    for (const std::string& group : m->parameterGroups()) {
        int count = 0;
        for (const ParameterSpec& spec : m->parameters)
            count += spec.group == group;
        Section section;
        const QString name = QString::fromStdString(group);
        section.header = new QToolButton(formHost_);
        section.header->setObjectName(QStringLiteral("group-%1-header").arg(name));
        section.header->setText(tr("%1 (%2)").arg(groupTitle(group)).arg(count));
        section.header->setCheckable(true);
        section.header->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
        section.header->setAutoRaise(true);
        section.header->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        const int phase = m->phaseIndex(group);
        if (phase >= 0)
            section.header->setToolTip(
                QString::fromStdString(m->phases[static_cast<size_t>(phase)].description));
        section.body = new QWidget(formHost_);
        section.body->setObjectName(QStringLiteral("group-%1").arg(name));
        auto* form = new QFormLayout(section.body);
        form->setContentsMargins(12, 0, 0, 4);
        form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
        form->setRowWrapPolicy(QFormLayout::WrapLongRows);
        forms[group] = form;
        QToolButton* header = section.header;
        QWidget* body = section.body;
        connect(header, &QToolButton::toggled, body, [header, body](bool open) {
            header->setArrowType(open ? Qt::DownArrow : Qt::RightArrow);
            body->setVisible(open);
        });
        const bool open = expandAll || groups_.empty();
        header->setChecked(open);
        header->setArrowType(open ? Qt::DownArrow : Qt::RightArrow);
        body->setVisible(open);
        sections_->addWidget(header);
        sections_->addWidget(body);
        groups_.emplace_back(group, section);
    }
    const auto changed = [this] {
        if (updating_)
            return;
        updatePresetMark();
        emit parametersChanged();
    };
    for (const ParameterSpec& spec : m->parameters) {
        const QString help = QString::fromStdString(spec.help);
        QFormLayout* form = forms.at(spec.group);
        QWidget* host = form->parentWidget();
        QWidget* editor = nullptr;
        switch (spec.type) {
        case ParameterType::Bool: {
            auto* box = new QCheckBox(host);
            box->setChecked(numeric(spec.defaultValue) != 0.0);
            connect(box, &QCheckBox::toggled, this, changed);
            editor = box;
            break;
        }
        case ParameterType::Int: {
            auto* box = new QSpinBox(host);
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
            auto* box = new DoubleEdit(host);
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
            auto* box = new QComboBox(host);
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
        auto* label = new QLabel(QString::fromStdString(spec.label), host);
        label->setToolTip(help);
        label->setWordWrap(true);
        label->setBuddy(editor);
        form->addRow(label, editor);
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
    updatePresetMark();
}

QWidget* MethodPanel::editor(const QString& parameterName) const {
    const auto it = editors_.find(parameterName.toStdString());
    return it == editors_.end() ? nullptr : it->second;
}

} // namespace contour
