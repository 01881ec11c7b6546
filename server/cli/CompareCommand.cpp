// `orthosim compare PREDICTED REFERENCE [--case CASE.json [--rest SKIN]] [--map MAP.ply] [--image MAP.png]
// [--json FILE]`: the error of a predicted skin against a reference surface (the paper's
// section 3).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Comparison.hpp"
#include "io/SurfaceImport.hpp"
#include "render/ClinicalView.hpp"
#include "render/ColorScale.hpp"
#include "render/ImageFile.hpp"
#include "render/Renderer.hpp"
#include "scene/CaseFile.hpp"

namespace orthosim::cli {
namespace {

SurfaceMesh readSurface(const std::string& path, const char* role) {
  try {
    return importSurface(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(role) + " surface: " + e.what());
  }
}

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

void printSummary(const char* label, const ErrorSummary& s) {
  std::cout << label << format(": %.0f mm^2, %.0f vertices", s.area, s.vertices) << "\n"
            << format("  signed distance: mean %.3f mm; |d|: mean %.3f, 95th percentile %.3f, max %.3f mm\n",
                      s.meanSigned, s.meanAbs, s.p95Abs, s.maxAbs)
            << "  area within:";
  for (size_t k = 0; k < s.thresholds.size(); ++k)
    std::cout << format("  %g mm %.1f%%", s.thresholds[k], 100.0 * s.shareWithin[k]);
  std::cout << "\n";
}

void printLandmarks(const std::vector<LandmarkError>& lms) {
  if (lms.empty()) return;
  std::cout << "soft-tissue landmarks (error = predicted - reference, mm):\n"
            << "  landmark            error  anterior  superior     right\n";
  for (const LandmarkError& e : lms) {
    std::printf("  %-18s", e.name.c_str());
    if (e.status == LandmarkStatus::Measured)
      std::cout << format("%6.2f  %8.2f  %8.2f  %8.2f", e.error.norm(), e.errorInFrame.x(), e.errorInFrame.y(),
                          e.errorInFrame.z())
                << (e.referenceCorresponds ? "" : "  (reference: closest point)") << "\n";
    else
      std::cout << (e.status == LandmarkStatus::Missing ? "missing: " : "not measured: ") << e.note << "\n";
  }
}

// Vertex colours of the error map: the renderer's difference scale (blue inside, white 0, red
// outside the reference, held beyond +-range); grey outside the region of interest.
Eigen::Matrix3Xf mapColours(const Comparison& c, double rangeMm) {
  const render::ColorScale scale = render::differenceScale(rangeMm);
  Eigen::Matrix3Xf out(3, c.error.distance.size());
  for (Eigen::Index i = 0; i < out.cols(); ++i)
    out.col(i) = !c.inRegion.empty() && !c.inRegion[i] ? render::kNoValueColor : scale.colorAt(c.error.distance[i]);
  return out;
}

// The predicted skin coloured by its signed error on the renderer's difference scale, with its
// legend; grey outside the region of interest, as in the map file.
void renderErrorImage(const SurfaceMesh& predicted, const Comparison& c, const AnatomicalFrame& frame,
                      const CompareOptions& o) {
  render::Renderer renderer(800, 600);
  renderer.setSkin(predicted);
  renderer.setSkinValues(c.error.distance, c.inRegion);
  render::RenderOptions options;
  options.colorMap = render::ColorMap::Difference;
  options.differenceRangeMm = o.rangeMm;
  const render::Camera camera = render::clinicalCamera(render::parseClinicalView(o.view), frame, predicted.vertices,
                                                       renderer.viewAspect(options));
  render::writeImage(renderer.render(camera, options), o.imagePath);
}

}  // namespace

int runCompare(const CompareOptions& o) {
  try {
    const SurfaceMesh predicted = readSurface(o.predicted, "predicted");
    const SurfaceMesh reference = readSurface(o.reference, "reference");
    std::optional<CaseSpec> spec;
    std::optional<SurfaceMesh> rest;
    ComparisonInput in;
    in.predicted = &predicted;
    in.reference = &reference;
    if (!o.casePath.empty()) {
      spec = loadCaseFile(o.casePath);
      if (o.restPath.empty() && !spec->skin.empty()) rest = readSurface(spec->skin, "case skin");
      in.landmarks = &spec->landmarks;
      in.frame = spec->frame;
    }
    if (!o.restPath.empty()) rest = readSurface(o.restPath, "rest");
    in.restSkin = rest ? &*rest : nullptr;
    const Comparison c = compareSurfaces(in);

    std::cout << "predicted " << o.predicted << " (" << predicted.numVertices() << " vertices) against reference "
              << o.reference << " (" << reference.numVertices()
              << " vertices); signed distance, negative inside the reference\n";
    printSummary("whole surface", c.whole);
    std::cout << "region of interest: " << c.regionNote << "\n";
    if (c.hasRegion) printSummary("region of interest", c.region);
    printLandmarks(c.landmarks);

    if (!o.mapPath.empty()) {
      exportSurface(predicted, mapColours(c, o.rangeMm), o.mapPath);
      std::cout << "error map written to " << o.mapPath
                << format(" (blue -%g mm, white 0, red +%g mm", o.rangeMm, o.rangeMm)
                << (c.hasRegion ? "; grey outside the region of interest)" : ")") << "\n";
    }
    if (!o.imagePath.empty()) {
      renderErrorImage(predicted, c, in.frame, o);
      std::cout << "error image (" << o.view << " view" << (c.hasRegion ? ", grey outside the region of interest" : "")
                << ") written to " << o.imagePath << "\n";
    }
    if (!o.jsonPath.empty()) {
      std::ofstream out(o.jsonPath);
      out << comparisonJson(c).dump(2) << "\n";
      if (!out) throw std::runtime_error(o.jsonPath + ": cannot write the file");
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim compare: " << e.what() << "\n";
    return 1;
  }
}

void addCompareCommand(CLI::App& parent) {
  auto options = std::make_shared<CompareOptions>();
  CompareOptions& o = *options;
  auto* compare = parent.add_subcommand("compare",
                                        "Error of a predicted skin against a reference surface (signed distance, "
                                        "area within 1-4 mm, face region, soft-tissue landmarks)");
  compare->add_option("predicted", o.predicted, "Predicted skin (.stl, .obj, .ply), e.g. a solve's skin.obj")
      ->required()
      ->check(CLI::ExistingFile);
  compare->add_option("reference", o.reference, "Reference surface: a finer solve or a post-operative scan")
      ->required()
      ->check(CLI::ExistingFile);
  auto* casePath = compare
                       ->add_option("--case", o.casePath,
                                    "The case (JSON): face region from its frame and landmarks, "
                                    "landmark errors on its rest skin")
                       ->check(CLI::ExistingFile);
  compare
      ->add_option("--rest", o.restPath,
                   "With --case: the rest skin with the predicted skin's triangles "
                   "(a solve's skin_rest.obj; default: the case's skin)")
      ->check(CLI::ExistingFile)
      ->needs(casePath);
  compare->add_option("--map", o.mapPath, "Write the predicted skin coloured by its error (.ply or .obj)");
  compare->add_option("--image", o.imagePath, "Render the error map of the predicted skin (.png or .jpg)");
  compare->add_option("--view", o.view,
                      "The image's view: frontal, profile, profile_left, three_quarter, "
                      "three_quarter_left, worms_eye, birds_eye");
  compare->add_option("--range", o.rangeMm, "Colour range of the map and image, +-mm (default 3)")
      ->check(CLI::Range(0.01, 1000.0));
  addJsonOption(*compare, o.jsonPath);
  runWhenChosen(*compare, [options] { return runCompare(*options); });
}

}  // namespace orthosim::cli
