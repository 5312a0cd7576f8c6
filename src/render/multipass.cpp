#include "render/multipass.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "cluster/cluster.h"
#include "render/bump_gather.h"
#include "render/caustic_photons.h"
#include "render/control_variate.h"
#include "render/film_image.h"
#include "render/multipass_checkpoint.h"
#include "render/path_tracer.h"
#include "render/registry.h"
#include "render/secondary_sources.h"
#include "util/file_extension.h"
#include "util/interrupt.h"
#include "util/random.h"

namespace radiant {

namespace {

using Clock = std::chrono::steady_clock;

/// Seconds since `start` by rank 0's clock (cluster/cluster.h): with several
/// ranks every decision a budget makes is the same on all, so they render
/// the same passes. A collective: called at the same points on every rank.
double secondsSince(Clock::time_point start) {
  return cluster::fromRoot(std::chrono::duration<double>(Clock::now() - start).count());
}

/// Shots of the progressive solution before the preview: the first image
/// comes within a second on the Cornell box.
constexpr int kPreviewShots = 32;
/// Samples per pixel of the preview (they average the random choices of glass
/// in view), of the high-frequency pass and of the first paired pass.
constexpr int kPreviewSpp = 4, kHighFrequencySpp = 2, kFirstPairedSpp = 2;
/// Paired samples get at least this share of the passes' time whatever the
/// forecast says: D's variance is estimated from the pairs, and a few pairs
/// that missed the rare bright paths (light through the glass sphere seen
/// after a bounce) would otherwise keep the forecast from asking for more.
constexpr double kMinPairedShare = 0.1;
/// Without a time budget the schedule must not depend on measured speed
/// (the image would change from run to run): a control sample is taken to
/// cost this fraction of a paired one (measured 0.5–0.55 on the Cornell boxes).
constexpr double kControlCostRatio = 0.5;
/// Under a time budget, passes 1 and 2 and the solve of the solution the
/// later passes read are overhead: the final image uses none of their samples, and
/// at 2 s on the specular box they took 1.3 s of it (the RMSE of `path` at
/// equal time 2.1×). So, measured against the preview's time t₁: a budget
/// under kOwnSolveBudget·t₁ keeps the preview's solution as the control
/// variate instead of solving again (any fixed solution keeps the blocks' means
/// unbiased; a poorer one only raises D's variance), and pass 2 (the solve
/// and kok with its photon map, 3–4 t₁ on the boxes) runs only when the
/// budget is at least kHighFrequencyBudget·(time spent by then), so that the
/// previews take a few per cent of a budget and not most of it.
constexpr double kOwnSolveBudget = 10, kHighFrequencyBudget = 25;
/// A pass is never planned shorter than this (seconds; samples-per-pixel
/// units without a budget): an image write per pass.
constexpr double kMinPassSeconds = 0.1, kMinPassUnits = 4;

/// SplitMix64 of the seed and a stream: distinct runs never share numbers.
uint64_t hashSeed(uint64_t seed, uint64_t stream) {
  return mixBits(seed * 0x9e3779b97f4a7c15ULL + stream + 0x632be59bd9b4e019ULL);
}

/// The given values that `method`'s table declares: what multipass passes on to the renderer of a pass.
ParameterValues forMethod(const ParameterValues &given, const std::string &method) {
  ParameterValues values;
  for (const ParameterSpec &spec : findRenderer(method).parameters) {
    auto it = given.all().find(spec.name);
    if (it != given.all().end()) values.set(spec.name, it->second.text, it->second.origin);
  }
  return values;
}

}  // namespace

void renderMultipass(const RayTracer &tracer, const PinholeCamera &camera, int width, int height,
                     const MultipassOptions &options, const MultipassSolver &solve, const MultipassOutput &output,
                     const MultipassProgress &progress) {
  // A checkpoint to carry on from (multipass_checkpoint.h): passes 1 and 2
  // are behind it, and its time is the render's so far.
  const bool checkpointing = !options.checkpointPath.empty();
  std::optional<MultipassCheckpoint> resumed;
  if (checkpointing && options.resume && std::filesystem::exists(options.checkpointPath))
    resumed = readMultipassCheckpoint(options.checkpointPath, options.checkpointJob, width, height);
  const Clock::time_point start =
      Clock::now() - std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(resumed ? resumed->elapsedSeconds : 0.0));
  const bool budgeted = options.timeBudgetSeconds > 0;
  // Ctrl-C (util/interrupt.h) ends the passes: the last complete one's image stands.
  // Both collectives on every call, whatever the answer.
  auto spent = [&] {
    const double seconds = secondsSince(start);
    return cluster::anyRank(interruptRequested()) || (budgeted && seconds >= options.timeBudgetSeconds);
  };

  auto driverFor = [&](const MultipassPass &pass, int spp, int chunk) {
    DriverOptions driver;
    driver.samplesPerPixel = spp;
    // Each pass and chunk its own numbers, reproducibly, and no two (seed, pass) alike.
    driver.seed = hashSeed(options.seed, uint64_t(pass.index) << 32 | uint64_t(chunk));
    driver.threads = options.threads;
    return driver;
  };
  auto progressFor = [&](const MultipassPass &pass) {
    return progress ? progress(fmt::format("multipass {} ({})", pass.index, pass.name)) : ProgressCallback{};
  };
  auto finish = [&](MultipassPass &pass, const Film &film, Clock::time_point passStart) {
    pass.seconds = secondsSince(passStart);
    output(pass, meanImage(film), varianceImage(film));
  };

  // Pass 1: the radiosity preview, from an interrupted progressive solution.
  Clock::time_point passStart = Clock::now();
  MultipassPass pass{1, "radiosity preview", kPreviewSpp};
  const Solution preview = resumed && !resumed->previewSolution ? Solution{} : solve(kPreviewShots);
  if (!resumed) {
    RenderContext o = options.context;
    o.solution = &preview;
    Film film(width, height);
    renderImage(camera, *createRenderer("interpolate", tracer, o, forMethod(options.parameters, "interpolate")),
                driverFor(pass, kPreviewSpp, 0), film, progressFor(pass));
    finish(pass, film, passStart);
    if (spent()) return;
  }

  // The solution the later passes read: --solver's, unless the budget is
  // too short to pay for it (kOwnSolveBudget).
  passStart = Clock::now();
  const bool shortBudget = resumed ? resumed->previewSolution
                                   : budgeted && options.timeBudgetSeconds < kOwnSolveBudget * secondsSince(start);
  Solution solved;
  if (!shortBudget) solved = solve(0);
  const Solution &solution = shortBudget ? preview : solved;

  // Pass 2: high frequency — kok (direct light and the brightest reflectors
  // per pixel, the rest of the solution interpolated) with caustics from a
  // photon map. A preview: no later pass uses the map (see passes 3…), so a
  // short budget goes without it (kHighFrequencyBudget).
  if (!resumed &&
      (!budgeted || (!shortBudget && options.timeBudgetSeconds >= kHighFrequencyBudget * secondsSince(start)))) {
    pass = {2, "high frequency", kHighFrequencySpp};
    const CausticPhotonMap caustics(tracer, options.photonsPerPass, hashSeed(options.seed, 0xCA05ULL << 48),
                                    options.photonRadius);
    pass.causticPhotons = caustics.stored(), pass.photonRadius = caustics.radius();
    RenderContext o = options.context;
    o.solution = &solution;
    o.caustics = &caustics;
    ParameterValues kok = forMethod(options.parameters, "kok");
    // A quarter of kok's set-up: no later pass reads this image.
    kok.set("source-visibility-grid", "1", InputLocation::ofParameter("source-visibility-grid"));
    Film film(width, height);
    renderImage(camera, *createRenderer("kok", tracer, o, kok), driverFor(pass, kHighFrequencySpp, 0), film,
                progressFor(pass));
    finish(pass, film, passStart);
  }

  // Passes 3…: path tracing that reads the solution after one non-specular
  // bounce (control samples R), and the same paths continued to their end
  // beside it (paired samples: P and R from the same numbers). The image is
  // R̄ plus the pairs' mean difference over a correction tile
  // (render/control_variate.h): its tiles' sums are the unbiased estimator's,
  // and the tiles shrink towards pixels as pairs accumulate, so the image is
  // consistent; each pass adds the kind of sample that the forecast says
  // lowers its error more per second.
  //
  // Where R reads the solution it also reads a photon map of all light that
  // took a specular bounce on its way (the solution has mirrors and glass
  // black: on the specular box R was 6 % dark without it, 0.1 % with it);
  // P never does (it is `path`, so the image converges to `path`'s). At the
  // first vertex R finds caustics as P does, by BSDF samples: a caustic map
  // there blurred the sharp caustic, which no correction tile could undo.
  ControlVariateImage combined(width, height);
  // One film of each kind, cleared for every pass rather than allocated anew.
  Film pairedFilm(width, height, {"control"}), controlFilm(width, height);
  // Time (or, without a budget, cost units) spent on each kind, and per sample.
  double controlSpent = 0, pairedSpent = 0, controlCost = 0, pairedCost = 0;
  // The samples-per-pixel budget counts paired-sample equivalents: a control costs kControlCostRatio.
  double unitsSpent = 0;
  if (resumed) {
    combined.restore(std::move(resumed->sums));
    unitsSpent = resumed->unitsSpent, controlSpent = resumed->controlSpent, pairedSpent = resumed->pairedSpent;
    controlCost = resumed->controlCost, pairedCost = resumed->pairedCost;
  }
  // The pass in progress saves its film beside the checkpoint, in a file of its own.
  auto passCheckpoint = [&](int index) { return passFilePath(options.checkpointPath, index); };
  int index = resumed ? resumed->pass : 3;
  // R's photon map: none without mirrors or glass, nor after a map that stored nothing.
  const std::vector<Material> &materials = tracer.scene().materials;
  bool tracePhotons = std::any_of(materials.begin(), materials.end(), [](const Material &m) { return m.isDelta(); });
  if (resumed && progress && cluster::isRoot())
    fmt::print(stderr, "radiant: resumed from {} at pass {} ({} spp reading the solution done)\n",
               options.checkpointPath, index, combined.controlSamples());
  for (; !spent(); ++index) {
    const double unitsLeft = options.samplesPerPixel - unitsSpent;
    const bool planned = resumed && index == resumed->pass;  // the stopped pass, as it was planned
    if (unitsLeft < kControlCostRatio && !planned) break;
    // What to render: pairs first (the image needs D̄, and nothing is known of
    // D's variance before), then by the forecast, with a floor on the pairs'
    // share. Each pass's kind and length are fixed before its samples are
    // drawn, from image-wide variances and measured times only, so the
    // schedule does not bias R̄ + D̄ (control_variate.h).
    const double spentSoFar = controlSpent + pairedSpent;
    const double pairCost = budgeted ? pairedCost : 1.0;
    const double controlCostNow =
        budgeted ? (controlCost > 0 ? controlCost : kControlCostRatio * pairedCost) : kControlCostRatio;
    const double minimumLength = budgeted ? kMinPassSeconds : kMinPassUnits;
    double length = std::max(minimumLength, spentSoFar);
    const double left = budgeted ? options.timeBudgetSeconds - secondsSince(start) : unitsLeft;
    if (budgeted && left < 0.5 * minimumLength) break;  // a sliver of a pass would cost an image for nothing
    if (left - length < 0.5 * length) length = left;    // no sliver of a pass at the end
    length = std::min(length, left);
    bool paired = true;
    if (combined.pairedSamples() > 0) {
      const double asControls = combined.forecastMse(length / controlCostNow, 0);
      const double asPairs = combined.forecastMse(0, length / pairCost);
      paired = asPairs <= asControls;
      // The floor on the pairs' share: if a pass of controls would sink
      // below it, first a pass of pairs — twice what is owed, so that the
      // longer control pass planned after it does not owe again at once.
      const double owed = kMinPairedShare * (spentSoFar + length) - pairedSpent;
      if (!paired && owed > 0) paired = true, length = std::min(length, std::max({2 * owed, minimumLength, pairCost}));
    }
    const double sampleCost = paired ? pairCost : controlCostNow;
    int spp = combined.pairedSamples() == 0 ? kFirstPairedSpp : int(length / sampleCost);
    if (spp < 1) {
      if (budgeted && left < 0.5 * sampleCost) break;  // not half a sample per pixel fits in what is left
      spp = 1;
    }
    // --spp caps the work (the loop's condition leaves at least half a unit); a last half unit: controls.
    if (paired && unitsLeft < 1) paired = false;
    spp = std::min(spp, int(unitsLeft / (paired ? 1.0 : kControlCostRatio)));
    if (planned) paired = resumed->paired, spp = resumed->samplesPerPixel;

    passStart = Clock::now();
    pass = {index, paired ? "paired: path samples that correct the solution" : "low frequency, solution after 1 bounce",
            spp};
    DriverOptions driver = driverFor(pass, spp, 0);
    // Passes 3… draw one sequence of samples between them (render/sampler.h):
    // R̄'s samples, from whichever pass, keep the low-discrepancy sequence's
    // even cover (split into passes of fresh seeds they lost it: R̄'s
    // variance at 441 samples on the knots room was 2.3× one sequence's).
    driver.seed = hashSeed(options.seed, 3ULL << 32);
    driver.firstSample = uint64_t(combined.controlSamples());
    if (checkpointing) {
      // The state before this pass, with its plan; then the last pass's film is no longer needed.
      MultipassCheckpoint state;
      state.job = options.checkpointJob;
      state.pass = index, state.paired = paired, state.samplesPerPixel = spp;
      state.previewSolution = shortBudget;
      state.elapsedSeconds = std::chrono::duration<double>(Clock::now() - start).count();
      state.unitsSpent = unitsSpent, state.controlSpent = controlSpent, state.pairedSpent = pairedSpent;
      state.controlCost = controlCost, state.pairedCost = pairedCost;
      if (cluster::isRoot()) {
        writeMultipassCheckpoint(options.checkpointPath, state, combined);
        std::filesystem::remove(passCheckpoint(index - 1));
      }
      driver.checkpointPath = passCheckpoint(index);
      driver.checkpointIntervalSeconds = options.checkpointIntervalSeconds;
      driver.resume = planned;
      driver.checkpointJob = fmt::format("{}multipass pass {}: {} {} spp\n", options.checkpointJob, index,
                                         paired ? "paired" : "controls", spp);
      driver.checkpointWhenDone = true;  // a kill before the next pass's save finds it complete
    }
    {
      // A fresh map each pass, of the same radius, of all light that took a
      // specular bounce: R reads it with the solution at y (P never: it is
      // `path`), and the correction moves R̄'s blur and photon noise back
      // towards P's mean (control_variate.h). None where nothing is specular.
      std::optional<CausticPhotonMap> specularLight;
      if (tracePhotons) {
        specularLight.emplace(tracer, options.photonsPerPass / 4,
                              hashSeed(options.seed, 0x5105ULL << 48 | uint64_t(index)), options.photonRadius, true);
        tracePhotons = specularLight->stored() > 0;
      }
      RenderContext o = options.context;
      o.solution = &solution;
      o.readSolutionDepth = 1;
      if (specularLight && specularLight->stored()) o.specularLastLight = &*specularLight;
      const auto renderer = createRenderer("path", tracer, o, forMethod(options.parameters, "path"));
      Film &film = paired ? pairedFilm : controlFilm;
      film.clear();
      const RenderStats rendered = renderImage(camera, *renderer, driver, film, progressFor(pass));
      if (rendered.interrupted) return;  // the pass's film is in its checkpoint; no image of a part of a pass
      if (paired)
        combined.addPairs(film);
      else
        combined.addControls(film);
    }
    const double seconds = secondsSince(passStart);
    const double units = spp * (paired ? 1.0 : kControlCostRatio);
    unitsSpent += units;
    (paired ? pairedSpent : controlSpent) += budgeted ? seconds : units;
    (paired ? pairedCost : controlCost) = seconds / spp;

    ControlVariateStats stats;
    const Image mean = combined.mean(&stats);
    pass.seconds = seconds;
    pass.unbiased = paired;
    pass.controlSamples = combined.controlSamples();
    pass.pairedSamples = combined.pairedSamples();
    pass.estimatedBias = stats.biasRms;
    output(pass, mean, combined.variance());
  }
  // Finished (not stopped): the checkpoints have served.
  if (checkpointing && !interruptRequested() && cluster::isRoot()) {
    std::filesystem::remove(passCheckpoint(index - 1));
    std::filesystem::remove(passCheckpoint(index));  // a planned pass a budget then left out
    std::filesystem::remove(options.checkpointPath);
  }
}

std::string multipassSolverName(const std::string &requested, double timeBudgetSeconds) {
  return requested == "auto" && timeBudgetSeconds > 0 ? "stochastic" : requested;
}

std::string describePass(const MultipassPass &pass) {
  return fmt::format(
      "multipass {} ({}): {} spp, {:.2f} s{}{}", pass.index, pass.name, pass.samplesPerPixel, pass.seconds,
      pass.causticPhotons
          ? fmt::format(", {} caustic photons within {:.1f} mm", pass.causticPhotons, pass.photonRadius * 1e3)
          : std::string(),
      pass.index >= 3 ? fmt::format("; so far {} spp reading the solution, {} of them paired with the unbiased "
                                    "path, whose difference corrects the solution's bias ({:.3g} W/(sr m²) RMS)",
                                    pass.controlSamples, pass.pairedSamples, pass.estimatedBias)
                      : std::string());
}

namespace {

/// The registry's entry point: the command line's job, run as passes.
void renderMultipassJob(const ImageJob &job, const Parameters &parameters) {
  MultipassOptions options;
  options.timeBudgetSeconds = job.timeBudgetSeconds;
  options.samplesPerPixel = job.samplesPerPixel;
  options.seed = job.seed;
  options.threads = job.threads;
  options.context.pixelSpreadAngle = texturePixelSpread(job.pixelAngle, 4);  // its filtered passes: 4 spp
  options.parameters = parameters.givenValues();
  options.checkpointPath = job.checkpointPath, options.checkpointJob = job.checkpointJob;
  options.checkpointIntervalSeconds = job.checkpointIntervalSeconds, options.resume = job.resume;
  renderMultipass(
      job.tracer, job.camera, job.width, job.height, options, job.solve,
      [&](const MultipassPass &pass, const Image &mean, const Image &variance) {
        job.output(pass.index, describePass(pass), mean, variance);
      },
      job.progress);
}

}  // namespace

RendererInfo multipassMethod() {
  ParameterTable parameters = {maxDepthParameter()};
  for (const ParameterSpec &spec : secondarySourceParameters())
    if (spec.name != "source-visibility-grid") parameters.push_back(spec);  // pass 2 is a preview: 1
  parameters.push_back(bumpOrientationsParameter());
  return {"multipass",
          "progressive passes from a radiosity preview to the path-traced image with caustics (Chen et al. 1991)",
          parameters,
          nullptr,
          &renderMultipassJob,
          true};
}

}  // namespace radiant
