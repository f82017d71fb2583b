// The patch search of the consistent method on its own (edits/PatchSearch.h:
// compound moves, not in the paper, extending the edits of Bénard 2014 §6.3
// h and §6.4), without a phase around it. Its input is the mesh the method
// hands it: the bumpy torus (resolution 12) after vertex removal, from each
// of the 26 protocol views (a few inconsistent faces each, some views none).
// On each view the search must leave an oriented manifold with no more
// inconsistent faces, its tagged edges and CC edges kept, C vertices only
// moved along the contour, and counts that agree with the mesh (a new vertex
// adds two faces, accepted moves are the inserted plus the relocated
// vertices). Where it accepts nothing (no inconsistent face, every move
// rejected, or every patch kind off) the mesh is left exactly as it was.
// The patch-search phase publishes what the search returns on the same
// input, and a cancelled search leaves a valid mesh. The phase over whole
// runs: test_consistent_patch_search.
#include "ContourTestSupport.h"
#include "MeshChecks.h"
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/edits/PatchSearch.h"
#include "contours/consistent/extensions/PatchSearchOptions.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "pipeline/CounterNames.h"

#include <QtTest>
#include <cmath>
#include <cstring>
#include <stdexcept>

using namespace contour;
using namespace contour::consistent;
using namespace contour::testing;

namespace {

// The method's defaults, without the cusp retry (a branch after the phase:
// the snapshots of one straight run).
const Overrides kOverrides{{"cusp-retry", false}};

// One view's input to the search (the mesh after vertex removal, the
// settings the method's parameters give) and what the patch-search phase
// published from it.
struct ViewInput {
    ConsistentMesh mesh;
    PatchSearchSettings settings;
    int phase = 0;
    Snapshot published;
};

ViewInput viewInput(const std::shared_ptr<const PolygonMesh>& cage, const Camera& camera) {
    const MethodRun r = run("consistent", cage, camera, kOverrides, "patch-search");
    const ParameterSet p = parametersOf(*findMethod("consistent"), kOverrides);
    ConsistentMesh m = reload(PhaseContext(camera, p), r.phase("vertex-removal"));
    const PatchSearchSettings s = PatchSearchOptions::read(p).settings(m);
    const Snapshot& published = r.phase("patch-search");
    return {std::move(m), s, published.phaseIndex, published};
}

// Every view's input, computed once for the suite.
const std::vector<ViewInput>& inputs() {
    static const std::vector<ViewInput> all = [] {
        const std::shared_ptr<const PolygonMesh> cage = shape("bumpy-torus", 12);
        std::vector<ViewInput> out;
        for (const Camera& camera : Camera::views26(cage->boundingBox(), Viewport{800, 600}))
            out.push_back(viewInput(cage, camera));
        return out;
    }();
    return all;
}

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// "" when a and b hold the same vertices (every field, to the bit), faces,
// face phases and edge tags; else the first difference.
std::string meshDifference(const ConsistentMesh& a, const ConsistentMesh& b) {
    if (a.vertexCount() != b.vertexCount() || a.faceCount() != b.faceCount())
        return "sizes differ: " + std::to_string(a.vertexCount()) + " / " +
               std::to_string(a.faceCount()) + " against " + std::to_string(b.vertexCount()) +
               " / " + std::to_string(b.faceCount());
    for (Index v = 0; v < a.vertexCount(); ++v) {
        const MeshVertex &x = a.vertex(v), &y = b.vertex(v);
        bool same = x.preimage.face == y.preimage.face && sameBits(x.preimage.u, y.preimage.u) &&
                    sameBits(x.preimage.v, y.preimage.v) && sameBits(x.g, y.g) &&
                    sameBits(x.normalOffset, y.normalOffset) && x.cusp == y.cusp &&
                    x.label == y.label && x.provenance == y.provenance && x.phase == y.phase;
        for (int d = 0; d < 3; ++d)
            same = same && sameBits(x.position[d], y.position[d]) &&
                   sameBits(x.normal[d], y.normal[d]);
        if (!same)
            return "vertex " + std::to_string(v) + " differs";
    }
    for (Index f = 0; f < a.faceCount(); ++f)
        if (a.face(f) != b.face(f) || a.facePhase(f) != b.facePhase(f))
            return "face " + std::to_string(f) + " differs";
    if (a.edgeTags() != b.edgeTags())
        return "edge tags differ";
    return {};
}

long long contourEdges(const ConsistentMesh& m) {
    long long n = 0;
    for (const auto& [a, b] : m.edges())
        n += m.vertex(a).label == VertexLabel::Contour && m.vertex(b).label == VertexLabel::Contour;
    return n;
}

// Faces that are not counter-clockwise in a common chart (appendix B).
long long parameterFolds(const ConsistentMesh& m) {
    long long n = 0;
    for (Index f = 0; f < m.faceCount(); ++f) {
        const std::optional<int> o = m.parameterOrientation(f);
        n += !o || *o <= 0;
    }
    return n;
}

// "" when `after` is what a search that returned `r` may leave of `before`;
// else the first broken rule.
std::string brokenRule(const ConsistentMesh& before, const ConsistentMesh& after,
                       const PatchSearchSettings& set, const PatchSearchResult& r) {
    const PatchSearchStats& n = r.moves;
    if (const std::string e = connectivityErrors(after); !e.empty())
        return "not an oriented manifold: " + e;
    const auto in = static_cast<long long>(inconsistentFaces(before).size());
    const auto out = static_cast<long long>(inconsistentFaces(after).size());
    if (r.faces.before != in)
        return "tally.before " + std::to_string(r.faces.before) + ", the input has " +
               std::to_string(in);
    if (out > in)
        return "inconsistent faces " + std::to_string(in) + " -> " + std::to_string(out);
    if (r.faces.accepted > r.faces.tried)
        return "more moves accepted than faces tried";
    if (r.faces.accepted != n.inserted + n.relocated)
        return "accepted " + std::to_string(r.faces.accepted) + ", inserted + relocated " +
               std::to_string(n.inserted + n.relocated);
    if (n.slid > n.relocated || n.newRadial > r.faces.accepted || n.newRadialCusps > n.newRadial)
        return "move kinds do not add up";
    if (n.rejected + n.unplanned > n.samples || (n.samples > 0 && n.patches == 0))
        return "samples do not add up";
    if (r.faces.tried > 0 && r.faces.sweeps == 0)
        return "faces tried without a sweep";
    if (after.vertexCount() != before.vertexCount() + n.inserted ||
        after.faceCount() != before.faceCount() + 2 * n.inserted)
        return "a new vertex must add one vertex and two faces";
    if (parameterFolds(after) > parameterFolds(before))
        return "a parameter-space fold appeared";
    if (contourEdges(after) != contourEdges(before))
        return "CC edges " + std::to_string(contourEdges(before)) + " -> " +
               std::to_string(contourEdges(after));
    // Tagged edges stay (vertex indices are kept: nothing is compacted); the
    // only new tags are the new radial edges.
    long long newTags = 0;
    for (const auto& [key, tag] : after.edgeTags()) {
        const auto was = before.edgeTags().find(key);
        if (was == before.edgeTags().end()) {
            if (tag != kRadialEdge)
                return "a new edge tag other than radial";
            ++newTags;
        } else if (was->second != tag)
            return "an edge tag changed";
    }
    if (after.edgeTags().size() != before.edgeTags().size() + static_cast<size_t>(newTags) ||
        newTags != n.newRadial)
        return "tagged edges: " + std::to_string(before.edgeTags().size()) + " -> " +
               std::to_string(after.edgeTags().size()) + ", new radial edges " +
               std::to_string(n.newRadial);
    // C vertices stay C, no vertex becomes one, and a C vertex that moved
    // lies on the contour; cusps never move.
    for (Index v = 0; v < after.vertexCount(); ++v) {
        const MeshVertex& x = after.vertex(v);
        const bool wasC =
            v < before.vertexCount() && before.vertex(v).label == VertexLabel::Contour;
        if ((x.label == VertexLabel::Contour) != wasC)
            return "vertex " + std::to_string(v) + " changed to or from C";
        if (!wasC || x.position == before.vertex(v).position)
            continue;
        if (x.cusp)
            return "cusp " + std::to_string(v) + " moved";
        if (!(std::abs(x.g) <= set.rootTolerance))
            return "C vertex " + std::to_string(v) + " moved off the contour";
    }
    return {};
}

} // namespace

class TestPatchSearch : public QObject {
    Q_OBJECT
private slots:
    // Every view: the rules of brokenRule(); where nothing was accepted,
    // the very same mesh. Over the views the search must meet each case at
    // least once: faces removed, faces tried and every move rejected, no
    // inconsistent face at all.
    void keepsTheMeshValidOnEveryView() {
        long long in = 0, out = 0;
        int improved = 0, rejectedAll = 0, consistent = 0;
        for (size_t v = 0; v < inputs().size(); ++v) {
            const ViewInput& input = inputs()[v];
            const ConsistentMesh& before = input.mesh;
            QVERIFY2(connectivityErrors(before).empty(), qPrintable(QString("view %1").arg(v)));
            ConsistentMesh m = before;
            const PatchSearchResult r = searchPatches(m, input.settings, input.phase);
            const std::string broken = brokenRule(before, m, input.settings, r);
            QVERIFY2(broken.empty(), qPrintable(QString("view %1: %2").arg(v).arg(broken.c_str())));
            if (r.faces.accepted == 0) {
                const std::string changed = meshDifference(before, m);
                QVERIFY2(changed.empty(),
                         qPrintable(
                             QString("view %1, nothing accepted: %2").arg(v).arg(changed.c_str())));
            }
            const auto faces = static_cast<long long>(inconsistentFaces(m).size());
            in += r.faces.before;
            out += faces;
            improved += faces < r.faces.before;
            rejectedAll += r.faces.tried > 0 && r.faces.accepted == 0;
            consistent += r.faces.before == 0;
        }
        qInfo("bumpy torus, 26 views: inconsistent faces %lld -> %lld (%d views fewer, %d with "
              "every move rejected, %d without inconsistent faces)",
              in, out, improved, rejectedAll, consistent);
        QVERIFY(improved > 0);
        QVERIFY(rejectedAll > 0);
        QVERIFY(consistent > 0);
        QVERIFY(out < in);
    }

    // The phase is the search on the mesh vertex removal left, with the
    // settings its parameters give: what it publishes is what the search
    // returns there.
    void thePhasePublishesTheSearch() {
        int moved = 0;
        for (size_t v = 0; v < inputs().size(); ++v) {
            const ViewInput& input = inputs()[v];
            ConsistentMesh m = input.mesh;
            const PatchSearchResult r = searchPatches(m, input.settings, input.phase);
            const Snapshot& s = input.published;
            const QString at = QString("view %1").arg(v);
            const auto same = [&](const CounterName& key, long long value) {
                return s.counter(key, -1.0) == static_cast<double>(value);
            };
            QVERIFY2(same(counters::kInconsistentFacesBefore, r.faces.before), qPrintable(at));
            QVERIFY2(same(counters::kFacesTried, r.faces.tried), qPrintable(at));
            QVERIFY2(same(counters::kFacesAccepted, r.faces.accepted), qPrintable(at));
            QVERIFY2(same(counters::kSweeps, r.faces.sweeps), qPrintable(at));
            QVERIFY2(same(counters::kPatchesSearched, r.moves.patches), qPrintable(at));
            QVERIFY2(same(counters::kPatchSamples, r.moves.samples), qPrintable(at));
            QVERIFY2(same(counters::kVerticesInserted, r.moves.inserted), qPrintable(at));
            QVERIFY2(same(counters::kVerticesRelocated, r.moves.relocated), qPrintable(at));
            QVERIFY2(same(counters::kNewRadialEdges, r.moves.newRadial), qPrintable(at));
            QVERIFY2(same(counters::kFacesSkippedNothingChangedNearThem, r.moves.skipped),
                     qPrintable(at));
            QVERIFY2(same(counters::kInconsistentFaces,
                          static_cast<long long>(inconsistentFaces(m).size())),
                     qPrintable(at));
            QCOMPARE(m.faceCount(), s.mesh->faceCount());
            moved += r.faces.accepted > 0;
        }
        QVERIFY(moved > 0);
    }

    // Each patch kind can be switched off: without insertion patches no
    // vertex is inserted, without relocation patches none moves, without
    // the late moves no C vertex slides and no radial edge appears; with
    // neither kind the search tries the faces and changes nothing.
    void patchKindsSwitchOff() {
        long long inserted = 0, relocated = 0, tried = 0;
        for (size_t v = 0; v < inputs().size(); ++v) {
            const ViewInput& input = inputs()[v];
            const QString at = QString("view %1").arg(v);
            {
                ConsistentMesh m = input.mesh;
                PatchSearchSettings s = input.settings;
                s.insert = false;
                const PatchSearchResult r = searchPatches(m, s, input.phase);
                const std::string broken = brokenRule(input.mesh, m, s, r);
                QVERIFY2(broken.empty(), qPrintable(at + ": " + broken.c_str()));
                QVERIFY2(r.moves.inserted == 0, qPrintable(at));
                relocated += r.moves.relocated;
            }
            {
                ConsistentMesh m = input.mesh;
                PatchSearchSettings s = input.settings;
                s.relocate = false;
                s.contourSlide = false;
                s.newRadialEnds = false;
                const PatchSearchResult r = searchPatches(m, s, input.phase);
                const std::string broken = brokenRule(input.mesh, m, s, r);
                QVERIFY2(broken.empty(), qPrintable(at + ": " + broken.c_str()));
                QVERIFY2(r.moves.relocated == 0 && r.moves.slid == 0 && r.moves.newRadial == 0,
                         qPrintable(at));
                inserted += r.moves.inserted;
            }
            {
                ConsistentMesh m = input.mesh;
                PatchSearchSettings s = input.settings;
                s.insert = false;
                s.relocate = false;
                const PatchSearchResult r = searchPatches(m, s, input.phase);
                QVERIFY2(r.moves.patches == 0 && r.faces.accepted == 0, qPrintable(at));
                const std::string changed = meshDifference(input.mesh, m);
                QVERIFY2(changed.empty(), qPrintable(at + ": " + changed.c_str()));
                tried += r.faces.tried;
            }
        }
        // The switches were not idle: each kind alone still moves vertices.
        QVERIFY(inserted > 0);
        QVERIFY(relocated > 0);
        QVERIFY(tried > 0);
    }

    // A search stopped from checkCancelled (as a phase is cancelled) leaves
    // the moves it applied, each whole: a valid mesh, no more inconsistent
    // faces.
    void aCancelledSearchLeavesAValidMesh() {
        int cancelled = 0;
        for (size_t v = 0; v < inputs().size(); ++v) {
            const ViewInput& input = inputs()[v];
            ConsistentMesh m = input.mesh;
            const auto before = static_cast<long long>(inconsistentFaces(m).size());
            if (before < 2)
                continue;
            int visits = 0;
            bool thrown = false;
            try {
                searchPatches(m, input.settings, input.phase, [&] {
                    if (++visits == 2)
                        throw PhaseCancelled();
                });
            } catch (const PhaseCancelled&) {
                thrown = true;
            }
            QVERIFY(thrown);
            const QString at = QString("view %1").arg(v);
            const std::string e = connectivityErrors(m);
            QVERIFY2(e.empty(), qPrintable(at + ": " + e.c_str()));
            QVERIFY2(static_cast<long long>(inconsistentFaces(m).size()) <= before, qPrintable(at));
            ++cancelled;
        }
        QVERIFY(cancelled > 0);
    }
};

QTEST_APPLESS_MAIN(TestPatchSearch)
#include "test_patch_search.moc"
