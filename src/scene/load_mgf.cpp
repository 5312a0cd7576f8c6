// MGF 2.0 reader: the file, its entities and contexts (docs/scene-format.md#mgf-scenes).
//
// Ward, Shakespeare et al., "The Materials and Geometry Format" (LBNL, 1995;
// version 2.0 adds faces with holes). An MGF file is a list of entities, one
// per line (a line ending in `\` continues on the next); each entity changes a
// context (colour c, material m, vertex v, transform xf, object o) or adds
// geometry with the current ones. Entities are read into memory first, with
// limits checked before anything large is allocated, so that an `xf … -a N`
// array can replay its entities N times. Every error names the file and the
// line its entity starts on.

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>

#include "scene/load_detail.h"
#include "scene/mgf_detail.h"
#include "util/input_file.h"

namespace radiant::detail {
namespace {

namespace fs = std::filesystem;

/// Limits on what a file may ask for, checked before allocating.
constexpr size_t kMaxFaceCorners = 4096;
constexpr size_t kMaxEntityWords = kMaxMgfEntityWords;
constexpr int kMaxIncludeDepth = 16;
constexpr long long kMaxArrayCopies = 1 << 20;  // the product of an xf's -a counts
// Entities run, with arrays and includes replayed: 2²⁴ of a face's four
// entities made 2.4 M triangles in 3.3 s and 450 MB. Vertices made, every
// face's own (dropped repeats too): an entity makes up to 2 M of them (a
// sphere of 1024 slices), so an array of a few of them made 5·10⁹ triangles
// of 10 lines (22 GB before it was killed); 2²³ vertices are about 2.8 M
// faces and 1.7 GB (200 bytes a vertex, its face's share included).
// The fuzzing build (CMakeLists.txt) takes 2¹² and 2¹⁴: inputs at 2¹⁸
// entities took 1–4 s under ASan, 95 % of a campaign's time in 11 % of its
// inputs, and at 2¹⁵ entities and 2¹⁷ vertices still 0.5–2 s (6 % of the
// inputs, a quarter of the time).
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr long long kMaxGeneratedEntities = 1LL << 12;
constexpr size_t kMaxGeneratedVertices = size_t(1) << 14;
constexpr const char *kTooManyEntities =
    "the arrays and includes make more than 2¹² entities (a fuzzing build's limit)";
constexpr const char *kTooManyVertices = "the file makes more than 2¹⁴ vertices (a fuzzing build's limit)";
#else
constexpr long long kMaxGeneratedEntities = 1LL << 24;
constexpr size_t kMaxGeneratedVertices = size_t(1) << 23;
constexpr const char *kTooManyEntities = "the arrays and includes make more than 2²⁴ entities";
constexpr const char *kTooManyVertices = "the file makes more than 2²³ vertices (arrays, includes and primitives)";
#endif

/// A vertex context: its point (and normal) in the coordinates of the file.
using Vertex = MgfPoint;

/// One xf context: its transform, and the state of its arrays.
struct TransformContext {
  Transform local;  ///< of this context alone, for its current array element
  Transform total;  ///< everything above it, then `local`
  std::vector<std::string> arguments;
  std::vector<int> counts, indices;  ///< -a counts and the current element of each
  size_t firstEntity = 0;            ///< where its entities start, to replay them
};

class MgfReader {
 public:
  MgfReader(Scene &scene, const Transform &toWorld, std::string objectName)
      : scene_(scene), toWorld_(toWorld), objectName_(std::move(objectName)) {
    materials_[""] = MgfMaterial{};
    colours_[""] = MgfColour{};
  }

  void readFile(const std::string &path, const InputLocation &from, const Transform &includeTransform, int depth) {
    if (depth > kMaxIncludeDepth)
      throw InputError(from, "includes nested more than 16 deep (does the file include itself?)");
    // A file included again (by an array of includes, or from several places) is read and split once.
    std::shared_ptr<const std::vector<MgfEntity>> &cached = entitiesOfFile_[path];
    if (!cached) cached = std::make_shared<const std::vector<MgfEntity>>(readMgfEntities(path, from));
    const std::shared_ptr<const std::vector<MgfEntity>> held = cached;  // the map may grow while it runs
    const std::vector<MgfEntity> &entities = *held;
    const size_t transformDepth = transforms_.size();
    TransformContext outer;
    outer.total = (transforms_.empty() ? Transform{} : transforms_.back().total) * includeTransform;
    outer.local = includeTransform;
    transforms_.push_back(outer);
    run(path, entities, depth);
    if (transforms_.size() != transformDepth + 1)
      throw InputError({path, entities.empty() ? 0 : entities.back().line, 0, ""},
                       "the file ends inside an xf context (" +
                           std::to_string(transforms_.size() - transformDepth - 1) + " not ended by a bare 'xf')");
    transforms_.pop_back();
  }

  void finish() {
    for (const auto &[keyword, where] : unknown_)
      scene_.warnings.push_back(where + ": unknown MGF entity '" + keyword + "' ignored (and any later ones)");
  }

 private:
  Scene &scene_;
  Transform toWorld_;
  std::string objectName_;
  int luminaires_ = 0;  ///< ies entities read, for their names
  std::map<std::string, Vertex> vertices_;
  std::map<std::string, MgfColour> colours_;
  std::map<std::string, MgfMaterial> materials_;
  std::string currentVertex_, currentColour_, currentMaterial_;
  std::vector<TransformContext> transforms_;
  /// Each file's entities, by the path it was read from: an array of includes replays them, not the file.
  std::map<std::string, std::shared_ptr<const std::vector<MgfEntity>>> entitiesOfFile_;
  std::vector<std::string> objectNames_;
  std::map<std::string, uint32_t> objectIndex_;
  std::map<std::pair<std::string, uint64_t>, uint32_t> materialIndex_;
  /// Per MGF material name: its values when it last made a Radiant material, and that material.
  std::unordered_map<std::string, std::pair<MgfMaterial, uint32_t>> lastMaterialOfName_;
  std::unordered_map<std::string, int> nextSuffix_;  ///< per name: the next NAME#k to try
  MaterialNames materialNames_{scene_.materials};    ///< new names checked without a scan of every name
  LightNames lightNames_{scene_.lights};
  uint64_t materialClock_ = 0;
  std::map<std::string, std::string> unknown_;
  std::set<std::string> warnedEntities_;
  long long entitiesRun_ = 0;
  size_t firstPosition_ = scene_.positions.size();  ///< the scene's vertices before this file's
  std::string path_;
  int line_ = 0;

  InputLocation here() const { return {path_, line_, 0, ""}; }
  [[noreturn]] void fail(const std::string &message) const { throw InputError(here(), message); }

  double number(const std::string &word) const {
    // Decimal numbers only, whatever the locale: hexadecimal, inf and nan are refused.
    bool ok = !word.empty();
    for (char c : word)
      ok = ok &&
           (std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E');
    double value = 0;
    if (ok) {
      // std::from_chars: the "C" locale's grammar without a stream per number (an array replays millions).
      const char *first = word.data(), *last = word.data() + word.size();
      if (*first == '+' && last - first > 1 && first[1] != '-') ++first;
      const auto [end, error] = std::from_chars(first, last, value);
      ok = error == std::errc{} && end == last && std::isfinite(value);
    }
    if (!ok) fail("'" + word + "' is not a number");
    return value;
  }
  long long integer(const std::string &word) const {
    const double v = number(word);
    if (v != std::floor(v) || std::abs(v) > 1e15) fail("'" + word + "' is not an integer");
    return static_cast<long long>(v);
  }
  void expectArguments(const MgfEntity &e, size_t least, size_t most, const char *usage) const {
    const size_t n = e.words.size() - 1;
    if (n < least || n > most)
      fail("'" + e.words[0] + "' takes " + usage + ", got " + std::to_string(n) + " arguments");
  }

  const Vertex &vertex(const std::string &name) const {
    auto it = vertices_.find(name);
    if (it == vertices_.end()) fail("vertex '" + name + "' is not defined");
    return it->second;
  }
  Vec3 inMetres(const Vec3 &p) const { return toWorld_.point(transforms_.back().total.point(p)); }

  /// The three context entities c, m and v share their syntax: `X` (the unnamed
  /// context, reset), `X id` (select), `X id =` (define, reset), `X id = template`.
  template <typename T>
  void context(const MgfEntity &e, std::map<std::string, T> &table, std::string &current, const char *kind) {
    expectArguments(e, 0, 3, "[id [= [template]]]");
    if (e.words.size() == 1) {
      table[""] = T{};
      current = "";
      return;
    }
    const std::string &name = e.words[1];
    if (e.words.size() == 2) {
      if (!table.count(name)) fail(std::string(kind) + " '" + name + "' is not defined");
      current = name;
      return;
    }
    if (e.words[2] != "=") fail("expected '=' after the " + std::string(kind) + " name, got '" + e.words[2] + "'");
    T value{};
    if (e.words.size() == 4) {
      auto it = table.find(e.words[3]);
      if (it == table.end()) fail(std::string(kind) + " '" + e.words[3] + "' (the template) is not defined");
      value = it->second;
    }
    table[name] = value;
    current = name;
  }

  MgfMaterial &material() {
    MgfMaterial &m = materials_[currentMaterial_];
    m.version = ++materialClock_;
    return m;
  }

  uint32_t radiantMaterial() {
    const MgfMaterial &m = materials_[currentMaterial_];
    auto key = std::make_pair(currentMaterial_, m.version);
    auto it = materialIndex_.find(key);
    if (it != materialIndex_.end()) return it->second;
    // Defined again with the same values (an included file that defines its
    // own materials, included 10⁵ times): the Radiant material already made.
    auto last = lastMaterialOfName_.find(currentMaterial_);
    if (last != lastMaterialOfName_.end() && sameMgfValues(last->second.first, m)) {
      materialIndex_[key] = last->second.second;
      return last->second.second;
    }
    // A material changed after faces used it is a new Radiant material, NAME#2, NAME#3, …:
    // each name keeps its next suffix (trying all from 2 each time was quadratic).
    const std::string base = currentMaterial_.empty() ? "mgf-unnamed" : currentMaterial_;
    std::string name = base;
    int &suffix = nextSuffix_.try_emplace(base, 2).first->second;
    while (materialNames_.find(name) >= 0) name = base + "#" + std::to_string(suffix++);
    Material radiant = mgfToMaterial(m, name, here(), scene_.warnings, scene_.spectral.enabled());
    checkMaterial(radiant, here());
    const auto index = static_cast<uint32_t>(scene_.materials.size());
    scene_.materials.push_back(std::move(radiant));
    materialIndex_[key] = index;
    lastMaterialOfName_[currentMaterial_] = {m, index};
    return index;
  }

  uint32_t object() {
    std::string name = objectName_;
    for (const std::string &o : objectNames_) name += "/" + o;
    auto it = objectIndex_.find(name);
    if (it != objectIndex_.end()) return it->second;
    const auto index = static_cast<uint32_t>(scene_.objects.size());
    scene_.objects.push_back(SceneObject{name, path_});
    objectIndex_[name] = index;
    return index;
  }

  MgfTarget target() {
    MgfTarget t{scene_, toWorld_ * transforms_.back().total};
    t.material = radiantMaterial();
    t.object = object();
    return t;
  }

  /// The transform of xf arguments for the given array indices (each -a
  /// segment applied index times, a -i segment its count of times).
  Transform parseTransform(const std::vector<std::string> &args, std::vector<int> *counts,
                           const std::vector<int> &indices) const {
    Transform result, segment;
    int arrayNumber = -1;
    auto closeSegment = [&](long long times) {
      for (long long k = 0; k < times; ++k) result = segment * result;
      segment = Transform{};
    };
    auto repeatOfSegment = [&]() -> long long {
      return arrayNumber < 0 ? 1 : (arrayNumber < int(indices.size()) ? indices[size_t(arrayNumber)] : 0);
    };
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string &a = args[i];
      auto need = [&](size_t n) {
        if (i + n >= args.size()) fail("xf: '" + a + "' needs " + std::to_string(n) + " number(s)");
      };
      if (a == "-t") {
        need(3);
        segment = Transform::translate({number(args[i + 1]), number(args[i + 2]), number(args[i + 3])}) * segment;
        i += 3;
      } else if (a == "-rx" || a == "-ry" || a == "-rz") {
        need(1);
        const Vec3 axis = a == "-rx" ? Vec3{1, 0, 0} : a == "-ry" ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
        segment = Transform::rotate(number(args[++i]), axis) * segment;
      } else if (a == "-s") {
        need(1);
        const double s = number(args[++i]);
        if (!(s > 0)) fail("xf: '-s' needs a scale above 0 (mirror with -mx, -my, -mz)");
        segment = Transform::scale({s, s, s}) * segment;
      } else if (a == "-mx" || a == "-my" || a == "-mz") {
        segment =
            Transform::scale({a == "-mx" ? -1.0 : 1.0, a == "-my" ? -1.0 : 1.0, a == "-mz" ? -1.0 : 1.0}) * segment;
      } else if (a == "-i") {
        need(1);
        const long long n = integer(args[++i]);
        if (n < 0 || n > 1000000) fail("xf: '-i' needs a count from 0 to 10⁶");
        closeSegment(n * repeatOfSegment());
      } else if (a == "-a") {
        need(1);
        const long long n = integer(args[++i]);
        if (n < 1 || n > kMaxArrayCopies) fail("xf: '-a' needs a count from 1 to 1048576");
        closeSegment(repeatOfSegment());
        ++arrayNumber;
        if (counts) counts->push_back(int(n));
      } else {
        fail("xf: unknown argument '" + a + "' (expected -t, -rx, -ry, -rz, -s, -mx, -my, -mz, -i or -a)");
      }
    }
    closeSegment(repeatOfSegment());
    if (counts) {
      long long copies = 1;
      for (int c : *counts) copies *= c;
      if (copies > kMaxArrayCopies) fail("xf: the arrays make more than 1048576 copies");
    }
    return result;
  }

  void run(const std::string &path, const std::vector<MgfEntity> &entities, int depth) {
    for (size_t index = 0; index < entities.size(); ++index) {
      path_ = path;
      line_ = entities[index].line;
      if (++entitiesRun_ > kMaxGeneratedEntities) fail(kTooManyEntities);
      const MgfEntity &e = entities[index];
      const std::string &k = e.words[0];
      if (k == "xf") {
        if (e.words.size() == 1) {
          // End of an xf context; the outermost entry is the file's own.
          if (transforms_.size() <= 1 || transforms_.back().firstEntity == 0)
            fail("'xf' ends a transform context that was not begun in this file");
          TransformContext &t = transforms_.back();
          // Next array element: the last index runs fastest.
          size_t d = t.indices.size();
          while (d > 0) {
            if (++t.indices[d - 1] < t.counts[d - 1]) break;
            t.indices[d - 1] = 0;
            --d;
          }
          if (d > 0) {
            t.local = parseTransform(t.arguments, nullptr, t.indices);
            t.total = transforms_[transforms_.size() - 2].total * t.local;
            index = t.firstEntity - 1;  // the loop's ++ starts the context's first entity again
          } else {
            transforms_.pop_back();
          }
          continue;
        }
        TransformContext t;
        t.arguments.assign(e.words.begin() + 1, e.words.end());
        t.local = parseTransform(t.arguments, &t.counts, {});
        t.indices.assign(t.counts.size(), 0);
        t.local = parseTransform(t.arguments, nullptr, t.indices);
        t.total = transforms_.back().total * t.local;
        t.firstEntity = index + 1;
        transforms_.push_back(std::move(t));
        continue;
      }
      if (k == "i") {
        expectArguments(e, 1, kMaxEntityWords, "a file name and optional xf arguments");
        const std::string included = (fs::path(path).parent_path() / e.words[1]).string();
        std::vector<std::string> args(e.words.begin() + 2, e.words.end());
        std::vector<int> counts;
        parseTransform(args, &counts, {});
        std::vector<int> indices(counts.size(), 0);
        const InputLocation from = here();
        // Every array element includes the file once more.
        for (bool more = true; more;) {
          const Transform t = parseTransform(args, nullptr, indices);
          readFile(included, from, t, depth + 1);
          path_ = path;
          line_ = e.line;
          size_t d = indices.size();
          while (d > 0 && ++indices[d - 1] >= counts[d - 1]) indices[--d] = 0;
          more = d > 0;
        }
        continue;
      }
      entity(e);
      if (scene_.positions.size() - firstPosition_ > kMaxGeneratedVertices) fail(kTooManyVertices);
    }
  }

  void entity(const MgfEntity &e) {
    const std::string &k = e.words[0];
    const size_t n = e.words.size() - 1;
    if (k == "o") {
      if (n == 0) {
        if (objectNames_.empty()) fail("'o' ends an object context, but none was begun");
        objectNames_.pop_back();
      } else {
        expectArguments(e, 1, 1, "a name");
        objectNames_.push_back(e.words[1]);
      }
    } else if (k == "v") {
      context(e, vertices_, currentVertex_, "vertex");
    } else if (k == "p" || k == "n") {
      expectArguments(e, 3, 3, "three numbers");
      Vertex &v = vertices_[currentVertex_];
      const Vec3 value{number(e.words[1]), number(e.words[2]), number(e.words[3])};
      if (k == "p") {
        v.position = value;
      } else {
        v.normal = value;
        v.hasNormal = length(value) > 0;
      }
    } else if (k == "c") {
      context(e, colours_, currentColour_, "colour");
    } else if (k == "cxy") {
      expectArguments(e, 2, 2, "x y");
      colours_[currentColour_] = mgfColourFromChromaticity(number(e.words[1]), number(e.words[2]), here());
      if (colours_[currentColour_].y == 0)
        scene_.warnings.push_back(here().toString() + ": cxy with y = 0 has no luminance: the colour is black");
    } else if (k == "cspec") {
      expectArguments(e, 3, kMaxEntityWords, "λmin λmax and at least one value");
      std::vector<double> values;
      size_t negative = 0;
      for (size_t i = 3; i < e.words.size(); ++i) {
        values.push_back(number(e.words[i]));
        // Measured spectra dip a little below 0 in their noisy ends; MGF's parser keeps them.
        if (values.back() < 0) values.back() = 0, ++negative;
      }
      if (negative)
        scene_.warnings.push_back(here().toString() + ": cspec: " + std::to_string(negative) +
                                  " negative value(s) taken as 0");
      colours_[currentColour_] = mgfColourFromSpectrum(number(e.words[1]), number(e.words[2]), values, here());
    } else if (k == "cct") {
      expectArguments(e, 1, 1, "a temperature in kelvin");
      colours_[currentColour_] = mgfColourFromTemperature(number(e.words[1]), here());
    } else if (k == "cmix") {
      if (n < 2 || n % 2) fail("'cmix' takes pairs of a weight and a colour name");
      std::vector<std::pair<double, MgfColour>> parts;
      for (size_t i = 1; i < e.words.size(); i += 2) {
        auto it = colours_.find(e.words[i + 1]);
        if (it == colours_.end()) fail("colour '" + e.words[i + 1] + "' is not defined");
        parts.emplace_back(number(e.words[i]), it->second);
      }
      colours_[currentColour_] = mgfColourMix(parts, here());
    } else if (k == "m") {
      context(e, materials_, currentMaterial_, "material");
    } else if (k == "sides") {
      expectArguments(e, 1, 1, "1 or 2");
      const long long s = integer(e.words[1]);
      if (s != 1 && s != 2) fail("'sides' is 1 or 2, got " + e.words[1]);
      material().sides = int(s);
    } else if (k == "rd" || k == "td" || k == "ed") {
      expectArguments(e, 1, 1, "one number");
      const double v = number(e.words[1]);
      if (v < 0 || (k != "ed" && v > 1))
        fail("'" + k + "' " + e.words[1] + (k == "ed" ? ": expected ≥ 0" : ": expected 0 … 1"));
      MgfMaterial &m = material();
      (k == "rd" ? m.rd : k == "td" ? m.td : m.ed) = v;
      (k == "rd" ? m.rdColour : k == "td" ? m.tdColour : m.edColour) = colours_[currentColour_];
    } else if (k == "rs" || k == "ts") {
      expectArguments(e, 2, 2, "a reflectance and a roughness");
      const double v = number(e.words[1]), alpha = number(e.words[2]);
      if (v < 0 || v > 1) fail("'" + k + "' " + e.words[1] + ": expected 0 … 1");
      if (alpha < 0) fail("'" + k + "': the roughness " + e.words[2] + " is negative");
      MgfMaterial &m = material();
      (k == "rs" ? m.rs : m.ts) = v;
      (k == "rs" ? m.rsAlpha : m.tsAlpha) = alpha;
      (k == "rs" ? m.rsColour : m.tsColour) = colours_[currentColour_];
    } else if (k == "ir") {
      expectArguments(e, 2, 2, "n_real n_imaginary");
      MgfMaterial &m = material();
      m.iorReal = number(e.words[1]);
      m.iorImaginary = number(e.words[2]);
      if (!(m.iorReal > 0)) fail("'ir': the real index must be above 0");
    } else if (k == "f" || k == "fh") {
      face(e);
    } else if (k == "sph" || k == "cyl" || k == "cone" || k == "ring" || k == "torus" || k == "prism") {
      primitive(e);
    } else if (k == "ies") {
      luminaire(e);
    } else {
      unknown_.emplace(k, here().toString());
    }
  }

  /// `ies FILE [-m MULTIPLIER] [xf arguments]`: an IES luminaire with its
  /// photometric centre at the origin, its nadir along −z and C = 0 along +x
  /// (MGF 2.0), placed by the transform; a point light (docs/luminaires.md).
  void luminaire(const MgfEntity &e) {
    expectArguments(e, 1, kMaxEntityWords, "a file name, then an optional -m multiplier and xf arguments");
    std::vector<std::string> args(e.words.begin() + 2, e.words.end());
    double multiplier = 1;
    if (args.size() >= 2 && args[0] == "-m") {
      multiplier = number(args[1]);
      if (!(multiplier >= 0)) fail("ies: the multiplier after -m must be ≥ 0");
      args.erase(args.begin(), args.begin() + 2);
    }
    std::vector<int> counts;
    parseTransform(args, &counts, {});
    if (!counts.empty()) fail("ies: an array (-a) of luminaires is not read; place each with its own entity");
    const Transform t = toWorld_ * transforms_.back().total * parseTransform(args, nullptr, {});
    PointLight light;
    light.kind = PointLightKind::Photometric;
    light.definedAt = here();
    const std::string file = (fs::path(path_).parent_path() / e.words[1]).string();
    try {
      light.photometry = readIesFile(file);
    } catch (const InputError &error) {
      throw InputError(error.location(), error.message() + " (the luminaire of " + here().toString() + ")");
    }
    light.name = fmt::format("{}ies-{}", objectNames_.empty() ? "" : objectNames_.back() + "/", ++luminaires_);
    if (lightNames_.find(light.name) >= 0) light.name += "@" + here().toString();
    light.position = t.point(Vec3{0, 0, 0});
    if (!withinCoordinateRange(light.position)) fail("the luminaire lies beyond 10⁹ m");
    const Vec3 aim = t.vector(Vec3{0, 0, -1}), c0 = t.vector(Vec3{1, 0, 0});
    if (!(length(aim) > 0) || !(length(cross(aim, c0)) > 0)) fail("ies: the transform collapses the luminaire");
    light.axis = normalize(aim);
    light.c0 = normalize(c0 - light.axis * dot(c0, light.axis));
    light.c90 = normalize(cross(light.c0, light.axis));
    const Vec3 down = normalize(toWorld_.vector(Vec3{0, 0, -1}));
    const double tilt = std::acos(std::clamp(dot(light.axis, down), -1.0, 1.0)) * 180.0 / kPi;
    light.multiplier = multiplier * light.photometry->tiltFactor(tilt);
    if (light.multiplier * light.photometry->maxCandela() > 1e12)
      fail("ies: -m makes the luminaire brighter than 10¹² cd");
    if (scene_.spectral.enabled()) light.spectrum = SampledSpectrum{{550.0}, {1.0}};  // white: a constant spectrum
    scene_.lights.push_back(std::move(light));
  }

  void warnOnce(const std::string &key, const std::string &message) {
    if (warnedEntities_.insert(key).second) scene_.warnings.push_back(here().toString() + ": " + message);
  }

  void face(const MgfEntity &e) {
    if (e.words.size() - 1 < 3) fail("'" + e.words[0] + "' needs at least three vertices");
    if (e.words.size() - 1 > kMaxFaceCorners) fail("a face of more than 4096 vertices");
    std::vector<std::vector<MgfPoint>> contours(1);
    for (size_t i = 1; i < e.words.size(); ++i) {
      if (e.words[i] == "-" && e.words[0] == "fh") {
        contours.emplace_back();
        continue;
      }
      contours.back().push_back(vertex(e.words[i]));
    }
    for (size_t c = 0; c < contours.size(); ++c)
      if (contours[c].size() < 3)
        fail(c == 0 ? "the face's outline needs at least three vertices"
                    : "hole " + std::to_string(c) + " needs at least three vertices");
    for (const auto &contour : contours)
      for (const MgfPoint &p : contour)
        if (!withinCoordinateRange(inMetres(p.position))) fail("a vertex lies beyond 10⁹ m");
    std::vector<std::vector<MgfPoint>> holes(contours.begin() + 1, contours.end());
    mgfAddFace(target(), contours[0], holes, here());
  }

  void primitive(const MgfEntity &e) {
    const std::string &k = e.words[0];
    auto radius = [&](const std::string &word) {
      const double r = number(word);
      if (std::abs(r) > kMaxCoordinateMetres) fail("'" + k + "': radius " + word + " is beyond 10⁹");
      return r;
    };
    auto centreOf = [&](const std::string &name) {
      const Vec3 p = vertex(name).position;
      if (!withinCoordinateRange(inMetres(p))) fail("a vertex lies beyond 10⁹ m");
      return p;
    };
    if (k == "sph") {
      expectArguments(e, 2, 2, "vc radius");
      const double r = radius(e.words[2]);
      if (r == 0) fail("'sph': the radius is 0");
      mgfAddSphere(target(), centreOf(e.words[1]), r);
    } else if (k == "cyl" || k == "cone") {
      const bool cyl = k == "cyl";
      expectArguments(e, cyl ? 3 : 4, cyl ? 3 : 4, cyl ? "v1 radius v2" : "v1 rad1 v2 rad2");
      const double r0 = radius(e.words[2]), r1 = cyl ? r0 : radius(e.words[4]);
      const Vec3 a = centreOf(e.words[1]), b = centreOf(e.words[3]);
      if (length(b - a) == 0) fail("'" + k + "': its two ends are at the same point");
      if (r0 * r1 < 0) fail("'cone': the radii have different signs");
      if (r0 == 0 && r1 == 0) fail("'" + k + "': both radii are 0");
      mgfAddCone(target(), a, r0, b, r1);
    } else if (k == "ring" || k == "torus") {
      expectArguments(e, 3, 3, "vc rmin rmax");
      const Vertex &c = vertex(e.words[1]);
      if (!c.hasNormal) fail("'" + k + "': vertex '" + e.words[1] + "' needs a normal ('n') for the axis");
      const double r0 = radius(e.words[2]), r1 = radius(e.words[3]);
      if (k == "ring") {
        if (!(r0 >= 0 && r1 > r0)) fail("'ring' needs 0 ≤ rmin < rmax");
        mgfAddRing(target(), centreOf(e.words[1]), c.normal, r0, r1);
      } else {
        if (r0 * r1 < 0 || !(std::abs(r1) > std::abs(r0)) || r0 == 0)
          fail("'torus' needs 0 < rmin < rmax (both negative for an inward torus)");
        mgfAddTorus(target(), centreOf(e.words[1]), c.normal, r0, r1);
      }
    } else {  // prism
      if (e.words.size() < 5) fail("'prism' takes v1 v2 v3 … length");
      if (e.words.size() - 2 > kMaxFaceCorners) fail("a prism of more than 4096 vertices");
      std::vector<Vec3> base;
      for (size_t i = 1; i + 1 < e.words.size(); ++i) base.push_back(centreOf(e.words[i]));
      const double length = radius(e.words.back());
      if (length == 0) fail("'prism': the length is 0");
      mgfAddPrism(target(), base, length, here());
    }
  }
};

}  // namespace

void appendMgf(Scene &scene, const std::string &path, const Transform &toWorld, const std::string &objectName,
               const InputLocation &fileFrom) {
  MgfReader reader(scene, toWorld, objectName);
  reader.readFile(path, fileFrom, Transform{}, 0);
  reader.finish();
}

}  // namespace radiant::detail
