// The method panel's form for the consistent method: one collapsible
// section per parameter group, the preset selector (an edit marks the chosen
// preset modified, choosing it again restores it), and the method's
// description wrapping inside the panel. Needs a display: run under
// `xvfb-run -a -s "-screen 0 1600x1200x24"`.
#include "MethodPanel.h"
#include "contours/Methods.h"

#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QToolButton>
#include <QtTest>

using namespace contour;

class TestMethodPanel : public QObject {
    Q_OBJECT

private slots:
    void consistentFormHasOneSectionPerGroup() {
        MethodPanel panel;
        QVERIFY(panel.setMethod(QStringLiteral("consistent")));
        const Method& m = *findMethod("consistent");
        QStringList expected;
        for (const std::string& group : m.parameterGroups())
            expected.push_back(QString::fromStdString(group));
        QCOMPARE(panel.groups(), expected);
        for (const QString& group : expected) {
            auto* header =
                panel.findChild<QToolButton*>(QStringLiteral("group-%1-header").arg(group));
            auto* body = panel.findChild<QWidget*>(QStringLiteral("group-%1").arg(group));
            QVERIFY2(header && body, qPrintable(group));
            QCOMPARE(header, panel.groupHeader(group));
            QCOMPARE(body, panel.groupBody(group));
            QVERIFY(!header->text().isEmpty());
            // Every editor of the group lives in its section.
            for (const ParameterSpec& spec : m.parameters)
                if (QString::fromStdString(spec.group) == group)
                    QVERIFY2(body->isAncestorOf(panel.editor(QString::fromStdString(spec.name))),
                             spec.name.c_str());
        }
    }

    void sectionsCollapseAndExpand() {
        MethodPanel panel;
        QVERIFY(panel.setMethod(QStringLiteral("consistent")));
        panel.resize(360, 900);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        const QString group = QStringLiteral("cusp-detection");
        QToolButton* header = panel.groupHeader(group);
        QWidget* body = panel.groupBody(group);
        QVERIFY(header && body);
        const bool open = panel.isGroupExpanded(group);
        QCOMPARE(body->isVisible(), open);
        QTest::mouseClick(header, Qt::LeftButton);
        QCOMPARE(panel.isGroupExpanded(group), !open);
        QCOMPARE(body->isVisible(), !open);
        QCOMPARE(header->arrowType(), open ? Qt::RightArrow : Qt::DownArrow);
        QTest::mouseClick(header, Qt::LeftButton);
        QCOMPARE(panel.isGroupExpanded(group), open);
        QCOMPARE(body->isVisible(), open);
        panel.setGroupExpanded(group, true);
        QVERIFY(body->isVisible());
        QVERIFY(panel.editor(QStringLiteral("cusp-contour-samples"))->isVisible());
    }

    void paperPresetChangesTheForm() {
        MethodPanel panel;
        QVERIFY(panel.setMethod(QStringLiteral("consistent")));
        QComboBox* presets = panel.presetSelector();
        QVERIFY(presets);
        QCOMPARE(presets->objectName(), QStringLiteral("presetSelector"));
        QVERIFY(presets->findData(QStringLiteral("default")) >= 0);
        QVERIFY(presets->findData(QStringLiteral("paper")) >= 0);
        QCOMPARE(panel.presetName(), QStringLiteral("default"));
        auto* patchSearch = qobject_cast<QCheckBox*>(panel.editor(QStringLiteral("patch-search")));
        auto* samples =
            qobject_cast<QSpinBox*>(panel.editor(QStringLiteral("cusp-contour-samples")));
        QVERIFY(patchSearch && samples);
        QVERIFY(patchSearch->isChecked());
        QVERIFY(samples->value() > 0);
        QSignalSpy changed(&panel, &MethodPanel::parametersChanged);
        QVERIFY(panel.setPreset(QStringLiteral("paper")));
        QCOMPARE(changed.count(), 1);
        QCOMPARE(panel.presetName(), QStringLiteral("paper"));
        QVERIFY(!patchSearch->isChecked());
        QCOMPARE(samples->value(), 0);
        const ParameterSet values = panel.parameters();
        QVERIFY(!values.getBool("patch-search"));
        QVERIFY(values.values() == presetValues(findMethod("consistent")->parameters,
                                                *findMethod("consistent")->preset("paper"))
                                       .values());
        QVERIFY(panel.setPreset(QStringLiteral("default")));
        QVERIFY(panel.parameters().values() ==
                ParameterSet::defaults(findMethod("consistent")->parameters).values());
        QVERIFY(!panel.setPreset(QStringLiteral("no-such-preset")));
        // The methods without extensions offer the defaults only.
        QVERIFY(panel.setMethod(QStringLiteral("mesh")));
        QCOMPARE(presets->count(), 1);
        QCOMPARE(panel.presetName(), QStringLiteral("default"));
    }

    void editingAfterAPresetMarksItModified() {
        MethodPanel panel;
        QVERIFY(panel.setMethod(QStringLiteral("consistent")));
        const Method& m = *findMethod("consistent");
        const ParameterSet paper = presetValues(m.parameters, *m.preset("paper"));
        QComboBox* presets = panel.presetSelector();
        QVERIFY(panel.setPreset(QStringLiteral("paper")));
        QCOMPARE(presets->currentText(), QStringLiteral("paper"));
        QVERIFY(!panel.isPresetModified());
        auto* snap = qobject_cast<QDoubleSpinBox*>(panel.editor(QStringLiteral("snap-fraction")));
        auto* patchSearch = qobject_cast<QCheckBox*>(panel.editor(QStringLiteral("patch-search")));
        QVERIFY(snap && patchSearch);
        QCOMPARE(snap->value(), paper.getDouble("snap-fraction"));
        const double other = paper.getDouble("snap-fraction") + 0.1;

        // An edit marks the preset modified; the preset stays the one chosen.
        QSignalSpy changed(&panel, &MethodPanel::parametersChanged);
        snap->setValue(other);
        QCOMPARE(changed.count(), 1);
        QVERIFY(panel.isPresetModified());
        QCOMPARE(presets->currentText(), QStringLiteral("paper (modified)"));
        QCOMPARE(panel.presetName(), QStringLiteral("paper"));
        QCOMPARE(presets->itemText(presets->findData(QStringLiteral("default"))),
                 QStringLiteral("default"));
        // Back to the preset's value: not modified any more.
        snap->setValue(paper.getDouble("snap-fraction"));
        QVERIFY(!panel.isPresetModified());
        QCOMPARE(presets->currentText(), QStringLiteral("paper"));

        // Two edits, then the user picks the preset again: its values return.
        snap->setValue(other);
        patchSearch->setChecked(!patchSearch->isChecked());
        QCOMPARE(presets->currentText(), QStringLiteral("paper (modified)"));
        changed.clear();
        emit presets->activated(presets->currentIndex());
        QCOMPARE(changed.count(), 1);
        QCOMPARE(snap->value(), paper.getDouble("snap-fraction"));
        QCOMPARE(patchSearch->isChecked(), paper.getBool("patch-search"));
        QVERIFY(panel.parameters().values() == paper.values());
        QVERIFY(!panel.isPresetModified());
        QCOMPARE(presets->currentText(), QStringLiteral("paper"));

        // Values put into the form (a reopened run) are compared with the
        // preset they started from, which is selected without changing them.
        ParameterSet restored = paper;
        restored.set("snap-fraction", other);
        changed.clear();
        panel.setParameters(restored);
        QVERIFY(panel.setStartingPreset(QStringLiteral("default")));
        QVERIFY(panel.isPresetModified());
        QCOMPARE(presets->currentText(), QStringLiteral("default (modified)"));
        QVERIFY(panel.setStartingPreset(QStringLiteral("paper")));
        QCOMPARE(changed.count(), 0);
        QCOMPARE(panel.presetName(), QStringLiteral("paper"));
        QCOMPARE(presets->currentText(), QStringLiteral("paper (modified)"));
        QCOMPARE(presets->itemText(presets->findData(QStringLiteral("default"))),
                 QStringLiteral("default"));
        QVERIFY(panel.parameters().values() == restored.values());
        QVERIFY(!panel.setStartingPreset(QStringLiteral("no-such-preset")));
        QCOMPARE(panel.presetName(), QStringLiteral("paper"));
        // A method change starts from its defaults, unmarked.
        QVERIFY(panel.setMethod(QStringLiteral("mesh")));
        QCOMPARE(presets->currentText(), QStringLiteral("default"));
        QVERIFY(!panel.isPresetModified());
    }

    void descriptionWrapsInsideThePanel() {
        MethodPanel panel;
        QVERIFY(panel.setMethod(QStringLiteral("consistent")));
        panel.resize(320, 900);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        QLabel* description = panel.descriptionLabel();
        QVERIFY(description);
        QCOMPARE(description->objectName(), QStringLiteral("methodDescription"));
        QVERIFY(description->wordWrap());
        QVERIFY(!description->text().isEmpty());
        QTRY_VERIFY(description->geometry().right() < panel.width());
        QVERIFY(description->width() <= panel.width());
        // Several lines: taller than one line of its font.
        QVERIFY(description->height() > 2 * description->fontMetrics().height());
        // The form can be as narrow as the dock (its minimum width is 320).
        QVERIFY2(panel.minimumSizeHint().width() <= 320,
                 qPrintable(QString::number(panel.minimumSizeHint().width())));
    }
};

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    TestMethodPanel test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_method_panel.moc"
