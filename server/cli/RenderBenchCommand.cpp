// `orthosim bench render`: frames per second while orbiting the phantom's predicted face, each
// frame drawn off-screen, read back and JPEG-encoded (what a streaming server does per frame), at
// coarse and fine resolution; plus the cost of a new deformed skin (positions and normals upload).
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/BenchCommands.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Statistics.hpp"
#include "phantom/PhantomCase.hpp"
#include "render/CaseView.hpp"
#include "render/ClinicalView.hpp"
#include "render/JpegEncoder.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// CPU time of the whole process (all of llvmpipe's threads), in ms: what a frame costs the machine,
// whatever else runs on it.
double cpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

struct Row {
  std::string name;
  int samples;  // multisampling of the row's renderer
  render::RenderOptions options;
};

struct Orbit {
  double fps, renderMs, encodeMs, jpegKb, cpuMsPerFrame;
};

// One turn around the head in `frames` steps; per frame: render + read back, then encode.
Orbit orbitOnce(render::Renderer& renderer, render::Camera camera, const render::RenderOptions& o, int frames) {
  render::JpegEncoder encoder;
  RgbImage image;
  std::vector<unsigned char> jpeg;
  std::vector<double> renderMs, encodeMs;
  double bytes = 0;
  const double cpu0 = cpuMs();
  const auto start = Clock::now();
  for (int f = 0; f < frames; ++f) {
    camera.orbit(360.0 / frames, 0);
    const auto t0 = Clock::now();
    renderer.render(camera, o, image);
    const auto t1 = Clock::now();
    encoder.encode(image, jpeg);
    encodeMs.push_back(ms(t1, Clock::now()));
    renderMs.push_back(ms(t0, t1));
    bytes += double(jpeg.size());
  }
  return {frames / (ms(start, Clock::now()) / 1000.0), median(renderMs), median(encodeMs), bytes / frames / 1024.0,
          (cpuMs() - cpu0) / frames};
}

double updateMs(render::Renderer& renderer, const CaseModel& model, const SimState& state) {
  std::vector<double> t;
  for (int k = 0; k < 5; ++k) {
    const auto t0 = Clock::now();
    render::setCaseState(renderer, model, state);
    t.push_back(ms(t0, Clock::now()));
  }
  return median(t);
}

nlohmann::json benchRow(render::Renderer& renderer, const CaseModel& model, const SimState& state, const Row& row,
                        const RenderBenchOptions& opt) {
  const double update = updateMs(renderer, model, state);
  const render::Camera camera = render::clinicalCamera(render::ClinicalView::Frontal, model.spec.frame,
                                                       renderer.skinPositions(), renderer.viewAspect(row.options));
  orbitOnce(renderer, camera, row.options, 4);  // warm-up: llvmpipe compiles shader variants on first use
  std::vector<double> fps, renderMs, encodeMs, kb, cpu;
  for (int r = 0; r < opt.repeats; ++r) {
    const Orbit o = orbitOnce(renderer, camera, row.options, opt.frames);
    fps.push_back(o.fps), renderMs.push_back(o.renderMs), encodeMs.push_back(o.encodeMs), kb.push_back(o.jpegKb);
    cpu.push_back(o.cpuMsPerFrame);
  }
  std::printf("%-34s %8d %9d %7.1f %9.1f %10.1f %10.1f %8.1f %10.1f %8.1f\n", row.name.c_str(),
              model.tissue.skin.numTriangles(), model.tissue.skin.numVertices(), median(fps), 1000.0 / median(fps),
              median(renderMs), median(encodeMs), median(cpu), update, median(kb));
  std::fflush(stdout);
  return {{"row", row.name},
          {"skin_triangles", model.tissue.skin.numTriangles()},
          {"skin_vertices", model.tissue.skin.numVertices()},
          {"fps_median", median(fps)},
          {"fps", fps},
          {"render_readback_ms_median", median(renderMs)},
          {"jpeg_encode_ms_median", median(encodeMs)},
          {"cpu_ms_per_frame_median", median(cpu)},
          {"skin_update_ms", update},
          {"jpeg_kb_mean", median(kb)}};
}

// The streaming default (no multisampling), the same with 4x multisampling (smoother edges, about
// twice the cost on a CPU), and the heaviest view: colour map, bones and a translucent skin.
std::vector<Row> rowsFor(Resolution res) {
  const std::string name = resolutionName(res);
  render::RenderOptions textured, analysis;
  analysis.colorMap = render::ColorMap::Displacement;
  analysis.showBones = true;
  analysis.skinOpacity = 0.5f;
  return {{name + " textured", 0, textured},
          {name + " textured, 4x MSAA", 4, textured},
          {name + " displacement+bones, 50% skin", 0, analysis}};
}

}  // namespace

int runRenderBench(const RenderBenchOptions& opt) {
  const fs::path work = fs::temp_directory_path() / ("orthosim_render_bench_" + std::to_string(::getpid()));
  const CaseSpec spec = loadCaseFile(writePhantomCase(0, (work / "case").string()));
  const RgbImage texture = render::caseTexture(spec);
  render::Renderer plain(opt.width, opt.height, 0), smooth(opt.width, opt.height, 4);
  std::printf(
      "orthosim bench render: phantom '%s' with its plan solved, %dx%d, %d frames per turn around the head,\n"
      "medians of %d turns; %s\n"
      "fps: frames per second of render + read back + JPEG encode; render_ms: draw and read back;\n"
      "cpu_ms: CPU time of all threads per frame (the machine's cost, whatever else runs);\n"
      "update_ms: a new deformed skin (positions and normals upload, and the fragment poses)\n\n",
      spec.name.c_str(), opt.width, opt.height, opt.frames, opt.repeats, plain.description().c_str());
  std::printf("%-34s %8s %9s %7s %9s %10s %10s %8s %10s %8s\n", "row", "skin_tri", "skin_vert", "fps", "frame_ms",
              "render_ms", "encode_ms", "cpu_ms", "update_ms", "jpeg_kb");
  nlohmann::json rows = nlohmann::json::array();
  for (Resolution res : {Resolution::Coarse, Resolution::Fine}) {
    const CaseModel model = buildCaseModel(spec, res, {(work / "cache").string()});
    Model solver(model.scene);
    const SolveResult result = solveScene(solver);
    if (!result.converged)
      throw std::runtime_error(std::string(resolutionName(res)) + " solve failed: " + result.error);
    render::setCase(plain, model, texture);
    render::setCase(smooth, model, texture);
    for (const Row& row : rowsFor(res)) {
      rows.push_back(benchRow(row.samples > 1 ? smooth : plain, model, result.state, row, opt));
      rows.back()["samples"] = row.samples;
    }
  }
  fs::remove_all(work);
  if (!opt.jsonPath.empty()) std::ofstream(opt.jsonPath) << rows.dump(2) << "\n";
  return 0;
}

void addRenderBench(CLI::App& bench) {
  auto options = std::make_shared<RenderBenchOptions>();
  RenderBenchOptions& o = *options;
  auto* render = bench.add_subcommand("render",
                                      "Time off-screen rendering: orbiting the phantom's predicted face at "
                                      "coarse and fine resolution (render + read back + JPEG encode)");
  render->add_option("--frames", o.frames, "Frames per turn around the head")->check(CLI::Range(4, 3600));
  render->add_option("--width", o.width, "Image width")->check(CLI::Range(16, 8192));
  render->add_option("--height", o.height, "Image height")->check(CLI::Range(16, 8192));
  addRepeatsOption(*render, o.repeats, "Turns around the head (medians reported)");
  addJsonOption(*render, o.jsonPath);
  runWhenChosen(*render, [options] { return runRenderBench(*options); });
}

}  // namespace orthosim::cli
