#include "render/spectral_film.h"

#include <cmath>
#include <stdexcept>

#include "render/film_image.h"
#include "scene/spectral_scene.h"

namespace radiant {

SpectralImages combineSpectralFilms(const std::vector<Film> &films, const SpectralSettings &spectral,
                                    WhiteBalance balance) {
  if (films.empty() || int(films.size()) != spectral.passCount())
    throw std::logic_error("combineSpectralFilms: one film per pass expected");
  const BandColourMatching matching(spectral.wavelengths);
  const std::vector<Vec3> weights = matching.linearSrgbWeights(balance);
  const int bands = matching.bandCount();
  const int width = films[0].width, height = films[0].height;
  const size_t pixels = films[0].pixelCount();

  SpectralImages out{Image(width, height), Image(width, height)};
  // The spectral channels hold spectral radiance per nm (the scene's values
  // divided by ∫ȳ over the range), so that 683·∫L ȳ dλ is the luminance in cd/m².
  const double perNm =
      1.0 / cieYIntegral(int(std::ceil(spectral.wavelengths.front())), int(std::floor(spectral.wavelengths.back())));
  out.colour.wavelengths = spectral.wavelengths;
  out.colour.spectral.resize(pixels * bands);
  for (size_t p = 0; p < pixels; ++p) {
    Vec3 rgb, spread;  // spread: Σ|w_i|σ_i per channel
    for (int i = 0; i < bands; ++i) {
      const Film &film = films[i / kBandCount];
      const int band = i % kBandCount;
      double value = film.mean(p)[band], sigma = std::sqrt(film.varianceOfMean(p)[band]);
      rgb += weights[i] * value;
      spread += Vec3{std::abs(weights[i].x), std::abs(weights[i].y), std::abs(weights[i].z)} * sigma;
      out.colour.spectral[p * bands + i] = float(value * perNm);
    }
    for (int c = 0; c < 3; ++c) {
      out.colour.rgb[3 * p + c] = float(rgb[c]);
      out.variance.rgb[3 * p + c] = float(spread[c] * spread[c]);
    }
  }
  return out;
}

SpectralImages renderPasses(Scene &scene, int width, int height, WhiteBalance balance,
                            const std::function<void(int pass, Film &film)> &renderPass) {
  if (!scene.spectral.enabled()) {
    Film film(width, height);
    renderPass(0, film);
    return {meanImage(film), varianceImage(film)};
  }
  std::vector<Film> films;
  for (int pass = 0; pass < scene.spectral.passCount(); ++pass) {
    applySpectralPass(scene, pass);
    films.emplace_back(width, height);
    if (passHasEmission(scene, pass)) renderPass(pass, films.back());
  }
  applySpectralColour(scene, balance);
  return combineSpectralFilms(films, scene.spectral, balance);
}

}  // namespace radiant
