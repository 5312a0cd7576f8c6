#include "scene/camera.h"

namespace radiant {

PinholeCamera::PinholeCamera(const CameraSettings &s, int width, int height)
    : eye_(s.eye), width_(width), height_(height) {
  forward_ = normalize(s.target - s.eye);
  // Right-handed world, camera looking along forward with up: image right is
  // forward × up. For the Cornell camera (forward +z, up +y) that is −x, so the
  // red wall at x ≈ 550 appears on the left, as it must in the published
  // Cornell box (Cornell Box Data; docs/scene-format.md).
  right_ = normalize(cross(forward_, s.up));
  up_ = cross(right_, forward_);
  tanHalfFov_ = std::tan(0.5 * s.verticalFovDegrees * kPi / 180.0);
  aspect_ = static_cast<double>(width) / height;
}

Ray PinholeCamera::generateRay(double imageX, double imageY) const {
  double ndcX = (2.0 * imageX / width_ - 1.0) * tanHalfFov_ * aspect_;
  double ndcY = (1.0 - 2.0 * imageY / height_) * tanHalfFov_;
  return {eye_, normalize(forward_ + right_ * ndcX + up_ * ndcY)};
}

}  // namespace radiant
