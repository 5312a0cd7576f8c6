#include "io/solution_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io/node_irradiance_pools.h"
#include "io/solution_geometry.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/input_file.h"

namespace radiant {

namespace {

constexpr char kMagic[16] = {'R', 'A', 'D', 'I', 'A', 'N', 'T', '-', 'S', 'O', 'L', 'U', 'T', 'I', 'O', 'N'};

class Writer {
 public:
  template <typename T>
  void put(const T &v) {
    static_assert(std::is_trivially_copyable_v<T>);
    data_.append(reinterpret_cast<const char *>(&v), sizeof v);
  }
  void put(const Vec3 &v) { put(v.x), put(v.y), put(v.z); }
  void put(const Bands &b) {
    for (int i = 0; i < kBandCount; ++i) put(b[i]);
  }
  void put(const std::string &s) {
    put(uint32_t(s.size()));
    data_ += s;
  }
  /// Bands as f32 (version 7's values: 10⁻⁷ relative, far below any solver's error).
  void putSingle(const Bands &b) {
    for (int i = 0; i < kBandCount; ++i) put(float(b[i]));
  }
  void putSingle(const std::vector<Bands> &values) {
    for (const Bands &b : values) putSingle(b);
  }
  const std::string &data() const { return data_; }

 private:
  std::string data_;
};

class Reader {
 public:
  Reader(std::string data, std::string path) : data_(std::move(data)), path_(std::move(path)) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_.data() + offset_, sizeof v);
    offset_ += sizeof v;
    return v;
  }
  Vec3 vec3() {
    Vec3 v;
    v.x = get<double>(), v.y = get<double>(), v.z = get<double>();
    return v;
  }
  Bands bands() {
    Bands b;
    for (int i = 0; i < kBandCount; ++i) b[i] = get<double>();
    return b;
  }
  Bands singleBands() {
    Bands b;
    for (int i = 0; i < kBandCount; ++i) b[i] = double(get<float>());
    return b;
  }
  /// `count` f32 band values, after checking that they fit in what is left.
  std::vector<Bands> singleBands(size_t count, const char *what) {
    std::vector<Bands> values(this->count(count, kBandCount * 4, what));
    for (Bands &b : values) b = singleBands();
    return values;
  }
  std::string string() {
    uint32_t n = get<uint32_t>();
    need(n);
    std::string s = data_.substr(offset_, n);
    offset_ += n;
    return s;
  }
  /// Checks that `count` records of `bytesEach` fit in what is left, before allocating for them.
  size_t count(uint64_t count, size_t bytesEach, const char *what) {
    if (count > (data_.size() - offset_) / std::max<size_t>(1, bytesEach))
      fail(fmt::format("the file is truncated or corrupt: it claims {} {}", count, what));
    return static_cast<size_t>(count);
  }
  [[noreturn]] void fail(const std::string &message) const { throw InputError(InputLocation{path_}, message); }
  bool atEnd() const { return offset_ == data_.size(); }
  bool startsWith(const char *prefix, size_t n) const {
    return data_.size() >= n && std::memcmp(data_.data(), prefix, n) == 0;
  }

 private:
  void need(size_t n) {
    if (data_.size() - offset_ < n)
      fail(fmt::format("the file is truncated: it ends after {} bytes, and the value at byte {} needs {}", data_.size(),
                       offset_, n));
  }
  std::string data_, path_;
  size_t offset_ = 0;
};

}  // namespace

namespace {

/// Version 7's pass contents: which parts are stored (the others are derived or empty).
enum PassContent : uint32_t {
  kGeometryStored = 1u << 0,         ///< patches, elements, nodes and trees in full (else derived)
  kFacesStored = 1u << 1,            ///< patchOfFace (else derived from the patches)
  kFacePatchCountsStored = 1u << 2,  ///< facePatchCount, with kFacesStored
  kReflectanceStored = 1u << 3,      ///< ρ per element (else from the materials)
  kEmissionStored = 1u << 4,         ///< E per element (else from the materials)
  kUnshotStored = 1u << 5,           ///< unshot radiosity per element (else 0)
  kTransmittanceStored = 1u << 6,    ///< τ per element (else 0)
  kTransmittedStored = 1u << 7,      ///< τH′ per element, direct and indirect (else none)
  kNodeIrradianceStored = 1u << 8,   ///< the irradiance at the nodes, direct and indirect (else none)
  kNodesOnCutsStored = 1u << 9,      ///< the list of nodes on a cut (else RadiosityMesh::nodeOnCut is empty)
  kTreeRadiosityStored = 1u << 10,   ///< B per tree node (hierarchical solvers; else none)
  kNodeIrradiancePooled = 1u << 11,  ///< with bit 8: one value per pool of nodes (io/node_irradiance_pools.h)
  kKnownContent = (1u << 12) - 1,
};

/// Bit of a compact patch record's shape byte (bits 0–2 hold the vertex count).
constexpr uint8_t kPatchCornersStored = 8;

/// Whether every band of every value is +0 (what a reload gives for a part not stored).
bool allZero(const std::vector<Bands> &values) {
  for (const Bands &b : values)
    for (int k = 0; k < kBandCount; ++k)
      if (std::bit_cast<uint64_t>(b[k]) != 0) return false;
  return true;
}

void putSolution(Writer &w, const Solution &s, const Scene &scene) {
  const RadiosityMesh &m = s.mesh;
  const size_t n = m.elements.size();
  for (size_t count :
       {m.patches.size(), n, m.nodes.size(), m.patchOfFace.size(), m.tree.size(), m.tVertices.size(), s.links.size()})
    if (count > UINT32_MAX) throw std::runtime_error("the solution is too large for the solution file's 32-bit counts");
  // What can be derived on reading, checked here bit for bit by deriving it.
  std::vector<CompactPatch> compact = compactPatches(scene, m);
  std::vector<int32_t> firstChild(m.tree.size(), -1);
  bool derivable = compact.size() == m.patches.size();
  for (size_t t = 0; t < m.tree.size() && derivable; ++t) {
    const auto &c = m.tree[t].children;
    if (c[0] >= 0) firstChild[t] = c[0];
    for (int k = 1; k < 4; ++k) derivable = derivable && c[k] == (c[0] < 0 ? -1 : c[0] + k);
  }
  if (derivable) {
    RadiosityMesh derived;
    derivable = deriveMeshGeometry(scene, compact, firstChild, n, m.nodes.size(), derived).empty() &&
                sameMeshGeometry(derived, m);
  }
  std::vector<int32_t> patchOfFace;
  std::vector<uint32_t> facePatchCount;
  deriveFacePatches(m.patchOfFace.size(), m.patches, patchOfFace, facePatchCount);
  const bool facesDerived = patchOfFace == m.patchOfFace && facePatchCount == m.facePatchCount;
  bool materialsDerived = !scene.spectral.enabled() && m.patchOfFace.size() == scene.faces.size();
  std::vector<Bands> reflectance, emission;
  if (materialsDerived) {
    for (const Patch &p : m.patches)
      materialsDerived = materialsDerived && p.material < scene.materials.size() && p.face < scene.faces.size();
    if (materialsDerived) deriveMaterialValues(scene, m, reflectance, emission);
  }
  std::vector<Bands> transmittance(n);
  for (size_t e = 0; e < n; ++e) transmittance[e] = s.transmittanceOf(e);
  uint32_t content = 0;
  if (!derivable) content |= kGeometryStored;
  if (!facesDerived) content |= kFacesStored | (m.facePatchCount.empty() ? 0u : uint32_t(kFacePatchCountsStored));
  if (!materialsDerived || !sameBits(reflectance, s.reflectance)) content |= kReflectanceStored;
  if (!materialsDerived || !sameBits(emission, s.emission)) content |= kEmissionStored;
  if (!allZero(s.unshot)) content |= kUnshotStored;
  if (!allZero(transmittance)) content |= kTransmittanceStored;
  if (s.hasTransmitted()) content |= kTransmittedStored;
  std::vector<uint32_t> pools;
  if (s.hasNodeIrradiance()) {
    content |= kNodeIrradianceStored;
    pools = s.nodePools();
    if (nodeIrradianceIsPooled(s, pools)) content |= kNodeIrradiancePooled;
  }
  if (!m.nodeOnCut.empty()) content |= kNodesOnCutsStored;
  // Adaptive rounds of the other solvers refine trees but keep no B per tree node.
  if (!m.tree.empty() && s.treeRadiosity.size() == m.tree.size()) content |= kTreeRadiosityStored;

  for (size_t count :
       {m.patches.size(), n, m.nodes.size(), m.patchOfFace.size(), m.tree.size(), m.tVertices.size(), s.links.size()})
    w.put(uint32_t(count));
  w.put(content);
  w.put(s.stats.solver);
  w.put(int64_t(s.stats.iterations));
  w.put(s.stats.residual);
  w.put(s.stats.seconds);
  w.put(uint64_t(s.stats.formFactorRays));
  w.put(s.stats.emittedPower);
  w.put(s.stats.absorbedPower);
  w.put(s.stats.escapedPower);
  w.put(s.ambient);
  w.put(s.indirectAmbient);
  if (derivable) {
    for (const CompactPatch &p : compact) {
      w.put(p.face), w.put(uint8_t(p.vertexCount | (p.cornersStored ? kPatchCornersStored : 0)));
      w.put(uint32_t(p.divisionsU)), w.put(uint32_t(p.divisionsV)), w.put(p.treeRoot);
    }
    for (const CompactPatch &p : compact)
      if (p.cornersStored)
        for (int k = 0; k < p.vertexCount; ++k) w.put(p.corners[k]);
    for (int32_t c : firstChild) w.put(c);
  } else {
    for (const Patch &p : m.patches) {
      w.put(p.face), w.put(p.material), w.put(p.object), w.put(uint8_t(p.vertexCount));
      for (const Vec3 &c : p.corners) w.put(c);
      w.put(p.normal), w.put(p.area), w.put(uint32_t(p.divisionsU)), w.put(uint32_t(p.divisionsV)), w.put(p.treeRoot);
      w.put(p.firstElement), w.put(p.elementCount), w.put(p.firstNode), w.put(p.nodeCount);
    }
    for (const Element &e : m.elements) {
      w.put(e.patch), w.put(uint8_t(e.vertexCount));
      for (uint32_t v : e.nodes) w.put(v);
      w.put(e.centre), w.put(e.area);
    }
    for (size_t v = 0; v < m.nodes.size(); ++v) w.put(m.nodes[v]), w.put(m.nodePatch[v]);
    for (const MeshTreeNode &t : m.tree) {
      for (int32_t c : t.children) w.put(c);
      w.put(t.element), w.put(t.patch), w.put(uint8_t(t.vertexCount));
      for (const Vec3 &c : t.corners) w.put(c);
      w.put(t.area);
    }
  }
  if (content & kFacesStored) {
    for (int32_t p : m.patchOfFace) w.put(p);
    for (uint32_t c : m.facePatchCount) w.put(c);
  }
  // Values as f32, one array after another. B is not stored: E + direct + indirect.
  if (content & kReflectanceStored) w.putSingle(s.reflectance);
  if (content & kEmissionStored) w.putSingle(s.emission);
  w.putSingle(s.direct);
  w.putSingle(s.indirect);
  w.putSingle(s.irradiance);
  if (content & kUnshotStored) w.putSingle(s.unshot);
  if (content & kTransmittanceStored) w.putSingle(transmittance);
  if (content & kTransmittedStored) w.putSingle(s.transmittedDirect), w.putSingle(s.transmittedIndirect);
  if (content & kTreeRadiosityStored) w.putSingle(s.treeRadiosity);
  for (const RadiosityMesh::TVertex &t : m.tVertices) w.put(t.node), w.put(t.edgeStart), w.put(t.edgeEnd), w.put(t.t);
  for (const Link &l : s.links) {
    w.put(l.receiver), w.put(l.source), w.put(l.formFactor), w.put(l.visibleFraction);
    w.put(uint8_t(l.visibility)), w.put(l.carriedPower);
  }
  if (content & kNodeIrradiancePooled) {
    const std::vector<uint32_t> heads = poolHeads(pools);
    w.put(uint32_t(heads.size()));
    for (const std::vector<Bands> *values : {&s.nodeDirectIrradiance, &s.nodeIndirectIrradiance})
      for (uint32_t v : heads) w.putSingle((*values)[v]);
  } else if (content & kNodeIrradianceStored) {
    w.putSingle(s.nodeDirectIrradiance), w.putSingle(s.nodeIndirectIrradiance);
  }
  if (content & kNodesOnCutsStored) {
    std::vector<uint32_t> onCut;
    for (size_t v = 0; v < m.nodeOnCut.size(); ++v)
      if (m.nodeOnCut[v]) onCut.push_back(uint32_t(v));
    w.put(uint32_t(onCut.size()));
    for (uint32_t v : onCut) w.put(v);
  }
}

}  // namespace

void writeSolutionPasses(std::span<const Solution> passes, const Scene &scene, const std::string &path) {
  if (int(passes.size()) != (scene.spectral.enabled() ? scene.spectral.passCount() : 1))
    throw std::logic_error("writeSolutionPasses: one solution per spectral pass expected");
  Writer w;
  w.put(kMagic);
  w.put(kSolutionFormatVersion);
  w.put(uint32_t(kBandCount));
  w.put(sceneFingerprint(scene));
  w.put(uint32_t(passes.size()));
  for (const Solution &s : passes) putSolution(w, s, scene);

  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(w.data().data(), std::streamsize(w.data().size()));
    out.close();
    if (!out) throw std::runtime_error("write failed");
  });
}

void writeSolution(const Solution &solution, const Scene &scene, const std::string &path) {
  writeSolutionPasses(std::span<const Solution>(&solution, 1), scene, path);
}

namespace {
Solution getSolution(Reader &r, const Scene &scene);
}  // namespace

std::vector<Solution> readSolutionPasses(const std::string &path, const Scene &scene) {
  Reader r(readInputFile(path, InputLocation{path}, "the solution file"), path);
  if (!r.startsWith(kMagic, sizeof kMagic)) r.fail("not a Radiant solution file (written by `radiant solve -o`)");
  for (size_t i = 0; i < sizeof kMagic; ++i) r.get<char>();
  uint32_t version = r.get<uint32_t>();
  if (version != kSolutionFormatVersion)
    r.fail(fmt::format("solution format version {}; this radiant reads version {} (solve the scene again)", version,
                       kSolutionFormatVersion));
  uint32_t bands = r.get<uint32_t>();
  if (bands != uint32_t(kBandCount))
    r.fail(fmt::format("the solution has {} bands; this build of radiant computes {}", bands, kBandCount));
  if (r.get<uint64_t>() != sceneFingerprint(scene))
    r.fail("the solution was made for another scene (its geometry or materials differ from '" + scene.sourceFile +
           "'); solve this scene again with `radiant solve`");
  const uint32_t expected = scene.spectral.enabled() ? uint32_t(scene.spectral.passCount()) : 1;
  const uint32_t passes = r.get<uint32_t>();
  if (passes != expected)
    r.fail(
        fmt::format("the solution has {} spectral passes; the scene needs {} (solve it again, with the same --colour)",
                    passes, expected));
  std::vector<Solution> solutions;
  for (uint32_t p = 0; p < passes; ++p) solutions.push_back(getSolution(r, scene));
  if (!r.atEnd()) r.fail("unexpected data after the solution");
  return solutions;
}

Solution readSolution(const std::string &path, const Scene &scene) {
  std::vector<Solution> passes = readSolutionPasses(path, scene);
  if (passes.size() != 1) throw InputError(InputLocation{path}, "a spectral solution: read it with its passes");
  return std::move(passes[0]);
}

namespace {

/// One pass's solution, checked so that a corrupt file cannot crash a renderer.
Solution getSolution(Reader &r, const Scene &scene) {
  Solution s;
  RadiosityMesh &m = s.mesh;
  const uint32_t patches = r.get<uint32_t>(), elements = r.get<uint32_t>(), nodes = r.get<uint32_t>(),
                 faces = r.get<uint32_t>(), treeNodes = r.get<uint32_t>(), tVertices = r.get<uint32_t>(),
                 links = r.get<uint32_t>();
  const uint32_t content = r.get<uint32_t>();
  if (content & ~uint32_t(kKnownContent)) r.fail(fmt::format("unknown content flags {:#x} in a pass", content));
  if ((content & kFacePatchCountsStored) && !(content & kFacesStored)) r.fail("face patch counts without their faces");
  const bool geometryStored = content & kGeometryStored;
  s.stats.solver = r.string();
  s.stats.iterations = static_cast<int>(r.get<int64_t>());
  s.stats.residual = r.get<double>();
  s.stats.seconds = r.get<double>();
  s.stats.formFactorRays = r.get<uint64_t>();
  s.stats.emittedPower = r.bands();
  s.stats.absorbedPower = r.bands();
  s.stats.escapedPower = r.bands();
  s.ambient = r.bands();
  if (!s.ambient.isFinite()) r.fail("the ambient term is not finite");
  s.indirectAmbient = r.bands();
  if (faces != scene.faces.size()) r.fail("the solution's face count differs from the scene's");

  std::vector<CompactPatch> compact;
  std::vector<int32_t> firstChild;
  if (!geometryStored) {
    compact.resize(r.count(patches, 4 + 1 + 4 + 4 + 4, "patches"));
    for (CompactPatch &p : compact) {
      p.face = r.get<uint32_t>();
      const uint8_t shape = r.get<uint8_t>();
      p.vertexCount = shape & 7, p.cornersStored = shape & kPatchCornersStored;
      if (shape & ~uint8_t(7 | kPatchCornersStored)) r.fail("a patch's subdivision is inconsistent");
      const uint32_t u = r.get<uint32_t>(), v = r.get<uint32_t>();
      if (u > uint32_t(INT32_MAX) || v > uint32_t(INT32_MAX)) r.fail("a patch's subdivision is inconsistent");
      p.divisionsU = int32_t(u), p.divisionsV = int32_t(v), p.treeRoot = r.get<int32_t>();
    }
    for (CompactPatch &p : compact)
      if (p.cornersStored) {
        if (p.vertexCount < 3 || p.vertexCount > 4) r.fail("a patch's subdivision is inconsistent");
        for (int k = 0; k < p.vertexCount; ++k) p.corners[k] = r.vec3();
        if (!std::all_of(p.corners.begin(), p.corners.end(), [](const Vec3 &c) { return isFinite(c); }))
          r.fail("a patch's corners, normal or area are not finite");
      }
    firstChild.resize(r.count(treeNodes, 4, "tree nodes"));
    for (int32_t &c : firstChild) c = r.get<int32_t>();
  } else {
    m.patches.resize(r.count(patches, 3 * 4 + 1 + 16 * 8 + 3 * 4 + 4 * 4, "patches"));
    for (Patch &p : m.patches) {
      p.face = r.get<uint32_t>(), p.material = r.get<uint32_t>(), p.object = r.get<uint32_t>();
      p.vertexCount = r.get<uint8_t>();
      for (Vec3 &c : p.corners) c = r.vec3();
      p.normal = r.vec3(), p.area = r.get<double>();
      const uint32_t u = r.get<uint32_t>(), v = r.get<uint32_t>();
      if (u > uint32_t(INT32_MAX) || v > uint32_t(INT32_MAX)) r.fail("a patch's subdivision is inconsistent");
      p.divisionsU = int32_t(u), p.divisionsV = int32_t(v), p.treeRoot = r.get<int32_t>();
      p.firstElement = r.get<uint32_t>(), p.elementCount = r.get<uint32_t>();
      p.firstNode = r.get<uint32_t>(), p.nodeCount = r.get<uint32_t>();
    }
    m.elements.resize(r.count(elements, 4 + 1 + 4 * 4 + 4 * 8, "elements"));
    for (Element &e : m.elements) {
      e.patch = r.get<uint32_t>(), e.vertexCount = r.get<uint8_t>();
      for (uint32_t &v : e.nodes) v = r.get<uint32_t>();
      e.centre = r.vec3(), e.area = r.get<double>();
    }
    m.nodes.resize(r.count(nodes, 3 * 8 + 4, "nodes"));
    m.nodePatch.resize(m.nodes.size());
    for (size_t v = 0; v < m.nodes.size(); ++v) m.nodes[v] = r.vec3(), m.nodePatch[v] = r.get<uint32_t>();
    m.tree.resize(r.count(treeNodes, 6 * 4 + 1 + 13 * 8, "tree nodes"));
    for (MeshTreeNode &t : m.tree) {
      for (int32_t &c : t.children) c = r.get<int32_t>();
      t.element = r.get<int32_t>(), t.patch = r.get<uint32_t>(), t.vertexCount = r.get<uint8_t>();
      for (Vec3 &c : t.corners) c = r.vec3();
      t.area = r.get<double>();
    }
  }
  if (content & kFacesStored) {
    m.patchOfFace.resize(r.count(faces, 4, "faces"));
    for (int32_t &p : m.patchOfFace) p = r.get<int32_t>();
    if (content & kFacePatchCountsStored) {
      m.facePatchCount.resize(r.count(faces, 4, "face patch counts"));
      for (uint32_t &c : m.facePatchCount) c = r.get<uint32_t>();
    }
  }
  // Element values: at least direct, indirect and irradiance follow, which bounds the element count.
  r.count(elements, 3 * kBandCount * 4, "element values");
  // Derived nodes are corners of elements, at most four each (a lattice has fewer).
  if (!geometryStored && uint64_t(nodes) > 4 * uint64_t(elements))
    r.fail(fmt::format("the file is truncated or corrupt: it claims {} nodes", nodes));
  if (content & kReflectanceStored) s.reflectance = r.singleBands(elements, "element values");
  if (content & kEmissionStored) s.emission = r.singleBands(elements, "element values");
  s.direct = r.singleBands(elements, "element values");
  s.indirect = r.singleBands(elements, "element values");
  s.irradiance = r.singleBands(elements, "element values");
  s.unshot =
      (content & kUnshotStored) ? r.singleBands(elements, "element values") : std::vector<Bands>(elements, Bands(0.0));
  s.transmittance = (content & kTransmittanceStored) ? r.singleBands(elements, "transmittances")
                                                     : std::vector<Bands>(elements, Bands(0.0));
  for (const Bands &t : s.transmittance)
    if (!t.isFinite() || t.min() < 0 || t.max() >= 1) r.fail("an element's transmittance is not in [0, 1)");
  if (content & kTransmittedStored) {
    s.transmittedDirect = r.singleBands(elements, "transmitted radiosities");
    s.transmittedIndirect = r.singleBands(elements, "transmitted radiosities");
    for (const std::vector<Bands> *v : {&s.transmittedDirect, &s.transmittedIndirect})
      for (const Bands &b : *v)
        if (!b.isFinite() || b.min() < 0) r.fail("an element's transmitted radiosity is negative or not finite");
  }
  if (content & kTreeRadiosityStored) s.treeRadiosity = r.singleBands(treeNodes, "tree radiosities");
  m.tVertices.resize(r.count(tVertices, 4 * 4, "T-vertices"));
  for (RadiosityMesh::TVertex &t : m.tVertices) {
    t.node = r.get<uint32_t>(), t.edgeStart = r.get<uint32_t>(), t.edgeEnd = r.get<uint32_t>();
    t.t = r.get<float>();
    if (!(t.t > 0 && t.t < 1)) r.fail("a T-vertex does not lie inside its edge");
  }
  s.links.resize(r.count(links, 4 * 4 + 1 + 4, "links"));
  for (Link &l : s.links) {
    l.receiver = r.get<uint32_t>(), l.source = r.get<uint32_t>();
    l.formFactor = r.get<float>(), l.visibleFraction = r.get<float>();
    uint8_t visibility = r.get<uint8_t>();
    if (visibility > 2) r.fail("a link's visibility is not none, partial or full");
    l.visibility = static_cast<LinkVisibility>(visibility);
    l.carriedPower = r.get<float>();
  }
  // Pooled: one value per pool, spread over its nodes once the mesh is whole (below).
  const bool pooled = (content & kNodeIrradiancePooled) != 0;
  if (pooled && !(content & kNodeIrradianceStored)) r.fail("pooled node irradiance without node irradiance");
  if (content & kNodeIrradianceStored) {
    const size_t count = pooled ? r.count(r.get<uint32_t>(), 2 * kBandCount * 4, "node irradiances") : nodes;
    if (count > nodes) r.fail("more pools of node irradiance than nodes");
    s.nodeDirectIrradiance = r.singleBands(count, "node irradiances");
    s.nodeIndirectIrradiance = r.singleBands(count, "node irradiances");
    for (const std::vector<Bands> *v : {&s.nodeDirectIrradiance, &s.nodeIndirectIrradiance})
      for (const Bands &b : *v)
        if (!b.isFinite() || b.min() < 0) r.fail("a node's irradiance is negative or not finite");
  }
  if (content & kNodesOnCutsStored) {
    const size_t onCut = r.count(r.get<uint32_t>(), 4, "nodes on cuts");
    m.nodeOnCut.assign(nodes, 0);
    int64_t previous = -1;
    for (size_t i = 0; i < onCut; ++i) {
      const uint32_t v = r.get<uint32_t>();
      if (v >= nodes || int64_t(v) <= previous) r.fail("a node on a cut does not exist or is listed twice");
      m.nodeOnCut[v] = 1, previous = v;
    }
  }

  // What the file does not store: geometry, faces' patches, ρ and E, B.
  if (!geometryStored) {
    const std::string inconsistent = deriveMeshGeometry(scene, compact, firstChild, elements, nodes, m);
    if (!inconsistent.empty()) r.fail(inconsistent);
  }
  if (!(content & kFacesStored)) deriveFacePatches(faces, m.patches, m.patchOfFace, m.facePatchCount);
  if (!(content & kReflectanceStored) || !(content & kEmissionStored)) {
    // The materials are looked up by patch: in a stored geometry those indices come from the file.
    for (const Patch &p : m.patches)
      if (p.material >= scene.materials.size() || p.face >= scene.faces.size())
        r.fail("a patch refers to a material or face that does not exist");
    for (const Element &e : m.elements)
      if (e.patch >= m.patches.size() || e.vertexCount < 3 || e.vertexCount > 4 ||
          std::any_of(e.nodes.begin(), e.nodes.begin() + e.vertexCount, [&](uint32_t v) { return v >= nodes; }))
        r.fail("an element is inconsistent");
    // A texture's mean over an element is taken at its nodes' positions.
    for (const Vec3 &v : m.nodes)
      if (!isFinite(v)) r.fail("a node's position is not finite");
    std::vector<Bands> reflectance, emission;
    deriveMaterialValues(scene, m, reflectance, emission);
    if (!(content & kReflectanceStored)) s.reflectance = std::move(reflectance);
    if (!(content & kEmissionStored)) s.emission = std::move(emission);
  }
  s.radiosity.resize(elements);
  for (size_t e = 0; e < elements; ++e) {
    if (!s.direct[e].isFinite() || !s.indirect[e].isFinite())
      r.fail(fmt::format("element {} has a negative or non-finite value", e));
    // E + direct + indirect; the two parts are rounded apart, so a sum of 0 may come out a hair below.
    s.radiosity[e] = s.emission[e] + s.direct[e] + s.indirect[e];
    for (int k = 0; k < kBandCount; ++k) s.radiosity[e][k] = std::max(0.0, s.radiosity[e][k]);
  }
  const size_t n = elements;

  // Cross-references must stay inside their arrays: a corrupt file must not crash a renderer.
  if (m.patchOfFace.size() != scene.faces.size()) r.fail("the solution's face count differs from the scene's");
  for (int32_t p : m.patchOfFace)
    if (p < -1 || p >= int32_t(m.patches.size())) r.fail("a face refers to a patch that does not exist");
  for (size_t f = 0; f < m.facePatchCount.size(); ++f)
    if (m.patchOfFace[f] >= 0 &&
        (m.facePatchCount[f] < 1 || uint64_t(m.patchOfFace[f]) + m.facePatchCount[f] > m.patches.size()))
      r.fail("a face's patches are inconsistent");
  for (const Patch &p : m.patches)
    if (p.vertexCount < 3 || p.vertexCount > 4 || p.divisionsU < 1 || p.divisionsV < 1 ||
        uint64_t(p.firstElement) + p.elementCount > m.elements.size() ||
        uint64_t(p.firstNode) + p.nodeCount > m.nodes.size() || p.treeRoot < -1 ||
        p.treeRoot >= int32_t(m.tree.size()) ||
        (p.treeRoot < 0 &&
         p.elementCount != uint64_t(p.divisionsU) * uint64_t(p.vertexCount == 4 ? p.divisionsV : p.divisionsU)))
      r.fail("a patch's subdivision is inconsistent");
  // Trees: children inside the array and after their parent (no cycles), leaves name elements,
  // no deeper than a solver subdivides (the renderers' walks assume it, and would name no file).
  std::vector<int> depth(m.tree.size(), 0);
  for (size_t n = 0; n < m.tree.size(); ++n) {
    const MeshTreeNode &t = m.tree[n];
    bool leaf = t.children[0] < 0;
    for (int32_t c : t.children)
      if ((leaf && c >= 0) || (!leaf && (c <= int32_t(n) || c >= int32_t(m.tree.size()))))
        r.fail("the subdivision tree is inconsistent");
    if (!leaf)
      for (int32_t c : t.children) depth[size_t(c)] = std::max(depth[size_t(c)], depth[n] + 1);
    if (depth[n] > kMaxSolutionTreeDepth)
      r.fail(fmt::format("a patch's subdivision tree is deeper than {} levels", kMaxSolutionTreeDepth));
    if (leaf && (t.element < 0 || t.element >= int32_t(m.elements.size())))
      r.fail("a subdivision leaf refers to an element that does not exist");
    if (t.patch >= m.patches.size() || (leaf && m.elements[t.element].patch != t.patch))
      r.fail("a subdivision node refers to another patch's element");
    if (t.vertexCount < 3 || t.vertexCount > 4) r.fail("a subdivision node is inconsistent");
  }
  for (const RadiosityMesh::TVertex &t : m.tVertices)
    if (t.node >= m.nodes.size() || t.edgeStart >= m.nodes.size() || t.edgeEnd >= m.nodes.size())
      r.fail("a T-vertex refers to a node that does not exist");
  for (const Link &l : s.links)
    if (l.receiver >= m.tree.size() || l.source >= m.tree.size()) r.fail("a link refers to a node that does not exist");
  for (uint32_t p : m.nodePatch)
    if (p >= m.patches.size()) r.fail("a node refers to a patch that does not exist");
  // Values a renderer divides by or displays must be finite and physical.
  for (size_t e = 0; e < n; ++e)
    for (const Bands *b : {&s.reflectance[e], &s.emission[e], &s.radiosity[e], &s.irradiance[e]})
      if (!b->isFinite() || b->min() < 0) r.fail(fmt::format("element {} has a negative or non-finite value", e));
  for (const Element &e : m.elements) {
    if (e.patch >= m.patches.size() || e.vertexCount < 3 || e.vertexCount > 4) r.fail("an element is inconsistent");
    for (int k = 0; k < e.vertexCount; ++k)
      if (e.nodes[k] >= m.nodes.size()) r.fail("an element refers to a node that does not exist");
  }
  // Geometry: nodes are pooled by rounding their position (Solution::nodeValues), and
  // hits are located in patches and trees by their corners; a NaN or an infinity there
  // overflowed the rounding (fuzz finding).
  for (const Vec3 &v : m.nodes)
    if (!isFinite(v)) r.fail("a node's position is not finite");
  for (const Patch &p : m.patches)
    if (!isFinite(p.normal) || !std::isfinite(p.area) ||
        !std::all_of(p.corners.begin(), p.corners.end(), [](const Vec3 &c) { return isFinite(c); }))
      r.fail("a patch's corners, normal or area are not finite");
  for (const MeshTreeNode &t : m.tree)
    if (!std::isfinite(t.area) ||
        !std::all_of(t.corners.begin(), t.corners.end(), [](const Vec3 &c) { return isFinite(c); }))
      r.fail("a subdivision node's corners or area are not finite");
  for (const Element &e : m.elements)
    if (!isFinite(e.centre) || !std::isfinite(e.area)) r.fail("an element's centre or area is not finite");
  m.buildPatchLookup();
  m.setShadingNormals(scene);  // not stored: from the scene's vertex normals, as buildMesh; the pools use them
  // One value per pool, in the order of the pools' first nodes (the writer's: same mesh, same pools).
  if (const std::string wrong = pooled ? spreadPooledNodeIrradiance(s) : std::string(); !wrong.empty()) r.fail(wrong);
  // Derived, not stored, and only after the checks above: the node values (ambient included) and
  // the error estimates, as the solver's last step made them (solveRadiosity).
  s.updateNodesAndErrors();
  for (const Bands &b : s.nodeRadiosity)
    if (!b.isFinite()) r.fail("a node radiosity is not finite");
  return s;
}

}  // namespace

}  // namespace radiant
