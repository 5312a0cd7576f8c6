// Small analytic scenes built in code, for tests that must not depend on the loader.
#pragma once

#include <initializer_list>

#include "scene/scene.h"

namespace radiant::test {

/// The inside of the axis-aligned box [0,size]³: six quads facing inwards.
/// Wall k gets material `wallMaterial[k]` (−x, +x, −y, +y, −z, +z); the
/// materials themselves are appended by the caller.
inline Scene closedBox(double size, const int wallMaterial[6]) {
  Scene s;
  s.objects.push_back({"box", "test"});
  const double a = size;
  // Corners; each face listed counter-clockwise as seen from inside.
  s.positions = {{0, 0, 0}, {a, 0, 0}, {a, a, 0}, {0, a, 0}, {0, 0, a}, {a, 0, a}, {a, a, a}, {0, a, a}};
  const uint32_t faces[6][4] = {
      {0, 3, 7, 4},  // x = 0, normal +x
      {1, 5, 6, 2},  // x = a, normal −x
      {0, 4, 5, 1},  // y = 0, normal +y
      {3, 2, 6, 7},  // y = a, normal −y
      {0, 1, 2, 3},  // z = 0, normal +z
      {4, 7, 6, 5},  // z = a, normal −z
  };
  for (int k = 0; k < 6; ++k) {
    Face f;
    f.vertexCount = 4;
    for (int i = 0; i < 4; ++i) f.vertices[i] = faces[k][i];
    f.material = static_cast<uint32_t>(wallMaterial[k]);
    s.addFace(f);
  }
  return s;
}

/// Quad faces over consecutive positions: quad q is positions 4q … 4q + 3
/// (counter-clockwise seen from its front), with material `materials[q]`.
inline void addQuads(Scene &s, std::initializer_list<uint32_t> materials) {
  uint32_t q = 0;
  for (uint32_t material : materials) {
    Face f;
    f.vertexCount = 4;
    for (uint32_t i = 0; i < 4; ++i) f.vertices[i] = 4 * q + i;
    f.material = material;
    s.addFace(f);
    ++q;
  }
}

/// Appends one quad over four new positions (counter-clockwise seen from its front).
inline void addQuad(Scene &s, std::initializer_list<Vec3> corners, uint32_t material) {
  Face f;
  f.vertexCount = 4;
  f.material = material;
  uint32_t k = 0;
  for (const Vec3 &p : corners) {
    f.vertices[k++] = uint32_t(s.positions.size());
    s.positions.push_back(p);
  }
  s.addFace(f);
}

/// A closed 4 × 2.5 × 3 m room whose walls are `wall` (material 0), lit by an
/// isotropic point source of 1000 cd at (1.3, 1.9, 1.1): all its light is
/// absorbed in the end, so the area-mean irradiance of a room of one
/// reflectance ρ is Φ / (A (1 − ρ)) exactly (the interreflection formula).
inline Scene pointLitRoom(const Material &wall) {
  const int walls[6] = {0, 0, 0, 0, 0, 0};
  Scene scene = closedBox(1.0, walls);
  for (Vec3 &p : scene.positions) p = Vec3{p.x * 4, p.y * 2.5, p.z * 3};
  scene.materials.push_back(wall);
  PointLight light;
  light.name = "bulb";
  light.position = Vec3{1.3, 1.9, 1.1};
  light.candela = 1000;
  scene.lights.push_back(light);
  return scene;
}

/// The furnace: every wall emits `emission` and reflects `reflectance`
/// (closed form: radiance E/(1−ρ) everywhere). Camera at the centre.
inline Scene furnace(double emission, double reflectance) {
  const int walls[6] = {0, 0, 0, 0, 0, 0};
  Scene s = closedBox(1.0, walls);
  Material m;
  m.name = "wall";
  m.diffuse = Bands(reflectance);
  m.emission = Bands(emission);
  s.materials.push_back(m);
  s.camera.eye = {0.5, 0.5, 0.5};
  s.camera.target = {1.0, 0.8, 0.9};
  s.camera.up = {0, 1, 0};
  s.camera.verticalFovDegrees = 90;
  return s;
}

/// The unit cube of docs/two-pass.md (`rushmeier`), ceiling (y = 1) emitting
/// E = 1 with ρ = 0, the other faces ρ = 0.5.
inline Scene unitCubeWithCeilingLight() {
  const int walls[6] = {1, 1, 1, 0, 1, 1};
  Scene s = test::closedBox(1.0, walls);
  Material light, wall;
  light.name = "light";
  light.diffuse = Bands(0.0);
  light.emission = Bands(kInvPi);  // radiance 1/π: exitance E = 1
  wall.name = "wall";
  wall.diffuse = Bands(0.5);
  s.materials = {light, wall};
  s.camera.eye = {0.5, 0.9, 0.5};
  s.camera.target = {0.5, 0.0, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.verticalFovDegrees = 100;
  return s;
}

}  // namespace radiant::test
