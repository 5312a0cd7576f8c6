// What a solution read back from its file (format 7, docs/solution-format.md)
// must hold: the mesh, trees, T-vertices, links and figures exactly; every
// stored value as its nearest f32; the derived values (B = E + direct +
// indirect, the node values, the error estimates) within f32 rounding.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <vector>

#include "io/solution_geometry.h"
#include "radiosity/solution.h"

namespace radiant::test {

/// A stored value comes back as the f32 nearest to it, exactly.
inline void expectStoredAsSingle(const std::vector<Bands> &written, const std::vector<Bands> &back,
                                 const std::string &what) {
  ASSERT_EQ(back.size(), written.size()) << what;
  for (size_t i = 0; i < written.size(); ++i)
    for (int b = 0; b < kBandCount; ++b)
      ASSERT_EQ(back[i][b], double(float(written[i][b]))) << what << " " << i << " band " << b;
}

/// A value derived from f32 parts: within 10⁻⁶ of the largest of its kind.
/// Each part is rounded by at most 2⁻²⁴ ≈ 6·10⁻⁸ of itself, and a sum or an
/// area-weighted average of a few of them by a few times that; 10⁻⁶ leaves a
/// margin and is still far below any solver's noise or tolerance.
inline void expectWithinSingle(const std::vector<Bands> &written, const std::vector<Bands> &back,
                               const std::string &what) {
  ASSERT_EQ(back.size(), written.size()) << what;
  double largest = 0;
  for (const Bands &b : written) largest = std::max({largest, std::abs(b.max()), std::abs(b.min())});
  for (size_t i = 0; i < written.size(); ++i)
    for (int b = 0; b < kBandCount; ++b)
      ASSERT_NEAR(back[i][b], written[i][b], 1e-6 * largest) << what << " " << i << " band " << b;
}

inline void expectSameTopology(const Solution &written, const Solution &back) {
  const RadiosityMesh &a = written.mesh, &b = back.mesh;
  EXPECT_TRUE(sameMeshGeometry(a, b)) << "patches, elements, nodes or trees differ";
  EXPECT_EQ(b.patchOfFace, a.patchOfFace);
  EXPECT_EQ(b.facePatchCount, a.facePatchCount);
  EXPECT_EQ(b.nodeOnCut, a.nodeOnCut);
  // Derived from the scene's vertex normals on reading, as the builder did; the pools depend on them.
  EXPECT_EQ(b.patchCornerNormals, a.patchCornerNormals);
  EXPECT_EQ(b.nodeShadingNormals, a.nodeShadingNormals);
  EXPECT_EQ(back.nodePools(), written.nodePools());
  ASSERT_EQ(b.tVertices.size(), a.tVertices.size());
  for (size_t t = 0; t < a.tVertices.size(); ++t) {
    EXPECT_EQ(b.tVertices[t].node, a.tVertices[t].node);
    EXPECT_EQ(b.tVertices[t].edgeStart, a.tVertices[t].edgeStart);
    EXPECT_EQ(b.tVertices[t].edgeEnd, a.tVertices[t].edgeEnd);
    EXPECT_EQ(b.tVertices[t].t, a.tVertices[t].t);
  }
  ASSERT_EQ(back.links.size(), written.links.size());
  for (size_t l = 0; l < written.links.size(); ++l) {
    const Link &x = written.links[l], &y = back.links[l];
    EXPECT_TRUE(x.receiver == y.receiver && x.source == y.source && x.formFactor == y.formFactor &&
                x.visibleFraction == y.visibleFraction && x.visibility == y.visibility &&
                x.carriedPower == y.carriedPower)
        << "link " << l;
  }
  EXPECT_EQ(back.stats.solver, written.stats.solver);
  EXPECT_EQ(back.stats.iterations, written.stats.iterations);
  EXPECT_EQ(back.stats.residual, written.stats.residual);
  EXPECT_EQ(back.stats.formFactorRays, written.stats.formFactorRays);
  for (int b = 0; b < kBandCount; ++b) {
    EXPECT_EQ(back.stats.emittedPower[b], written.stats.emittedPower[b]);
    EXPECT_EQ(back.stats.absorbedPower[b], written.stats.absorbedPower[b]);
    EXPECT_EQ(back.stats.escapedPower[b], written.stats.escapedPower[b]);
    EXPECT_EQ(back.ambient[b], written.ambient[b]);
    EXPECT_EQ(back.indirectAmbient[b], written.indirectAmbient[b]);
  }
}

/// Every field of a solution against what it was written from.
inline void expectSolutionReadBack(const Solution &written, const Solution &back) {
  expectSameTopology(written, back);
  // ρ and E are derived from the materials bit for bit, or stored as f32.
  for (size_t e = 0; e < written.elementCount(); ++e)
    for (int b = 0; b < kBandCount; ++b) {
      ASSERT_TRUE(back.reflectance[e][b] == written.reflectance[e][b] ||
                  back.reflectance[e][b] == double(float(written.reflectance[e][b])))
          << "element " << e;
      ASSERT_TRUE(back.emission[e][b] == written.emission[e][b] ||
                  back.emission[e][b] == double(float(written.emission[e][b])))
          << "element " << e;
    }
  expectStoredAsSingle(written.direct, back.direct, "direct");
  expectStoredAsSingle(written.indirect, back.indirect, "indirect");
  expectStoredAsSingle(written.irradiance, back.irradiance, "irradiance");
  expectStoredAsSingle(written.unshot, back.unshot, "unshot");
  std::vector<Bands> transmittance(written.elementCount());
  for (size_t e = 0; e < written.elementCount(); ++e) transmittance[e] = written.transmittanceOf(e);
  expectStoredAsSingle(transmittance, back.transmittance, "transmittance");
  expectStoredAsSingle(written.transmittedDirect, back.transmittedDirect, "transmitted direct");
  expectStoredAsSingle(written.transmittedIndirect, back.transmittedIndirect, "transmitted indirect");
  expectStoredAsSingle(written.nodeDirectIrradiance, back.nodeDirectIrradiance, "node direct irradiance");
  expectStoredAsSingle(written.nodeIndirectIrradiance, back.nodeIndirectIrradiance, "node indirect irradiance");
  expectStoredAsSingle(written.treeRadiosity, back.treeRadiosity, "tree radiosity");
  expectWithinSingle(written.radiosity, back.radiosity, "radiosity");
  expectWithinSingle(written.nodeRadiosity, back.nodeRadiosity, "node radiosity");
  expectWithinSingle(written.nodeReflectance, back.nodeReflectance, "node reflectance");
  ASSERT_EQ(back.errorEstimate.size(), written.errorEstimate.size());
  // A ratio of a node's difference from its element to the element's value:
  // the f32 rounding of both, relative to the larger of them.
  for (size_t e = 0; e < written.errorEstimate.size(); ++e)
    ASSERT_NEAR(back.errorEstimate[e], written.errorEstimate[e], 1e-5 * std::max(1.0, written.errorEstimate[e]))
        << "element " << e;
}

/// A solution read back and written again reads back bit for bit: nothing is
/// rounded twice or derived differently the second time.
inline void expectBitIdentical(const Solution &a, const Solution &b) {
  expectSameTopology(a, b);
  for (auto member :
       {&Solution::reflectance, &Solution::emission, &Solution::radiosity, &Solution::direct, &Solution::indirect,
        &Solution::unshot, &Solution::irradiance, &Solution::transmittance, &Solution::transmittedDirect,
        &Solution::transmittedIndirect, &Solution::nodeRadiosity, &Solution::nodeDirectIrradiance,
        &Solution::nodeIndirectIrradiance, &Solution::nodeReflectance, &Solution::treeRadiosity})
    EXPECT_TRUE(sameBits(a.*member, b.*member));
  ASSERT_EQ(a.errorEstimate.size(), b.errorEstimate.size());
  for (size_t e = 0; e < a.errorEstimate.size(); ++e)
    ASSERT_EQ(std::bit_cast<uint64_t>(a.errorEstimate[e]), std::bit_cast<uint64_t>(b.errorEstimate[e]));
}

}  // namespace radiant::test
