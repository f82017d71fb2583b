// The final push of the cusps' radial ends (not in the paper; extends
// Bénard 2014 §6.4 i): once the normal wiggle (§6.4, final step) is done,
// the far ends of the cusps' radial edges that still touch an inconsistent
// face are pushed along their radial curves again (RadialExtension.h), and
// the vertices of the faces still inconsistent are wiggled along their
// normals again around what moved.
#include "contours/consistent/edits/LocalEdit.h"
#include "contours/consistent/extensions/ExtensionPhases.h"
#include "contours/consistent/mesh/MeshQueries.h"
#include "contours/consistent/phases/NormalWiggle.h"
#include "contours/consistent/phases/PhaseChecks.h"
#include "contours/consistent/phases/RadialExtension.h"
#include "contours/consistent/phases/SnapshotRoundTrip.h"
#include "contours/consistent/predicates/FaceClassification.h"
#include "contours/consistent/predicates/MeshAnalysis.h"

namespace contour::consistent {

namespace {

struct CuspEndPushOptions {
    bool enabled = true;  // extension-cusp-push-final
    bool everyEnd = true; // extension-push-every-end-final
};

CuspEndPushOptions cuspEndPushOptions(const ParameterSet& p) {
    return {p.getBool("extension-cusp-push-final"), p.getBool("extension-push-every-end-final")};
}

void runCuspEndPush(const PhaseContext& ctx, Snapshot& s) {
    const CuspEndPushOptions o = cuspEndPushOptions(ctx.parameters);
    const NormalWiggleOptions wiggle = normalWiggleOptions(ctx.parameters);
    ConsistentMesh m = reload(ctx, s);
    const int phase = s.phaseIndex;
    const auto before = static_cast<double>(inconsistentFaces(m).size());
    CuspPushCounts push;
    OptimizationTally again;
    NormalWiggleStats st;
    if (o.enabled) {
        push = pushCuspRadialEnds(ctx, m, phase, o.everyEnd);
        if (push.moved > 0)
            wiggleVertices(ctx, m, wiggle, phase, again, st);
    }
    const NormalOffsetStats offsets = normalOffsetStats(m);
    publish(s, m);
    s.setCounter(counters::kInconsistentFacesBefore, before);
    s.setCounter(counters::kCuspEndsPushed, static_cast<double>(push.moved - push.everyEndMoved));
    s.setCounter(counters::kOtherEndsPushed, static_cast<double>(push.everyEndMoved));
    s.setCounter(counters::kPushWiggleTried, static_cast<double>(again.tried));
    s.setCounter(counters::kPushWiggleAccepted, static_cast<double>(again.accepted));
    s.setCounter(counters::kPushWiggleRejectedFold, static_cast<double>(st.rejectedFold));
    publishNormalOffsetStats(s, offsets);
}

} // namespace

void addCuspEndPushPhase(Method& m) {
    m.parameters.push_back(
        {"extension-cusp-push-final",
         "Extension: cusp push after the normal wiggle",
         "Not in the paper: the cusps' radial ends are pushed again "
         "(extension-cusp-push-depth) after the normal wiggle (§6.4), on the faces still "
         "inconsistent then.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.parameters.push_back(
        {"extension-push-every-end-final",
         "Extension: push every radial end at the end",
         "Not in the paper: after the cusps' final push, the far ends of all radial "
         "edges at inconsistent faces are pushed the same way, each push kept only when "
         "fewer faces are inconsistent. Needs extension-cusp-push-depth > 0 and "
         "extension-cusp-push-final.",
         ParameterType::Bool,
         true,
         0,
         0,
         {}});
    m.addPhase(
        {"cusp-end-push",
         "Not in the paper: with extension-cusp-push-final, the far ends of the cusps' radial "
         "edges that still touch an inconsistent face are pushed along their radial curves "
         "through up to extension-cusp-push-depth faces (as radial-extension does), then with "
         "extension-push-every-end-final every radial end; when an end moved, the vertices of "
         "the inconsistent faces are wiggled along their normals again (§6.4).",
         runCuspEndPush, normalWiggleChecks});
}

} // namespace contour::consistent
