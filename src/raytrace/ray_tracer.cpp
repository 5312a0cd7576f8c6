#include "raytrace/ray_tracer.h"

#include <bit>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <stdexcept>
#include <string>
#include <vector>

#include "util/phase.h"

namespace radiant {

static void reportEmbreeError(void *, RTCError code, const char *message) {
  if (code != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + (message ? message : "error"));
}

RayTracer::RayTracer(const Scene &scene) : scene_(scene) {
  Phase phase("building the ray tracer's BVH");
  device_ = rtcNewDevice(nullptr);  // BVH builds run on TBB's workers, like the rest of Radiant
  if (!device_) throw std::runtime_error("Embree: cannot create a device (unsupported CPU?)");
  rtcSetDeviceErrorFunction(device_, reportEmbreeError, nullptr);

  rtcScene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(rtcScene_, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(rtcScene_, RTC_SCENE_FLAG_ROBUST);

  double extent = 0;
  for (const Vec3 &p : scene.positions) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  // Float has 24 bits; 2^-17 of the scene's magnitude is ~100 ulps of it.
  epsilon_ = std::max(1e-9, extent * 7.6e-6);

  geometry_.reserve(scene.triangles.size());
  for (const Triangle &t : scene.triangles) {
    const Vec3 &p0 = scene.positions[t.v[0]];
    geometry_.push_back({p0, scene.positions[t.v[1]] - p0, scene.positions[t.v[2]] - p0, scene.triangleNormal(t),
                         t.material, t.face, t.n[0] >= 0 && t.n[1] >= 0 && t.n[2] >= 0});
  }

  // Back faces stay out of the BVH: each is the same polygon as its front.
  bool anyBack = false;
  for (const Face &f : scene.faces) anyBack = anyBack || f.back;
  if (anyBack) {
    std::vector<BackTriangles> ofFace(scene.faces.size());
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
      BackTriangles &b = ofFace[scene.triangles[t].face];
      if (b.count++ == 0) b.first = t;  // a face's triangles are consecutive (Scene::addFace)
    }
    back_.resize(scene.triangles.size());
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
      const Face &face = scene.faces[scene.triangles[t].face];
      if (face.back)
        continue;
      else
        embreeTriangle_.push_back(t);
      if (face.twin >= 0) back_[t] = ofFace[size_t(face.twin)];
    }
  }
  const size_t primitives = anyBack ? embreeTriangle_.size() : scene.triangles.size();

  if (primitives > 0) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), scene.positions.size()));
    for (size_t i = 0; i < scene.positions.size(); ++i) {
      vertices[3 * i + 0] = static_cast<float>(scene.positions[i].x);
      vertices[3 * i + 1] = static_cast<float>(scene.positions[i].y);
      vertices[3 * i + 2] = static_cast<float>(scene.positions[i].z);
    }
    auto *indices = static_cast<unsigned *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), primitives));
    for (size_t i = 0; i < primitives; ++i)
      for (int j = 0; j < 3; ++j) indices[3 * i + j] = scene.triangles[anyBack ? embreeTriangle_[i] : i].v[j];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(rtcScene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(rtcScene_);
}

RayTracer::~RayTracer() {
  if (rtcScene_) rtcReleaseScene(rtcScene_);
  if (device_) rtcReleaseDevice(device_);
}

/// Fills Embree's ray in three 16-byte blocks (origin+tnear, direction+time,
/// tfar+mask+id+flags). Embree reads them 16 bytes at a time; writing them
/// float by float stalls those reads on store forwarding and cost a third of
/// the wrapper's throughput (bench/ray_throughput).
inline void setEmbreeRay(RTCRay &out, const Ray &ray, double tMax) {
  const float tfar = std::isfinite(tMax) ? static_cast<float>(tMax) : INFINITY;
#if defined(__SSE2__)
  // Convert and store each block as one vector: the compiler would otherwise
  // assemble it with scalar stores, which is exactly what stalls.
  __m128 origin = _mm_movelh_ps(_mm_cvtpd_ps(_mm_setr_pd(ray.origin.x, ray.origin.y)),
                                _mm_cvtpd_ps(_mm_setr_pd(ray.origin.z, 0.0)));
  __m128 direction = _mm_movelh_ps(_mm_cvtpd_ps(_mm_setr_pd(ray.direction.x, ray.direction.y)),
                                   _mm_cvtpd_ps(_mm_setr_pd(ray.direction.z, 0.0)));
  _mm_store_ps(&out.org_x, origin);
  _mm_store_ps(&out.dir_x, direction);
  _mm_store_si128(reinterpret_cast<__m128i *>(&out.tfar), _mm_setr_epi32(std::bit_cast<int>(tfar), -1, 0, 0));
#else
  alignas(16) const float origin[4] = {static_cast<float>(ray.origin.x), static_cast<float>(ray.origin.y),
                                       static_cast<float>(ray.origin.z), 0.0f};
  alignas(16) const float direction[4] = {static_cast<float>(ray.direction.x), static_cast<float>(ray.direction.y),
                                          static_cast<float>(ray.direction.z), 0.0f};
  alignas(16) uint32_t tail[4] = {std::bit_cast<uint32_t>(tfar), 0xFFFFFFFFu, 0, 0};
  std::memcpy(&out.org_x, origin, 16);
  std::memcpy(&out.dir_x, direction, 16);
  std::memcpy(&out.tfar, tail, 16);
#endif
}

inline void setEmbreeRayHit(RTCRayHit &out, const Ray &ray, double tMax) {
  setEmbreeRay(out.ray, ray, tMax);
  out.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  out.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

void RayTracer::resolveHit(const Ray &ray, unsigned primitive, float &u, float &v, uint32_t &triangle) const {
  triangle = embreeTriangle_.empty() ? primitive : embreeTriangle_[primitive];
  if (back_.empty() || back_[triangle].count == 0 || !(dot(ray.direction, geometry_[triangle].normal) > 0)) return;
  // From behind: the back triangle holding the same point (the back's fan may
  // cut the polygon along the other diagonal), in its own barycentrics.
  const TriangleGeometry &g = geometry_[triangle];
  const Vec3 p = g.p0 + g.edge1 * double(u) + g.edge2 * double(v);
  double bestOutside = INFINITY;
  const BackTriangles &b = back_[triangle];
  for (uint32_t t = b.first; t < b.first + b.count; ++t) {
    const TriangleGeometry &h = geometry_[t];
    const Vec3 d = p - h.p0;
    const double a11 = dot(h.edge1, h.edge1), a12 = dot(h.edge1, h.edge2), a22 = dot(h.edge2, h.edge2);
    const double r1 = dot(d, h.edge1), r2 = dot(d, h.edge2), det = a11 * a22 - a12 * a12;
    if (!(det > 0)) continue;
    const double b1 = (a22 * r1 - a12 * r2) / det, b2 = (a11 * r2 - a12 * r1) / det;
    const double outside = std::max({0.0, -b1, -b2, b1 + b2 - 1});
    if (outside < bestOutside) bestOutside = outside, triangle = t, u = float(b1), v = float(b2);
  }
}

void RayTracer::completeHit(const Ray &ray, float tfar, unsigned triangle, float u, float v, Hit &hit,
                            bool interpolateNormal) const {
  const TriangleGeometry &g = geometry_[triangle];
  hit.triangle = triangle;
  hit.b1 = u;
  hit.b2 = v;
  hit.material = g.material;
  hit.face = g.face;
  hit.position = g.p0 + g.edge1 * hit.b1 + g.edge2 * hit.b2;
  double distance = dot(hit.position - ray.origin, ray.direction);
  hit.distance = std::isfinite(distance) ? distance : static_cast<double>(tfar);
  hit.geometricNormal = g.normal;
  hit.shadingNormal = g.normal;
  if (interpolateNormal && g.hasVertexNormals) {
    const Triangle &t = scene_.triangles[triangle];
    double b0 = 1.0 - hit.b1 - hit.b2;
    Vec3 n = normalize(scene_.normals[t.n[0]] * b0 + scene_.normals[t.n[1]] * hit.b1 + scene_.normals[t.n[2]] * hit.b2);
    if (isFinite(n) && length(n) > 0) hit.shadingNormal = dot(n, g.normal) < 0 ? -n : n;
  }
}

bool RayTracer::intersect(const Ray &ray, Hit &hit, double tMax) const {
  return nearestHit(ray, tMax, true, hit);
}

bool RayTracer::intersectPosition(const Ray &ray, Hit &hit) const {
  return nearestHit(ray, INFINITY, false, hit);
}

bool RayTracer::nearestHit(const Ray &ray, double tMax, bool interpolateNormal, Hit &hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  setEmbreeRayHit(rh, ray, tMax);
  rtcIntersect1(rtcScene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  uint32_t triangle;
  resolveHit(ray, rh.hit.primID, rh.hit.u, rh.hit.v, triangle);
  completeHit(ray, rh.ray.tfar, triangle, rh.hit.u, rh.hit.v, hit, interpolateNormal);
  return true;
}

bool RayTracer::occluded(const Ray &ray, double tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  setEmbreeRay(r, ray, tMax);
  rtcOccluded1(rtcScene_, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to −inf on a hit
}

bool RayTracer::seesPoint(const Vec3 &from, const Vec3 &fromNormal, const Vec3 &p) const {
  const Vec3 d = p - from;
  if (!(dot(d, d) > 0)) return true;
  Ray ray = spawnRay(from, fromNormal, normalize(d));
  const Vec3 toPoint = p - ray.origin;
  const double distance = length(toPoint);
  ray.direction = toPoint / distance;
  const double tMax = distance * (1 - 1e-5);
  return tMax <= 0 || !occluded(ray, tMax);
}

bool RayTracer::visible(const Vec3 &from, const Vec3 &fromNormal, const Vec3 &to, const Vec3 &toNormal) const {
  Vec3 d = to - from;
  if (!(dot(d, d) > 0)) return true;
  Ray ray = spawnRay(from, fromNormal, normalize(d));
  Vec3 toTarget = to - ray.origin;
  double distance = length(toTarget);
  ray.direction = toTarget / distance;
  // Stop where the ray is `epsilon` from the target's plane, not `epsilon`
  // along the ray: a grazing shadow ray (a wall point just under a ceiling
  // light) otherwise meets the target's own plane early through float
  // round-off and the light is wrongly found occluded.
  double cosTarget = std::abs(dot(ray.direction, toNormal));
  double tMax = distance - epsilon_ / std::max(cosTarget, 1e-4);
  return tMax <= 0 || !occluded(ray, tMax);
}

void RayTracer::intersectMany(std::span<const Ray> rays, std::span<HitRecord> records) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  constexpr size_t kChunk = 256;
  RTCRayHit batch[kChunk];
  for (size_t start = 0; start < rays.size(); start += kChunk) {
    size_t count = std::min(kChunk, rays.size() - start);
    for (size_t i = 0; i < count; ++i) setEmbreeRayHit(batch[i], rays[start + i], INFINITY);
    rtcIntersect1M(rtcScene_, &context, batch, static_cast<unsigned>(count), sizeof(RTCRayHit));
    for (size_t i = 0; i < count; ++i) {
      RTCRayHit &rh = batch[i];
      HitRecord &r = records[start + i];
      r.triangle = HitRecord::kNone;
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
        resolveHit(rays[start + i], rh.hit.primID, rh.hit.u, rh.hit.v, r.triangle);
      r.distance = rh.ray.tfar;
      r.b1 = rh.hit.u;
      r.b2 = rh.hit.v;
    }
  }
}

void RayTracer::intersectMany(std::span<const Ray> rays, std::span<Hit> hits, std::span<uint8_t> found) const {
  constexpr size_t kChunk = 256;
  HitRecord records[kChunk];
  for (size_t start = 0; start < rays.size(); start += kChunk) {
    size_t count = std::min(kChunk, rays.size() - start);
    intersectMany(rays.subspan(start, count), std::span<HitRecord>(records, count));
    for (size_t i = 0; i < count; ++i) {
      found[start + i] = records[i].found();
      if (found[start + i]) completeHit(rays[start + i], records[i], hits[start + i]);
    }
  }
}

}  // namespace radiant
