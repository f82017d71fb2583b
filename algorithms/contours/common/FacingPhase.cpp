#include "contours/common/FacingPhase.h"

#include "camera/Facing.h"
#include "pipeline/FieldNames.h"

#include <string>
#include <tbb/parallel_for.h>

namespace contour {

std::vector<int> faceFacing(const TriangleMesh& mesh, const Camera& camera) {
    std::vector<int> facing(mesh.faceCount());
    tbb::parallel_for(Index(0), mesh.faceCount(), [&](Index f) {
        const Triangle& t = mesh.triangle(f);
        facing[f] = static_cast<int>(
            triangleFacing(camera, mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2])));
    });
    return facing;
}

void publishFaceFacing(const PhaseContext& ctx, Snapshot& s) {
    std::vector<int> facing = faceFacing(*s.mesh, ctx.camera);
    long long front = 0, back = 0, edgeOn = 0;
    for (int f : facing) {
        front += f > 0;
        back += f < 0;
        edgeOn += f == 0;
    }
    s.setField(fields::kFacing, {FieldLocation::Face, std::move(facing),
                                 "+1 front-facing, -1 back-facing, 0 edge-on (exact predicate)"});
    s.setCounter(counters::kFrontFaces, static_cast<double>(front));
    s.setCounter(counters::kBackFaces, static_cast<double>(back));
    s.setCounter(counters::kEdgeOnFaces, static_cast<double>(edgeOn));
    if (edgeOn > 0)
        s.notes.push_back(std::to_string(edgeOn) +
                          " faces are exactly edge-on (not in generic position, tutorial §3.5); "
                          "they count as back-facing");
}

Phase makeFacingPhase() {
    return {"facing",
            "Per-face facing for the analysis camera, from the exact orientation of the camera "
            "against each triangle's plane.",
            publishFaceFacing, [](const PhaseContext&, const Snapshot& s) {
                InvariantCheck all{"every face has a facing label", 0, ""};
                const Field* f = s.field(fields::kFacing);
                if (!f || !f->labels() ||
                    static_cast<Index>(f->labels()->size()) != s.mesh->faceCount())
                    all.violations = 1;
                return std::vector<InvariantCheck>{all};
            }};
}

} // namespace contour
