// Pinhole camera: eye, target, up, vertical field of view.
#pragma once

#include "util/math.h"

namespace radiant {

struct CameraSettings {
  Vec3 eye{0, 0, 0};
  Vec3 target{0, 0, 1};
  Vec3 up{0, 1, 0};
  double verticalFovDegrees = 40.0;
};

/// The angle one pixel subtends at the image centre, radians: its side on the
/// image plane at distance 1, for an image `height` pixels high.
inline double pixelAngle(const CameraSettings &camera, int height) {
  return 2 * std::tan(0.5 * camera.verticalFovDegrees * kPi / 180) / (height > 0 ? height : 1);
}

struct Ray {
  Vec3 origin;
  Vec3 direction;  ///< unit length
};

/// Generates primary rays. Image coordinates: x right, y down, in pixels, with
/// (0,0) the top-left corner of the top-left pixel.
class PinholeCamera {
 public:
  PinholeCamera(const CameraSettings &settings, int width, int height);
  Ray generateRay(double imageX, double imageY) const;

 private:
  Vec3 eye_, forward_, right_, up_;
  double tanHalfFov_ = 0, aspect_ = 1;
  int width_ = 1, height_ = 1;
};

}  // namespace radiant
