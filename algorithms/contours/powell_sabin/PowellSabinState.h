#pragma once
// The working data the powell-sabin method attaches to its snapshots
// (Snapshot::methodState), for readers outside the method: the inspector,
// the export of the spline and the tests' oracles. A cache of what the
// fields came from: every phase can rebuild it by re-running the fit.
#include "contours/powell_sabin/ConeLayout.h"
#include "contours/powell_sabin/ContourChains.h"
#include "contours/powell_sabin/PatchContour.h"
#include "contours/powell_sabin/PatchCusps.h"
#include "contours/powell_sabin/PowellSabinSpline.h"
#include "mesh/TriangleMesh.h"
#include "pipeline/Snapshot.h"

#include <memory>
#include <vector>

namespace contour::powell_sabin {

// The runner hands each phase a copy of the previous snapshot; the stages
// need the input's triangulation, which the cone phase replaces.
struct PowellSabinState : MethodState {
    std::shared_ptr<const TriangleMesh> triangulatedCage;
    // Per view, from the fit on: the spline (in the view's transformed
    // coordinates, ProjectiveTransform.h), its layout and tessellation
    // level; then the contour segments, their chains and the cusps.
    std::shared_ptr<const ConeLayout> layout;
    std::shared_ptr<const PowellSabinSpline> spline;
    int tessellationLevel = 0;
    std::shared_ptr<const std::vector<ContourSegment>> segments;
    std::shared_ptr<const ContourChaining> chaining;
    std::shared_ptr<const std::vector<PatchCusp>> cusps;
};

// The snapshot's state, or nullptr when it is not a powell-sabin snapshot.
inline const PowellSabinState* powellSabinState(const Snapshot& snapshot) {
    return dynamic_cast<const PowellSabinState*>(snapshot.methodState.get());
}

} // namespace contour::powell_sabin
