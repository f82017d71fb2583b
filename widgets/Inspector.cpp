#include "Inspector.h"

#include "contours/powell_sabin/PatchDescription.h"
#include "pipeline/FieldNames.h"

#include <QComboBox>
#include <QFont>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QIntValidator>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <cmath>

namespace contour {

namespace {

QString number(double v) {
    return std::isnan(v) ? QStringLiteral("NaN") : QString::number(v, 'g', 6);
}

QString yesNo(bool b) {
    return b ? QStringLiteral("yes") : QStringLiteral("no");
}

QString labelName(int label) {
    return label > 0 ? QStringLiteral("F") : label < 0 ? QStringLiteral("B") : QStringLiteral("C");
}

QString orientationName(int value, const char* front, const char* back, const char* zero) {
    return QStringLiteral("%1 (%2%3)")
        .arg(QString::fromUtf8(value > 0   ? front
                               : value < 0 ? back
                                           : zero),
             value > 0 ? QStringLiteral("+") : QString())
        .arg(value);
}

QString provenanceName(int p) {
    switch (p) {
    case 0:
        return QStringLiteral("initial");
    case 1:
        return QStringLiteral("inserted");
    case 2:
        return QStringLiteral("shifted");
    case 3:
        return QStringLiteral("wiggled");
    default:
        return QStringLiteral("unknown (%1)").arg(p);
    }
}

QString phaseName(int phase, const std::vector<std::string>& names) {
    if (phase >= 0 && phase < static_cast<int>(names.size()))
        return QStringLiteral("%1 %2").arg(phase).arg(QString::fromStdString(names[phase]));
    if (phase < 0)
        return QStringLiteral("input (%1)").arg(phase);
    return QString::number(phase);
}

QString indexList(const std::vector<Index>& indices) {
    QStringList parts;
    for (const Index i : indices)
        parts << (i == kInvalidIndex ? QStringLiteral("—") : QString::number(i));
    return parts.join(QStringLiteral(", "));
}

QString vec3(const Vec3& p) {
    return QStringLiteral("(%1, %2, %3)").arg(number(p.x()), number(p.y()), number(p.z()));
}

// Why a face is not contour-consistent, from its published VBO, facing and
// vertex labels (Definitions 1-2): "none" for a consistent face.
QString failingCondition(int consistent, int vbo, int facing, const QString& labels) {
    if (consistent != 0)
        return QStringLiteral("none");
    if (vbo == 0)
        return QStringLiteral("VBO undefined: labels %1 are none of FFF, CFF, CCF, BBB, CBB, "
                              "CCB (Definition 1)")
            .arg(labels);
    if (facing == 0)
        return QStringLiteral("edge-on face: facing is neither front nor back (Definition 2)");
    if (vbo != facing)
        return QStringLiteral("VBO %1 but the face is %2-facing (Definition 2)")
            .arg(vbo > 0 ? QStringLiteral("F") : QStringLiteral("B"),
                 facing > 0 ? QStringLiteral("front") : QStringLiteral("back"));
    return QStringLiteral("marked inconsistent although VBO equals facing");
}

void faceRows(const Snapshot& s, Index f, const std::vector<std::string>& phases,
              std::vector<InspectorRow>& rows) {
    const TriangleMesh& mesh = *s.mesh;
    const Index nf = mesh.faceCount(), nv = mesh.vertexCount();
    const Triangle& t = mesh.triangle(f);
    using L = FieldLocation;
    rows.push_back({QStringLiteral("face"), QString::number(f)});
    rows.push_back({QStringLiteral("vertices"), indexList({t[0], t[1], t[2]})});
    QString labels;
    if (const auto* label = fieldValues<int>(s, fields::kLabel, L::Vertex, nv)) {
        labels = QStringLiteral("%1 %2 %3")
                     .arg(labelName((*label)[t[0]]), labelName((*label)[t[1]]),
                          labelName((*label)[t[2]]));
        rows.push_back({QStringLiteral("vertex labels"), labels});
    }
    const auto* facing = fieldValues<int>(s, fields::kFacing, L::Face, nf);
    if (facing)
        rows.push_back(
            {QStringLiteral("facing"), orientationName((*facing)[f], "front", "back", "edge-on")});
    const auto* vbo = fieldValues<int>(s, fields::kVbo, L::Face, nf);
    if (vbo)
        rows.push_back({QStringLiteral("VBO"), orientationName((*vbo)[f], "F", "B", "undefined")});
    if (const auto* consistent = fieldValues<int>(s, fields::kConsistent, L::Face, nf)) {
        rows.push_back({QStringLiteral("consistent"), yesNo((*consistent)[f] != 0)});
        rows.push_back(
            {QStringLiteral("fails"), failingCondition((*consistent)[f], vbo ? (*vbo)[f] : 0,
                                                       facing ? (*facing)[f] : 0, labels)});
    }
    if (const auto* radial = fieldValues<int>(s, fields::kRadial, L::Face, nf))
        rows.push_back({QStringLiteral("radial"), yesNo((*radial)[f] != 0)});
    if (const auto* standard = fieldValues<int>(s, fields::kStandardRadial, L::Face, nf))
        rows.push_back({QStringLiteral("standard radial"), yesNo((*standard)[f] != 0)});
    if (const auto* folded = fieldValues<int>(s, fields::kFolded, L::Face, nf))
        rows.push_back({QStringLiteral("folded"), yesNo((*folded)[f] != 0)});
    if (const auto* domain = fieldValues<int>(s, fields::kDomainFace, L::Face, nf))
        rows.push_back({QStringLiteral("domain face"), QString::number((*domain)[f])});
    if (const auto* phase = fieldValues<int>(s, fields::kChangedByPhase, L::Face, nf))
        rows.push_back({QStringLiteral("phase"), phaseName((*phase)[f], phases)});
    std::vector<Index> neighbours;
    for (int i = 0; i < 3; ++i) {
        const Index opposite = mesh.opposite(TriangleMesh::halfedge(f, i));
        neighbours.push_back(opposite == kInvalidIndex ? kInvalidIndex
                                                       : TriangleMesh::face(opposite));
    }
    rows.push_back({QStringLiteral("neighbours"), indexList(neighbours)});
    // The spline's patch under the face (its tessellation's `patch` field).
    const auto* state = powell_sabin::powellSabinState(s);
    const auto* patch = fieldValues<int>(s, fields::kPatch, L::Face, nf);
    if (state && state->spline && state->layout && patch) {
        const auto described = powell_sabin::describePatch(*state, (*patch)[f]);
        for (size_t i = 0; i < described.size(); ++i)
            rows.push_back({QString::fromStdString(described[i].first),
                            QString::fromStdString(described[i].second), i == 0});
    }
}

void vertexRows(const Snapshot& s, Index v, const std::vector<std::string>& phases,
                std::vector<InspectorRow>& rows) {
    const TriangleMesh& mesh = *s.mesh;
    const Index nv = mesh.vertexCount();
    using L = FieldLocation;
    rows.push_back({QStringLiteral("vertex"), QString::number(v)});
    rows.push_back({QStringLiteral("position"), vec3(mesh.position(v))});
    const auto* preimageFace = fieldValues<int>(s, fields::kPreimageFace, L::Vertex, nv);
    const auto* preimageUv = fieldValues<Vec3>(s, fields::kPreimageUv, L::Vertex, nv);
    if (preimageFace && preimageUv)
        rows.push_back({QStringLiteral("preimage"),
                        QStringLiteral("face %1, u %2, v %3")
                            .arg((*preimageFace)[v])
                            .arg(number((*preimageUv)[v].x()), number((*preimageUv)[v].y()))});
    if (const auto* label = fieldValues<int>(s, fields::kLabel, L::Vertex, nv))
        rows.push_back({QStringLiteral("label"), labelName((*label)[v])});
    if (const auto* g = fieldValues<double>(s, fields::kG, L::Vertex, nv))
        rows.push_back({QStringLiteral("g"), number((*g)[v])});
    if (const auto* kr = fieldValues<double>(s, fields::kRadialCurvature, L::Vertex, nv))
        rows.push_back({QStringLiteral("κr"), number((*kr)[v])});
    if (const auto* provenance = fieldValues<int>(s, fields::kProvenance, L::Vertex, nv))
        rows.push_back({QStringLiteral("provenance"), provenanceName((*provenance)[v])});
    if (const auto* phase = fieldValues<int>(s, fields::kVertexChangedByPhase, L::Vertex, nv))
        rows.push_back({QStringLiteral("phase"), phaseName((*phase)[v], phases)});
    if (const auto* cusp = fieldValues<int>(s, fields::kCusp, L::Vertex, nv)) {
        const auto* singular = fieldValues<int>(s, fields::kSingularCusp, L::Vertex, nv);
        rows.push_back(
            {QStringLiteral("cusp"), singular && (*singular)[v] != 0
                                         ? QStringLiteral("yes, at a singular point of the surface")
                                         : yesNo((*cusp)[v] != 0)});
    }
    if (const auto* offset = fieldValues<double>(s, fields::kNormalOffset, L::Vertex, nv))
        rows.push_back({QStringLiteral("normal offset"), number((*offset)[v])});
    std::vector<Index> faces;
    for (Index f = 0; f < mesh.faceCount(); ++f) {
        const Triangle& t = mesh.triangle(f);
        if (t[0] == v || t[1] == v || t[2] == v)
            faces.push_back(f);
    }
    rows.push_back({QStringLiteral("faces"), indexList(faces)});
}

void edgeRows(const Snapshot& s, Index e, std::vector<InspectorRow>& rows) {
    const TriangleMesh& mesh = *s.mesh;
    const Index ne = mesh.edgeCount();
    const Index h = mesh.edgeHalfedge(e);
    using L = FieldLocation;
    rows.push_back({QStringLiteral("edge"), QString::number(e)});
    rows.push_back({QStringLiteral("endpoints"), indexList({mesh.from(h), mesh.to(h)})});
    const Index opposite = mesh.opposite(h);
    rows.push_back(
        {QStringLiteral("faces"),
         indexList({TriangleMesh::face(h),
                    opposite == kInvalidIndex ? kInvalidIndex : TriangleMesh::face(opposite)})});
    if (const auto* contour = fieldValues<int>(s, fields::kContourEdge, L::Edge, ne)) {
        const int c = (*contour)[e];
        rows.push_back({QStringLiteral("contour edge"), c == 1   ? QStringLiteral("convex")
                                                        : c == 2 ? QStringLiteral("concave")
                                                                 : QStringLiteral("no")});
    }
    rows.push_back({QStringLiteral("boundary"), yesNo(opposite == kInvalidIndex)});
    if (const auto* radial = fieldValues<int>(s, fields::kRadialEdge, L::Edge, ne))
        rows.push_back({QStringLiteral("radial edge"), yesNo((*radial)[e] != 0)});
    if (const auto* cusp = fieldValues<int>(s, fields::kCuspEdge, L::Edge, ne))
        rows.push_back({QStringLiteral("cusp edge"), yesNo((*cusp)[e] != 0)});
    if (const auto* zero = fieldValues<double>(s, fields::kZeroCrossing, L::Edge, ne))
        rows.push_back({QStringLiteral("zero crossing"), number((*zero)[e])});
}

QString nodeName(const ViewGraph& graph, Index n) {
    if (n == kInvalidIndex || n >= static_cast<Index>(graph.nodes.size()))
        return QStringLiteral("—");
    return QStringLiteral("%1 (%2)").arg(n).arg(
        QString::fromLatin1(toString(graph.nodes[static_cast<size_t>(n)].type)));
}

void chainRows(const Snapshot& s, Index c, std::vector<InspectorRow>& rows) {
    const ViewGraph& graph = *s.viewGraph;
    const ViewChain& chain = graph.chains[static_cast<size_t>(c)];
    rows.push_back({QStringLiteral("chain"), QString::number(c)});
    rows.push_back({QStringLiteral("type"), QString::fromLatin1(toString(chain.type))});
    rows.push_back({QStringLiteral("source"), chain.source == SegmentSource::MeshEdge
                                                  ? QStringLiteral("mesh edges")
                                                  : QStringLiteral("faces")});
    rows.push_back({QStringLiteral("points"), QString::number(chain.points.size())});
    rows.push_back({QStringLiteral("length"),
                    QStringLiteral("%1 px").arg(QString::number(chain.lengthPixels, 'f', 1))});
    rows.push_back({QStringLiteral("QI"),
                    chain.qi < 0 ? QStringLiteral("unknown") : QString::number(chain.qi)});
    rows.push_back({QStringLiteral("QI lower bound"), QString::number(chain.qiLowerBound)});
    rows.push_back({QStringLiteral("ray QI"),
                    chain.rayQi < 0 ? QStringLiteral("not tested") : QString::number(chain.rayQi)});
    rows.push_back({QStringLiteral("decided by"), QString::fromLatin1(toString(chain.decidedBy))});
    rows.push_back({QStringLiteral("ambiguous"), yesNo(chain.ambiguous)});
    QString conflict = yesNo(chain.conflict);
    for (const VisibilityConflict& k : graph.conflicts)
        if (k.chain == c) {
            conflict += QStringLiteral("; propagated QI %1, ray QI %2 (%3)")
                            .arg(k.propagatedQi)
                            .arg(k.rayQi)
                            .arg(QString::fromStdString(k.reason));
            // Which propagation step and which ray disagree.
            if (k.viaNode != kInvalidIndex)
                conflict += QStringLiteral("; propagated from chain %1 across node %2 (%3)")
                                .arg(k.fromChain)
                                .arg(k.viaNode)
                                .arg(QString::fromLatin1(toString(graph.nodes[k.viaNode].type)));
            else
                conflict += QStringLiteral("; the component's seed ray");
            conflict += QStringLiteral("; ray from (%1, %2, %3)")
                            .arg(k.rayOrigin.x(), 0, 'g', 6)
                            .arg(k.rayOrigin.y(), 0, 'g', 6)
                            .arg(k.rayOrigin.z(), 0, 'g', 6);
        }
    rows.push_back({QStringLiteral("conflict"), conflict});
    rows.push_back({QStringLiteral("concave"), yesNo(chain.concave)});
    rows.push_back({QStringLiteral("simplified away"), yesNo(chain.simplifiedAway)});
    rows.push_back({QStringLiteral("closed"), yesNo(chain.closed)});
    rows.push_back({QStringLiteral("start node"), nodeName(graph, chain.startNode)});
    rows.push_back({QStringLiteral("end node"), nodeName(graph, chain.endNode)});
    if (powell_sabin::powellSabinState(s))
        rows.push_back({QStringLiteral("patches"),
                        QString::fromStdString(powell_sabin::describeChainPatches(chain))});
}

} // namespace

std::vector<InspectorRow> inspectorRows(const Snapshot& snapshot, const Selection& selection,
                                        const std::vector<std::string>& phaseNames) {
    std::vector<InspectorRow> rows;
    if (!selectionExists(snapshot, selection))
        return rows;
    switch (selection.kind) {
    case SelectionKind::Face:
        faceRows(snapshot, selection.id, phaseNames, rows);
        break;
    case SelectionKind::Vertex:
        vertexRows(snapshot, selection.id, phaseNames, rows);
        break;
    case SelectionKind::Edge:
        edgeRows(snapshot, selection.id, rows);
        break;
    case SelectionKind::Chain:
        chainRows(snapshot, selection.id, rows);
        break;
    case SelectionKind::None:
        break;
    }
    return rows;
}

Inspector::Inspector(QWidget* parent) : QWidget(parent) {
    auto* layout = new QVBoxLayout(this);
    auto* idRow = new QHBoxLayout;
    kind_ = new QComboBox(this);
    kind_->setObjectName(QStringLiteral("inspectorKind"));
    for (const SelectionKind k :
         {SelectionKind::Face, SelectionKind::Vertex, SelectionKind::Edge, SelectionKind::Chain})
        kind_->addItem(QString::fromLatin1(toString(k)), static_cast<int>(k));
    idEdit_ = new QLineEdit(this);
    idEdit_->setObjectName(QStringLiteral("inspectorId"));
    idEdit_->setValidator(new QIntValidator(0, 2147483647, idEdit_));
    idEdit_->setPlaceholderText(tr("index"));
    idEdit_->setToolTip(tr("Select an element of the current phase by its index (Return)"));
    selectButton_ = new QPushButton(tr("Select"), this);
    idRow->addWidget(kind_);
    idRow->addWidget(idEdit_, 1);
    idRow->addWidget(selectButton_);
    layout->addLayout(idRow);
    title_ = new QLabel(this);
    title_->setWordWrap(true);
    layout->addWidget(title_);
    table_ = new QTreeWidget(this);
    table_->setObjectName(QStringLiteral("inspectorTable"));
    table_->setColumnCount(2);
    table_->setHeaderLabels({tr("Property"), tr("Value")});
    table_->setRootIsDecorated(false);
    table_->setAlternatingRowColors(true);
    table_->setWordWrap(true);
    table_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    table_->header()->setStretchLastSection(true);
    layout->addWidget(table_, 1);
    connect(idEdit_, &QLineEdit::returnPressed, this, &Inspector::requestSelection);
    connect(selectButton_, &QPushButton::clicked, this, &Inspector::requestSelection);
    showSelection(Snapshot(), Selection());
}

void Inspector::requestSelection() {
    bool ok = false;
    const int id = idEdit_->text().toInt(&ok);
    if (!ok)
        return;
    emit selectRequested({static_cast<SelectionKind>(kind_->currentData().toInt()), id});
}

void Inspector::showSelection(const Snapshot& snapshot, const Selection& selection) {
    rows_ = inspectorRows(snapshot, selection, phaseNames_);
    shown_ = rows_.empty() ? Selection() : selection;
    table_->clear();
    if (shown_.isEmpty()) {
        title_->setText(tr("Nothing selected. Click a face, vertex or edge in the 3D view, a "
                           "chain or face in the 2D view, or type an index above; N steps "
                           "through the inconsistent faces."));
        return;
    }
    title_->setText(tr("<b>%1</b> in phase %2")
                        .arg(shown_.describe(), QString::fromStdString(snapshot.phaseName)));
    // The reason a face is inconsistent is long: in full under the title too.
    if (const QString fails = value(QStringLiteral("fails"));
        !fails.isEmpty() && fails != QStringLiteral("none"))
        title_->setText(title_->text() + QStringLiteral("<br>") +
                        tr("inconsistent: %1").arg(fails));
    QTreeWidgetItem* group = nullptr;
    for (const InspectorRow& row : rows_) {
        auto* item = group && !row.heading ? new QTreeWidgetItem(group, {row.property, row.value})
                                           : new QTreeWidgetItem(table_, {row.property, row.value});
        item->setToolTip(1, row.value);
        if (row.heading) {
            QFont bold = item->font(0);
            bold.setBold(true);
            item->setFont(0, bold);
            group = item;
        }
    }
    table_->expandAll();
    const int k = kind_->findData(static_cast<int>(shown_.kind));
    if (k >= 0)
        kind_->setCurrentIndex(k);
    idEdit_->setText(QString::number(shown_.id));
}

QString Inspector::value(const QString& property) const {
    for (const InspectorRow& row : rows_)
        if (row.property == property)
            return row.value;
    return {};
}

} // namespace contour
