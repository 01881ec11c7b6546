// orthosim: soft-tissue prediction for orthognathic surgery planning.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/BenchCommands.hpp"
#include "cli/Commands.hpp"
#include "scene/CaseTissue.hpp"

int main(int argc, char** argv) {
  CLI::App app{"orthosim: soft-tissue simulation for orthognathic surgery planning"};
  app.require_subcommand(1);

  std::string scene, out;
  auto* solve = app.add_subcommand(
      "solve", "Solve a scene or surface-based case (JSON); write deformed nodes, skin and result.json");
  solve->add_option("scene", scene, "Scene or case file (JSON, see docs/scene-format.md)")
      ->required()
      ->check(CLI::ExistingFile);
  solve->add_option("--out", out, "Output folder")->required();
  std::string resolution = "coarse";
  orthosim::cli::SolveOptions solveOptions;
  solveOptions.cacheDir = orthosim::defaultCacheDir();
  bool noCache = false;
  solve->add_option("--resolution", resolution, "Surface cases: coarse (preview) or fine (confirm)")
      ->check(CLI::IsMember({"coarse", "fine"}));
  solve->add_option("--cache", solveOptions.cacheDir, "Folder of built tissue models (default: ~/.cache/orthosim)");
  solve->add_flag("--no-cache", noCache, "Build the tissue model even if it is cached, and do not store it");

  std::string demoOut = "orthosim-demo";
  auto* demo = app.add_subcommand("demo", "Write the built-in demo scene and solve it (no data needed)");
  demo->add_option("--out", demoOut, "Output folder (scene/ and result/ inside)");

  orthosim::cli::BenchCommands bench(app);

  int phantomVariant = 0;
  std::string phantomOut = "phantom";
  auto* phantom = app.add_subcommand("phantom", "Write the built-in phantom head as a surface-based case");
  phantom->add_option("--out", phantomOut, "Output folder")->required();
  phantom->add_option("--variant", phantomVariant, "Morphology variant (see --help of the case: 0 class I, ...)")
      ->check(CLI::Range(0, 100));
  std::string phantomCt;
  double phantomCtSpacing = 0;
  phantom->add_option("--ct", phantomCt,
                      "Also write the phantom as a CT's DICOM series into this folder (to try a scan's import)");
  phantom->add_option("--ct-spacing", phantomCtSpacing, "With --ct: isotropic voxel size in mm (default 0.5 x 0.5 x 1)")
      ->check(CLI::Range(0.3, 3.0));

  std::string renderCase, renderResolution = "coarse";
  orthosim::cli::RenderCommandOptions renderOptions;
  renderOptions.cacheDir = orthosim::defaultCacheDir();
  bool renderNoCache = false;
  auto* render =
      app.add_subcommand("render", "Solve a case's plan and render the predicted face off-screen (PNG or JPEG)");
  render->add_option("case", renderCase, "Surface-based case file (JSON)")->required()->check(CLI::ExistingFile);
  render->add_option("--out", renderOptions.out, "Image file: .png or .jpg")->required();
  render
      ->add_option("--plan", renderOptions.planPath,
                   "Plan file {fragment: {translation_mm, rotation_deg, center_mm}} (or {\"plan\": {...}}) "
                   "instead of the case's plan")
      ->check(CLI::ExistingFile);
  render->add_option(
      "--view", renderOptions.view,
      "frontal, profile (right), profile_left, three_quarter (right), three_quarter_left, worms_eye, birds_eye");
  render->add_option("--width", renderOptions.width, "Image width in pixels")->check(CLI::Range(16, 8192));
  render->add_option("--height", renderOptions.height, "Image height in pixels")->check(CLI::Range(16, 8192));
  render->add_option("--colormap", renderOptions.colorMap,
                     "none (texture), displacement (mm from rest) or difference (vs --reference, else this resolution "
                     "vs the other, mm)");
  render
      ->add_option("--reference", renderOptions.reference,
                   "With --colormap difference: a surface (OBJ, STL, PLY; "
                   "the case's frame, mm) to measure the predicted skin against, e.g. a scan")
      ->check(CLI::ExistingFile);
  render
      ->add_option("--scale-mm", renderOptions.scaleMm,
                   "Colour scale: displacement maximum or difference range "
                   "(default 10 and 3 mm)")
      ->check(CLI::PositiveNumber);
  render->add_option("--resolution", renderResolution, "coarse (preview) or fine (confirm)")
      ->check(CLI::IsMember({"coarse", "fine"}));
  render->add_option("--cache", renderOptions.cacheDir, "Folder of built tissue models (default: ~/.cache/orthosim)");
  render->add_flag("--no-cache", renderNoCache, "Build the tissue model even if it is cached, and do not store it");
  render->add_flag("--bones", renderOptions.bones, "Draw the bone fragments at their planned poses");
  render->add_option("--skin-opacity", renderOptions.skinOpacity, "Below 1: translucent skin over the bones")
      ->check(CLI::Range(0.05, 1.0));
  render->add_flag("--before-after", renderOptions.beforeAfter, "Rest (left) and predicted (right) side by side");

  std::string bandCase, bandResolution = "coarse";
  orthosim::cli::BandCommandOptions bandOptions;
  bandOptions.cacheDir = orthosim::defaultCacheDir();
  bool bandNoCache = false;
  auto* band =
      app.add_subcommand("band",
                         "Prediction band of a case's plan over the model parameters that change the "
                         "answer: envelope surfaces, landmark ranges and sensitivities (docs/prediction-band.md)");
  band->add_option("case", bandCase, "Surface-based case file (JSON)")->required()->check(CLI::ExistingFile);
  band->add_option("--out", bandOptions.outDir, "Output folder")->required();
  band->add_option("--plan", bandOptions.planPath,
                   "Plan file {fragment: {translation_mm, rotation_deg, center_mm}} instead of the case's plan")
      ->check(CLI::ExistingFile);
  band->add_option("--resolution", bandResolution, "coarse (preview) or fine (confirm)")
      ->check(CLI::IsMember({"coarse", "fine"}));
  band->add_option("--range-scale", bandOptions.rangeScale, "Scale of every parameter range about the nominal (0, 2]");
  band->add_flag("--no-corners", bandOptions.noCorners, "Only the one-at-a-time runs (no factorial corners)");
  band->add_option("--cache", bandOptions.cacheDir, "Folder of built tissue models (default: ~/.cache/orthosim)");
  band->add_flag("--no-cache", bandNoCache, "Build the tissue model even if it is cached, and do not store it");

  orthosim::cli::CompareOptions compareOptions;
  auto* compare = app.add_subcommand("compare",
                                     "Error of a predicted skin against a reference surface (signed distance, "
                                     "area within 1-4 mm, face region, soft-tissue landmarks)");
  compare
      ->add_option("predicted", compareOptions.predicted, "Predicted skin (.stl, .obj, .ply), e.g. a solve's skin.obj")
      ->required()
      ->check(CLI::ExistingFile);
  compare
      ->add_option("reference", compareOptions.reference, "Reference surface: a finer solve or a post-operative scan")
      ->required()
      ->check(CLI::ExistingFile);
  auto* compareCase = compare
                          ->add_option("--case", compareOptions.casePath,
                                       "The case (JSON): face region from its frame and landmarks, "
                                       "landmark errors on its rest skin")
                          ->check(CLI::ExistingFile);
  compare
      ->add_option("--rest", compareOptions.restPath,
                   "With --case: the rest skin with the predicted skin's triangles "
                   "(a solve's skin_rest.obj; default: the case's skin)")
      ->check(CLI::ExistingFile)
      ->needs(compareCase);
  compare->add_option("--map", compareOptions.mapPath, "Write the predicted skin coloured by its error (.ply or .obj)");
  compare->add_option("--image", compareOptions.imagePath, "Render the error map of the predicted skin (.png or .jpg)");
  compare->add_option("--view", compareOptions.view,
                      "The image's view: frontal, profile, profile_left, three_quarter, "
                      "three_quarter_left, worms_eye, birds_eye");
  compare->add_option("--range", compareOptions.rangeMm, "Colour range of the map and image, +-mm (default 3)")
      ->check(CLI::Range(0.01, 1000.0));
  compare->add_option("--json", compareOptions.jsonPath, "Also write the figures to this JSON file");

  orthosim::CaseImportInput importInput;
  std::string importOut, importCuts;
  auto* import = app.add_subcommand(
      "import", "Make a case from a patient's segmented surfaces (STL, OBJ, PLY) or label map (NIfTI, NRRD)");
  auto* importSkin = import->add_option("--skin", importInput.skin, "Closed skin (soft-tissue envelope) surface");
  auto* importSkull = import->add_option("--skull", importInput.skull, "Skull with the maxilla (held fixed)");
  auto* importMandible = import->add_option("--mandible", importInput.mandible, "Mandible");
  auto* importLabelMap =
      import->add_option("--label-map", importInput.labelMap,
                         "Instead of --skin, --skull, --mandible: one label map (.nii, .nii.gz, .nrrd, .nhdr)");
  for (auto* surface : {importSkin, importSkull, importMandible}) importLabelMap->excludes(surface);
  auto* importDicom = import->add_option(
      "--dicom", importInput.dicom,
      "Folder of a CT or CBCT DICOM series (or several: choose with --series), segmented automatically");
  for (auto* other : {importSkin, importSkull, importMandible, importLabelMap}) importDicom->excludes(other);
  import->add_option("--series", importInput.dicomSeries, "With --dicom: the SeriesInstanceUID to use")
      ->needs(importDicom);
  double importSkinThreshold = 0, importBoneThreshold = 0;
  std::vector<double> importMandibleSeed, importSkullSeed;
  auto* skinThreshold =
      import->add_option("--skin-threshold", importSkinThreshold,
                         "With --dicom: air/tissue grey value (default -400 HU, or from the histogram)");
  auto* boneThreshold = import->add_option("--bone-threshold", importBoneThreshold,
                                           "With --dicom: bone grey value (default 300 HU, or from the histogram)");
  import->add_option("--mandible-seed", importMandibleSeed, "With --dicom: a point x y z on the mandible (LPS mm)")
      ->expected(3)
      ->needs(importDicom);
  import->add_option("--skull-seed", importSkullSeed, "With --dicom: a point x y z on the skull (LPS mm)")
      ->expected(3)
      ->needs(importDicom);
  import->add_option("--voxel", importInput.segmentation.voxelMm, "With --dicom: working voxel size in mm (default 1)")
      ->check(CLI::Range(0.2, 5.0))
      ->needs(importDicom);
  skinThreshold->needs(importDicom);
  boneThreshold->needs(importDicom);
  import
      ->add_option("--tissue-labels", importInput.tissueLabels,
                   "With --label-map: the soft tissue's label numbers (comma-separated)")
      ->delimiter(',')
      ->needs(importLabelMap);
  import
      ->add_option("--skull-labels", importInput.skullLabels,
                   "With --label-map: the skull's (with the maxilla) label numbers")
      ->delimiter(',')
      ->needs(importLabelMap);
  import->add_option("--mandible-labels", importInput.mandibleLabels, "With --label-map: the mandible's label numbers")
      ->delimiter(',')
      ->needs(importLabelMap);
  import->add_option("--cavity", importInput.cavities, "Closed air cavity inside the skin (repeatable)");
  import
      ->add_option(
          "--oral-cavity", importInput.oralCavity,
          "Without --cavity: auto builds the oral cavity closed lips and teeth in occlusion lack, none does not")
      ->check(CLI::IsMember({"auto", "none"}));
  import->add_option("--texture", importInput.texture, "Image for the skin's texture coordinates");
  import->add_option("--landmarks", importInput.landmarks, "JSON file of landmarks {name: [x, y, z]}");
  import->add_option("--cuts", importCuts, "Osteotomy templates, comma-separated (e.g. le_fort_1,bsso)");
  import->add_option("--units", importInput.units, "Units of the files: auto (mm; refuses metre-sized data), mm, m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  import->add_option("--name", importInput.name, "Name of the case (default: the folder's)");
  importInput.checkOpens = true;
  import->add_flag(
      "!--no-open-check", importInput.checkOpens,
      "Skip building the coarse model before the case is written (it is then checked at its first opening)");
  std::vector<double> importAnterior, importSuperior;
  import->add_option("--anterior", importAnterior, "Anterior direction of the files' axes (default -1 0 0)")
      ->expected(3);
  import->add_option("--superior", importSuperior, "Superior direction (default 0 0 1)")->expected(3);
  import->add_option("--out", importOut, "Case folder to write (must not exist)")->required();

  orthosim::cli::PlanFromFaceOptions faceOptions;
  faceOptions.cacheDir = orthosim::defaultCacheDir();
  std::string faceResolution = "coarse";
  auto* face = app.add_subcommand(
      "plan-from-face",
      "Find the fragment poses that move soft-tissue landmarks where wanted (docs/planning-from-the-face.md)");
  face->add_option("case", faceOptions.casePath, "Surface-based case (JSON)")->required()->check(CLI::ExistingFile);
  face->add_option("--targets", faceOptions.targetsPath,
                   "Targets (JSON): {\"targets\": {landmark: {anterior_mm, ...}}, \"locks\": ...}")
      ->required()
      ->check(CLI::ExistingFile);
  face->add_option("--out", faceOptions.outDir, "Output folder (report.json, plan.json, skin.obj)")->required();
  face->add_option("--resolution", faceResolution, "coarse (default) or fine")
      ->check(CLI::IsMember({"coarse", "fine"}));
  face->add_option("--cache", faceOptions.cacheDir, "Folder of built tissue models (default: ~/.cache/orthosim)");
  face->add_option("--translation-limit", faceOptions.translationLimitMm, "Largest move of a fragment, mm (default 30)")
      ->check(CLI::Range(0.1, 100.0));
  face->add_option("--rotation-limit", faceOptions.rotationLimitDeg, "Largest turn of a fragment, degrees (default 30)")
      ->check(CLI::Range(0.1, 90.0));

  orthosim::cli::ServeOptions serveOptions;
  serveOptions.webDir = ORTHOSIM_WEB_DIR;
  serveOptions.builtinDir = ORTHOSIM_CASES_DIR;
  auto* serve = app.add_subcommand("serve", "Serve the planning API and the browser page over HTTP");
  serve->add_option("--host", serveOptions.host, "Address to bind (default 127.0.0.1: this machine only)");
  serve->add_option("--port", serveOptions.port, "TCP port; 0 picks a free one")->check(CLI::Range(0, 65535));
  serve->add_option("--web", serveOptions.webDir, "Folder of the browser page (default: the source tree's web/)");
  serve->add_option("--data", serveOptions.dataDir,
                    "Folder for built cases, the mesh cache and saved plans (default: $ORTHOSIM_DATA, else "
                    "~/.local/share/orthosim)");
  serve->add_option("--cases", serveOptions.casesDir,
                    "Folder of case folders (DIR/<id>/case.json) to serve besides the phantom");
  serve->add_option("--builtin-cases", serveOptions.builtinDir,
                    "Folder of the shipped cases (default: the source tree's cases/; holds the ArtiSynth face)");
  serve->add_option("--token", serveOptions.token, "Access token required on /api and /ws (default: $ORTHOSIM_TOKEN)");
  serve->add_option("--token-file", serveOptions.tokenFile,
                    "Without --token or $ORTHOSIM_TOKEN: read the token from this file, or write a random one there");
  serve->add_flag("--insecure", serveOptions.insecure,
                  "Allow a --host other than the loopback without a token (anyone who reaches the port can plan)");
  serve->add_option("--allow-origin", serveOptions.allowedOrigins,
                    "Origin (e.g. http://planning.example:8080) whose pages may open the WebSocket; '*' allows any");
  serve->add_option("--allow-host", serveOptions.allowedHosts,
                    "Host name clients may use besides localhost, addresses and this machine's name (\"*\": any)");
  serve->add_option("--fine-workers", serveOptions.fineWorkers, "Fine jobs run at once")->check(CLI::Range(1, 16));
  serve->add_option("--max-sessions", serveOptions.maxSessions, "Planning sessions open at once")
      ->check(CLI::Range(1, 1024));
  serve
      ->add_option("--preview-iterations", serveOptions.previewIterations,
                   "Newton iterations one coarse preview may spend (beyond: refused, the last good preview kept)")
      ->check(CLI::Range(1, 10000));
  serve->add_option("--preview-seconds", serveOptions.previewSeconds, "Seconds one coarse preview may take")
      ->check(CLI::Range(0.1, 3600.0));
  serve
      ->add_option("--unopened-timeout", serveOptions.unopenedTimeoutSeconds,
                   "Seconds a session may stay without opening a case before it is closed")
      ->check(CLI::Range(1, 86400));
  serve->add_flag("!--no-warm-up", serveOptions.warmUp, "Do not build the phantom's coarse model at start");
  serve->add_option("--max-upload-mb", serveOptions.maxUploadMb, "Largest patient upload (POST /api/patients), MiB")
      ->check(CLI::Range(1, 4096));
  serve
      ->add_option("--max-uploads", serveOptions.maxUploads,
                   "Uploads (POST /api/patients, /api/scans) received or imported at once; more get 503")
      ->check(CLI::Range(1, 256));
  serve
      ->add_option("--scan-expiry", serveOptions.scanExpirySeconds,
                   "Seconds a scan staged for import (POST /api/scans) is kept unused before it is removed")
      ->check(CLI::Range(1, 86400));
  serve->add_option("--max-staged-scans", serveOptions.maxStagedScans, "Scans staged for import at once")
      ->check(CLI::Range(1, 64));
  serve->add_option("--redis", serveOptions.redis,
                    "redis://HOST:PORT: fine jobs go to `orthosim worker` processes through Redis Streams "
                    "(default: run them in this process)");
  serve->add_option("--replica", serveOptions.replica,
                    "With --redis: this server's name there, the same after a restart so that its queued jobs "
                    "are found again; one per running server (default: HOST-PORT)");
  serve
      ->add_option("--orphan-grace", serveOptions.orphanGraceSeconds,
                   "With --redis: seconds a fine job whose session is gone waits for a session to resume it")
      ->check(CLI::Range(1, 86400));

  orthosim::cli::WorkerOptions workerOptions;
  workerOptions.builtinDir = ORTHOSIM_CASES_DIR;
  auto* worker = app.add_subcommand(
      "worker",
      "Run fine, band and cohort jobs from Redis Streams (serve --redis, bench cohort --redis) on this machine");
  worker->add_option("--redis", workerOptions.redis, "redis://HOST:PORT, the same as the servers'")->required();
  worker->add_option("--data", workerOptions.dataDir,
                     "The servers' data folder (shared: cases, mesh cache, results; default: $ORTHOSIM_DATA, else "
                     "~/.local/share/orthosim)");
  worker->add_option("--cases", workerOptions.casesDir, "The servers' --cases folder, if they use one");
  worker->add_option("--builtin-cases", workerOptions.builtinDir, "The servers' --builtin-cases folder");
  worker->add_option("--concurrency", workerOptions.concurrency, "Jobs at once")->check(CLI::Range(1, 64));
  worker
      ->add_option("--visibility-timeout", workerOptions.visibilitySeconds,
                   "Seconds after which a job whose worker stopped (died) goes to another worker (default 60)")
      ->check(CLI::Range(0.5, 86400.0));
  worker->add_option("--name", workerOptions.name, "Name of this worker in Redis (default: HOST-PID)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; any usage error is bad input (exit 1), as for a bad scene.
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (*solve) {
      solveOptions.resolution = resolution == "fine" ? orthosim::Resolution::Fine : orthosim::Resolution::Coarse;
      if (noCache) solveOptions.cacheDir.clear();
      return orthosim::cli::runSolve(scene, out, solveOptions);
    }
    if (*demo) return orthosim::cli::runDemo(demoOut);
    if (*face) {
      faceOptions.resolution = faceResolution == "fine" ? orthosim::Resolution::Fine : orthosim::Resolution::Coarse;
      return orthosim::cli::runPlanFromFace(faceOptions);
    }
    if (bench.chosen()) return bench.run();
    if (*phantom) return orthosim::cli::runPhantom(phantomVariant, phantomOut, phantomCt, phantomCtSpacing);
    if (*import) {
      for (std::size_t at = 0; at < importCuts.size();) {
        const std::size_t comma = std::min(importCuts.find(',', at), importCuts.size());
        if (comma > at) importInput.cuts.push_back(importCuts.substr(at, comma - at));
        at = comma + 1;
      }
      if (importAnterior.size() == 3)
        importInput.anterior = Eigen::Vector3d(importAnterior[0], importAnterior[1], importAnterior[2]);
      if (importSuperior.size() == 3)
        importInput.superior = Eigen::Vector3d(importSuperior[0], importSuperior[1], importSuperior[2]);
      if (skinThreshold->count()) importInput.segmentation.skinThreshold = importSkinThreshold;
      if (boneThreshold->count()) importInput.segmentation.boneThreshold = importBoneThreshold;
      if (importMandibleSeed.size() == 3)
        importInput.segmentation.mandibleSeed =
            Eigen::Vector3d(importMandibleSeed[0], importMandibleSeed[1], importMandibleSeed[2]);
      if (importSkullSeed.size() == 3)
        importInput.segmentation.skullSeed =
            Eigen::Vector3d(importSkullSeed[0], importSkullSeed[1], importSkullSeed[2]);
      return orthosim::cli::runImport(importInput, importOut);
    }
    if (*serve) return orthosim::cli::runServe(serveOptions);
    if (*worker) return orthosim::cli::runWorker(workerOptions);
    if (*render) {
      renderOptions.resolution = renderResolution == "fine" ? orthosim::Resolution::Fine : orthosim::Resolution::Coarse;
      if (renderNoCache) renderOptions.cacheDir.clear();
      return orthosim::cli::runRender(renderCase, renderOptions);
    }
    if (*compare) return orthosim::cli::runCompare(compareOptions);
    if (*band) {
      bandOptions.resolution = bandResolution == "fine" ? orthosim::Resolution::Fine : orthosim::Resolution::Coarse;
      if (bandNoCache) bandOptions.cacheDir.clear();
      return orthosim::cli::runBand(bandCase, bandOptions);
    }
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
