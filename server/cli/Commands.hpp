#pragma once
// Sub-commands of the `orthosim` executable.
#include <string>
#include <vector>

#include <filesystem>
#include "cases/CaseCatalog.hpp"
#include "cases/ModelCache.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseImport.hpp"

namespace orthosim::cli {

struct SolveOptions {
  Resolution resolution = Resolution::Coarse;  // surface-based cases
  std::string cacheDir;                        // built tissue cache; empty: none
};

// Solves an explicit scene or a surface-based case. Exit codes: 0 converged, 1 bad input, 2 solve
// did not converge (outputs hold the last good state).
int runSolve(const std::string& scenePath, const std::string& outDir, const SolveOptions& options = {});

// Writes the built-in demo scene under outDir/scene and solves it into outDir/result.
int runDemo(const std::string& outDir);

struct BenchOptions {
  std::vector<int> tetCounts{2000, 20000, 100000};
  int repeats = 5;
  std::string jsonPath;  // optional machine-readable copy of the table
};
int runBench(const BenchOptions& options);

struct ScanBenchOptions {
  std::vector<int> size = {512, 512, 300};  // the phantom CT's voxels
  int repeats = 3;
  std::string jsonPath;
};
int runScanBench(const ScanBenchOptions& options);

struct CaseBenchOptions {
  std::string casePath;  // empty: the phantom
  int phantomVariant = 0;
  int repeats = 3;
  std::string jsonPath;
  std::string planPath;  // JSON object {fragment: motion} replacing the case's plan; empty: keep it
};
int runCaseBench(const CaseBenchOptions& options);

struct LatencyBenchOptions {
  int changes = 50;
  double stepMm = 0.2;  // of each pose change
  int phantomVariant = 0;
  std::string dataDir = "orthosim-bench-data";  // built phantom and mesh cache (reused between runs)
  std::string webDir;
  std::string jsonPath;
};
// Round-trip latency of coarse previews through the planning server (bench latency).
int runLatencyBench(const LatencyBenchOptions& options);

struct SessionsBenchOptions {
  std::vector<int> counts = {1, 4, 16};  // sessions open when the memory is read (increasing)
  int phantomVariant = 0;
  std::string dataDir = "orthosim-bench-data";
  std::string webDir;
  std::string jsonPath;
  std::vector<int> dragSessions;  // --drag: sessions dragging at once, one round each; empty: the memory bench
  int backgroundLoad = 0;         // spinning processes beside the server during a drag round
  double dragSeconds = 6, poseRate = 20;
};
// Resident memory with 1, 4, 16 sessions on one case, and the open time (bench sessions).
int runSessionsBench(const SessionsBenchOptions& options);
// Sessions dragging a fragment at once (bench sessions --drag): frames/s, pose-to-frame time,
// release to converged preview, per session.
int runSessionsDragBench(const SessionsBenchOptions& options);

struct RenderCommandOptions {
  std::string planPath;          // plan file replacing the case's plan; empty: the case's plan
  std::string view = "profile";  // a clinical view (render/ClinicalView.hpp)
  std::string out;               // .png or .jpg
  int width = 800, height = 600;
  std::string colorMap = "none";  // none, displacement, difference (vs `reference`, else coarse vs fine)
  std::string reference;          // surface file (OBJ, STL, PLY) the difference map measures against
  Resolution resolution = Resolution::Coarse;
  std::string cacheDir;  // built tissue cache; empty: none
  bool bones = false;
  double skinOpacity = 1.0;  // < 1 also shows the bones
  bool beforeAfter = false;
  double scaleMm = 0;  // colour scale: displacement max or difference range; 0: default
};
// Renders a case's predicted face for a plan into an image file. Exit codes as for solve: 0, 1 bad
// input (also no EGL), 2 the solve did not converge (the image shows the last converged state).
int runRender(const std::string& casePath, const RenderCommandOptions& options);

struct RenderBenchOptions {
  int repeats = 3;  // turns around the head; medians reported
  int frames = 60;  // frames per turn
  int width = 800, height = 600;
  std::string jsonPath;
};
// `orthosim bench render`: frames per second of render + read back + JPEG encode while orbiting
// the phantom's predicted face, coarse and fine, without and with 4x multisampling.
int runRenderBench(const RenderBenchOptions& options);

struct CohortBenchOptions {
  int patients = -1;                    // the first N of the cohort (engine/eval/Cohort); -1: all
  std::vector<std::string> patientIds;  // instead: these patients (M1..M12)
  int coarseTriangles = 3000;           // skin triangles (the case defaults)
  int fineTriangles = 20000;
  int referenceTriangles = 60000;         // the discretisation reference: 3x fine
  double referenceToleranceScale = 1e-2;  // of the default tolerances (1e-4 E h^2, 1e-4 h)
  int sweepPatients = 1;                  // patients also solved over more resolutions and tolerances (the plot)
  int repeats = 3;                        // solves per run; medians reported
  bool noContact = false;                 // drop the case's lips-teeth contact (quick checks only)
  std::string facePath;                   // the ArtiSynth face folder: its ratios too; empty: not measured
  std::string jsonPath, imagePath;
  std::string dataDir;  // cohort cases and tissue cache (kept); empty: a temporary folder
  // The runs as jobs on Redis (cli/CohortOnRedis), solved by `orthosim worker` processes that share
  // dataDir; with spawnWorkers, by that many local workers per round (e.g. 1, 2, 4), timed.
  std::string redis;
  std::vector<int> spawnWorkers;
  int spawnRepeats = 1;     // rounds per count, interleaved; medians reported
  bool pinWorkers = false;  // each spawned worker on one core of this machine (one-core machines' stand-in)
};
// `orthosim bench cohort`: the paper's Table 4 on the synthetic cohort, the speed-versus-error
// plot, the soft-to-hard movement ratios. 0 when every patient is measured, 1 on bad input, 2 when
// a patient could not be (its row says why; the others are still measured and written).
int runCohortBench(const CohortBenchOptions& options);

struct BandCommandOptions {
  std::string planPath;  // plan file replacing the case's plan; empty: the case's plan
  Resolution resolution = Resolution::Coarse;
  std::string cacheDir;  // built tissue cache; empty: none
  std::string outDir;
  double rangeScale = 1.0;  // of the parameter ranges (eval/ParameterDesign)
  bool noCorners = false;   // one-at-a-time runs only
};
// The prediction band of a case's plan: envelope_low.ply, envelope_high.ply, nominal.ply and
// band.json in outDir. 0 when every run converged, 1 on bad input, 2 when the nominal failed (no
// band) or a variant did not converge (named; the band is written without it).
int runBand(const std::string& casePath, const BandCommandOptions& options);

struct BandCohortBenchOptions {
  int patients = -1;                    // the first N of the cohort; -1: all
  std::vector<std::string> patientIds;  // instead: these patients
  bool corners = false;                 // also the corners (only the one-at-a-time runs give the table)
  std::string jsonPath;
  std::string dataDir;  // cohort cases and tissue cache (kept); empty: a temporary folder
};
// `orthosim bench band-cohort`: each cohort patient's band at coarse resolution, and the median
// over the patients of each parameter's effect on each soft-tissue landmark (the sensitivity
// table). 0 when every patient's band was made, 1 on bad input, 2 when one could not be.
int runBandCohortBench(const BandCohortBenchOptions& options);
struct FaceBenchOptions {
  int patients = 1000;  // the first N cohort patients
  int repeats = 3;      // fits per patient (median time reported)
  std::string dataDir;  // cohort cases and tissue cache (kept); empty: a temporary folder
  std::string jsonPath;
};
// `orthosim bench face`: planning from the face from rest to each cohort plan's predicted
// landmarks. 0 when every patient is measured, 2 when one could not be.
int runFaceBench(const FaceBenchOptions& options);

// Writes the built-in phantom head (variant N) as a surface-based case under outDir.
// With `ctDir`: also the phantom as a CT's DICOM series there (phantom/PhantomCt.hpp), voxels of
// `ctSpacing` mm (0: a head CT's 0.5 x 0.5 x 1).
int runPhantom(int variant, const std::string& outDir, const std::string& ctDir = "", double ctSpacing = 0);

// Writes the imported case; 0 when written, 1 with the file and defect named on stderr otherwise.
int runImport(const CaseImportInput& input, const std::string& outDir);

struct CompareOptions {
  std::string predicted;         // surface file (.stl, .obj, .ply): the predicted skin
  std::string reference;         // surface file: a finer solve, or a post-operative scan
  std::string casePath;          // optional case: region of interest, landmarks (and its skin as the rest skin)
  std::string restPath;          // optional rest skin with the predicted skin's triangles (a solve's skin_rest.obj)
  std::string mapPath;           // optional coloured error map (.ply or .obj with vertex colours)
  std::string imagePath;         // optional rendered error map (.png or .jpg, engine/render)
  std::string view = "frontal";  // its clinical view (render/ClinicalView.hpp)
  std::string jsonPath;          // optional machine-readable copy of the figures
  double rangeMm = 3.0;          // the map's colour range, +-mm
};
// Prints the surface error (whole skin and face region) and the soft-tissue landmark errors;
// 0 when measured, 1 on bad input (missing or unreadable file, empty mesh, bad case).
int runCompare(const CompareOptions& options);

struct PlanFromFaceOptions {
  std::string casePath, targetsPath, outDir;
  Resolution resolution = Resolution::Coarse;
  std::string cacheDir;  // built tissue cache; empty: none
  double translationLimitMm = 30, rotationLimitDeg = 30;
};
// Writes report.json (poses, residuals, iterations), plan.json (the case file's plan format) and
// skin.obj (the predicted face). 0 when every target is reached, 1 on bad input, 2 when a target
// cannot be reached (the best poses are written) or the solve fails.
int runPlanFromFace(const PlanFromFaceOptions& options);

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;         // 0: any free port; the chosen one is printed as "listening on http://HOST:PORT"
  std::string webDir;      // the browser page folder
  std::string dataDir;     // empty: $ORTHOSIM_DATA, else $XDG_DATA_HOME/orthosim, else ~/.local/share/orthosim
  std::string casesDir;    // case folders besides the phantom (optional)
  std::string builtinDir;  // the shipped cases (the ArtiSynth face); absent or empty: the phantom only
  std::string token;       // empty: $ORTHOSIM_TOKEN if set, else the token file's
  std::string tokenFile;   // read, or made with a random token when absent (net/TokenFile.hpp)
  bool insecure = false;   // allow a bind off the loopback without a token
  std::vector<std::string> allowedOrigins, allowedHosts;
  bool warmUp = true;  // build the phantom's coarse model at start
  int threads = 0;     // the thread budget (0: the usable cores); previews run on this many threads
  int fineWorkers = 1;
  int maxSessions = 32;
  int modelMemoryMiB = static_cast<int>(server::kDefaultModelMemoryMiB);  // case models kept in memory (estimate)
  int unopenedTimeoutSeconds = 300;  // a session that opens no case in this time is closed
  int previewIterations = 100;       // what one preview may spend (server::PlanningOptions)
  double previewSeconds = 15;
  double faceFitSeconds = 60;    // what one face fit may spend (server::PlanningOptions::faceFitTime)
  int jobsPerSession = 4;        // fine and band jobs one session may have queued or running
  int maxUploadMb = 256;         // a patient's upload from the page (net::HttpLimits::uploadBytes)
  int maxUploads = 4;            // uploads received or imported at once (net::HttpLimits::maxUploads)
  int scanExpirySeconds = 1800;  // a scan staged for import (POST /api/scans) is removed when unused this long
  int maxStagedScans = 3;        // scans staged at once
  std::string redis;             // "redis://HOST:PORT": fine jobs on `orthosim worker` processes; empty: in process
  std::string replica;           // with redis: this server's name there (default <host>-<port>; none for port 0)
  int orphanGraceSeconds = 120;  // with redis: a job whose session is gone waits this long to be resumed
};
// Serves HTTP (and later the WebSocket API) until SIGINT or SIGTERM; 0 on a clean stop, 1 when
// the server cannot start (bad host, port taken, no web folder).
int runServe(const ServeOptions& options);

// The cases of `serve` and `worker`: the built-in ones (the ArtiSynth face when builtinDir holds
// it) and the case folders of casesDir, with what is skipped said on stderr as `orthosim COMMAND`.
std::vector<server::CaseEntry> caseCatalog(const std::string& builtinDir, const std::string& casesDir,
                                           const std::string& command);
// dataDir, or $ORTHOSIM_DATA, else $XDG_DATA_HOME/orthosim, else ~/.local/share/orthosim; absolute.
std::filesystem::path dataDirOrDefault(const std::string& dataDir);

struct WorkerOptions {
  std::string redis;  // redis://HOST:PORT
  std::string dataDir;
  std::string casesDir, builtinDir;  // as for serve: the same cases the servers offer
  int threads = 0;                   // the thread budget (0: the usable cores)
  int concurrency = 0;               // jobs at once; 0: one per thread of the budget
  int modelMemoryMiB = static_cast<int>(server::kDefaultModelMemoryMiB);  // as for serve
  double visibilitySeconds = 60;  // a job whose worker stops claiming it this long goes to another
  std::string name;               // consumer name; empty: <host>-<pid>
};
// Runs fine, band and cohort jobs from Redis until SIGINT or SIGTERM (0); 1 when it cannot start (bad address,
// Redis unreachable, data folder not writable), with the reason on stderr.
int runWorker(const WorkerOptions& options);

}  // namespace orthosim::cli
