#pragma once
// Every face of the editable mesh classified at once (Bénard 2014 §4-§5,
// appendix B), with the counts every phase publishes and the first example
// of each defect for the post-conditions.
#include "contours/consistent/mesh/ConsistentMesh.h"

#include <string>
#include <vector>

namespace contour::consistent {

struct Analysis {
    std::vector<int> facing, vbo, consistent, folded;
    std::vector<char> noChart; // 1 where the corners have no common chart
    long long inconsistent = 0, undefinedVbo = 0, fbEdges = 0, degenerate = 0, contourVertices = 0,
              cusps = 0, foldedFaces = 0;
    std::string firstFb, firstUndefined, firstDegenerate, firstFolded;
};

// `published`, when given, is m.toTriangleMesh() (the same faces in the
// same order), whose opposite half-edges replace the hash look-ups.
Analysis analyse(const ConsistentMesh& m, const TriangleMesh* published = nullptr);

} // namespace contour::consistent
