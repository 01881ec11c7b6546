// Band and cohort jobs as they travel on Redis (jobs/BandJobMessage, jobs/CohortJobMessage) and the
// results their workers leave in the data folder (jobs/BandResultFile, jobs/CohortResultFile): a
// round trip keeps every field; a malformed message or file is refused naming what is wrong and
// where.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "jobs/ArrayJson.hpp"
#include "jobs/BandResultFile.hpp"
#include "jobs/CohortResultFile.hpp"
#include "jobs/JobMessage.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

JobMessage bandJob() {
  JobMessage m;
  m.job = "0123456789abcdef-8";
  m.kind = JobKind::band;
  m.caseId = "phantom-0";
  m.caseHash = "00ff00ff00ff00ff";
  m.resolution = Resolution::Coarse;
  m.replyStream = replyStreamName("0123456789abcdef");
  FragmentMotion maxilla;
  maxilla.translation = {-4.000000000000001, 0.1, 1.0 / 3.0};
  m.plan["maxilla"] = maxilla;
  m.band = BandJobSpec{0.30000000000000004, false, 1.25};
  return m;
}

JobMessage cohortJob() {
  JobMessage m;
  m.job = "bench0123456789-3";
  m.kind = JobKind::cohort;
  m.caseId = "M4";
  m.caseHash = "00ff00ff00ff00ff";
  m.resolution = Resolution::Coarse;
  m.replyStream = replyStreamName("bench0123456789");
  CohortJobSpec s;
  s.config = {"reference", 12000, 1e-2, 3000};
  s.repeats = 2;
  s.contact = false;
  s.fallbackToDefaultTolerances = true;
  m.cohort = s;
  return m;
}

void expectRefused(const json& j, const std::string& mentions) {
  try {
    decodeJobMessage(j.dump());
    ADD_FAILURE() << "accepted: " << j.dump();
  } catch (const BadJobMessage& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

TEST(JobKinds, EachKindTravelsAsItsWord) {
  for (JobKind kind : {JobKind::fine, JobKind::band, JobKind::cohort})
    EXPECT_EQ(jobKindOfWord(jobKindWord(kind)), kind);
  EXPECT_STREQ(jobKindWord(JobKind::fine), "fine");
  EXPECT_STREQ(jobKindWord(JobKind::band), "band");
  EXPECT_STREQ(jobKindWord(JobKind::cohort), "cohort");
  EXPECT_FALSE(jobKindOfWord("Band").has_value());
  EXPECT_FALSE(jobKindOfWord("").has_value());
  const json wire = json::parse(encodeJobMessage(bandJob()));
  EXPECT_EQ(wire["kind"], "band");
}

TEST(JobKinds, ABandJobRoundTripsWithItsOptions) {
  const JobMessage in = bandJob();
  const JobMessage out = decodeJobMessage(encodeJobMessage(in));
  EXPECT_EQ(out.kind, JobKind::band);
  EXPECT_EQ(out.resolution, Resolution::Coarse);
  ASSERT_TRUE(out.band.has_value());
  EXPECT_FALSE(out.cohort.has_value());
  EXPECT_EQ(out.band->rangeScale, in.band->rangeScale);  // bit for bit
  EXPECT_FALSE(out.band->corners);
  EXPECT_EQ(out.band->touchDistanceMm, 1.25);
  EXPECT_EQ(out.plan.at("maxilla").translation, in.plan.at("maxilla").translation);
  const BandOptions o = out.band->options();
  EXPECT_EQ(o.design.rangeScale, in.band->rangeScale);
  EXPECT_FALSE(o.design.corners);
}

TEST(JobKinds, ACohortJobRoundTripsWithItsRun) {
  const JobMessage out = decodeJobMessage(encodeJobMessage(cohortJob()));
  EXPECT_EQ(out.kind, JobKind::cohort);
  EXPECT_EQ(out.caseId, "M4");
  ASSERT_TRUE(out.cohort.has_value());
  EXPECT_FALSE(out.band.has_value());
  EXPECT_EQ(out.cohort->config.label, "reference");
  EXPECT_EQ(out.cohort->config.skinTriangles, 12000);
  EXPECT_EQ(out.cohort->config.toleranceScale, 1e-2);
  EXPECT_EQ(out.cohort->config.maxTotalIterations, 3000);
  EXPECT_EQ(out.cohort->repeats, 2);
  EXPECT_FALSE(out.cohort->contact);
  EXPECT_TRUE(out.cohort->fallbackToDefaultTolerances);
}

TEST(JobKinds, MalformedBandAndCohortJobsAreNamed) {
  const json band = json::parse(encodeJobMessage(bandJob()));
  const json cohort = json::parse(encodeJobMessage(cohortJob()));
  json j = band;
  j.erase("band");
  expectRefused(j, "/band: required field is missing");
  j = band;
  j["band"]["range_scale"] = 5;
  expectRefused(j, "/band/range_scale: 5 is not in [0.01, 2");
  j = band;
  j["band"]["range_scale"] = "wide";
  expectRefused(j, "/band/range_scale: must be a number");
  j = band;
  j["band"]["corner"] = true;
  expectRefused(j, "/band/corner: unknown field");
  j = band;
  j["band"].erase("corners");
  expectRefused(j, "/band/corners: required field is missing");
  j = band;
  j["kind"] = "fine";
  expectRefused(j, "/band: only a band job has band options");
  j = band;
  j["kind"] = "celery";
  expectRefused(j, "/kind: 'celery' is not a job kind this worker runs (fine, band, cohort)");
  j = cohort;
  j["cohort"]["repeats"] = 0;
  expectRefused(j, "/cohort/repeats: 0 is not an integer in [1, 100]");
  j = cohort;
  j["cohort"]["skin_triangles"] = 12.5;
  expectRefused(j, "/cohort/skin_triangles");
  j = cohort;
  j["cohort"]["tolerance_scale"] = -1;
  expectRefused(j, "/cohort/tolerance_scale: -1 is not a number in (0, 1e6]");
  j = cohort;
  j["cohort"].erase("label");
  expectRefused(j, "/cohort/label: required field is missing");
  j = cohort;
  j["plan"] = band["plan"];
  expectRefused(j, "/plan: a cohort job's plan is its patient's (must be empty)");
  j = cohort;
  j["band"] = band["band"];
  expectRefused(j, "/band: only a band job has band options");
  j = cohort;
  j.erase("cohort");
  expectRefused(j, "/cohort: required field is missing");
}

SurfaceMesh triangle(double shift) {
  SurfaceMesh s;
  s.vertices.resize(3, 4);
  s.vertices << 0, 1, 0, 1, 0, 0, 1, 1, shift, shift, shift, 0.1 + 1.0 / 3.0;
  s.triangles.resize(3, 2);
  s.triangles << 0, 1, 1, 2, 3, 3;
  return s;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_jobkinds_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

void expectBadFile(const std::function<void()>& read, const std::string& mentions) {
  try {
    read();
    ADD_FAILURE() << "accepted";
  } catch (const BadResultFile& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

void rewrite(const fs::path& file, const std::function<void(json&)>& edit) {
  std::ifstream in(file);
  json j = json::parse(in);
  edit(j);
  std::ofstream(file) << j.dump();
}

TEST(JobKinds, TheBandResultFileRoundTripsAndNamesItsDefects) {
  BandOutcome o;
  o.band = {{"converged", 8}, {"landmarks", json::array()}};
  o.envelope.nominal = triangle(0.5);
  o.envelope.normals = Eigen::Matrix3Xd::Random(3, 4);
  o.envelope.low = Eigen::Vector4d(-0.1, -1.0 / 3.0, 0, -2);
  o.envelope.high = Eigen::Vector4d(0.1, 0.2, 1e-300, 2);
  RigidPose p;
  p.R = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p.b = {1.0 / 7.0, -2, 3};
  o.fragments = {RigidPose{}, p};
  o.seconds = 12.5;
  const fs::path file = scratch(fs::path(bandResultFileName("x-1")).filename().string());
  writeBandResult(file, o);
  const BandOutcome back = readBandResult(file);
  EXPECT_EQ(back.band, o.band);
  EXPECT_EQ(back.seconds, 12.5);
  EXPECT_EQ(back.envelope.nominal.vertices, o.envelope.nominal.vertices);  // bit for bit
  EXPECT_EQ(back.envelope.nominal.triangles, o.envelope.nominal.triangles);
  EXPECT_EQ(back.envelope.normals, o.envelope.normals);
  EXPECT_EQ(back.envelope.low, o.envelope.low);
  EXPECT_EQ(back.envelope.high, o.envelope.high);
  ASSERT_EQ(back.fragments.size(), 2u);
  EXPECT_EQ(back.fragments[1].R, p.R);
  EXPECT_EQ(back.fragments[1].b, p.b);

  const auto read = [&] { readBandResult(file); };
  rewrite(file, [](json& j) { j["envelope"]["low"].erase(0); });
  expectBadFile(read, "/envelope/low: 3 numbers, expected 4");
  writeBandResult(file, o);
  rewrite(file, [](json& j) { j["envelope"]["high"][2] = nullptr; });
  expectBadFile(read, "/envelope/high/2: must be a number");
  writeBandResult(file, o);
  rewrite(file, [](json& j) { j["envelope"]["nominal"]["triangles"][4] = 9; });
  expectBadFile(read, "/envelope/nominal/triangles/4: must be a vertex index below 4");
  writeBandResult(file, o);
  rewrite(file, [](json& j) { j["format"] = "orthosim-band-result-0"; });
  expectBadFile(read, "/format: not orthosim-band-result-1");
  writeBandResult(file, o);
  rewrite(file, [](json& j) { j.erase("fragments"); });
  expectBadFile(read, "/fragments: required field is missing");
  std::ofstream(file) << "{\"format\": \"orthosim-band";
  expectBadFile(read, "not JSON");
  fs::remove(file);
  expectBadFile(read, "cannot be read");
  fs::remove_all(file.parent_path());
}

TEST(JobKinds, TheCohortResultFileRoundTripsAndNamesItsDefects) {
  CohortOutcome o;
  o.run.config = {"fine", 6000, 1.0, 0};
  o.run.skinTriangles = 5990;
  o.run.tets = 40000;
  o.run.nodes = 9000;
  o.run.buildSeconds = 3.25;
  o.run.solveTimes = {2.0, 1.0, 3.0};
  o.run.iterations = 17;
  o.run.chordIterations = 2;
  o.run.warnings = {"crushed tissue near the chin"};
  o.run.rest = triangle(0);
  o.run.skin = triangle(1.0 / 3.0);
  o.note = "reference at the default tolerances";
  CaseSpec spec;
  spec.name = "M4";
  const fs::path file = scratch("c-1.cohort.json");
  writeCohortResult(file, o);
  const CohortOutcome back = readCohortResult(file, spec);
  EXPECT_EQ(back.note, o.note);
  EXPECT_EQ(back.run.config.label, "fine");
  EXPECT_EQ(back.run.config.skinTriangles, 6000);
  EXPECT_EQ(back.run.skinTriangles, 5990);
  EXPECT_EQ(back.run.tets, 40000);
  EXPECT_EQ(back.run.nodes, 9000);
  EXPECT_EQ(back.run.solveSeconds, 2.0);  // the median
  EXPECT_EQ(back.run.iterations, 17);
  EXPECT_EQ(back.run.warnings, o.run.warnings);
  EXPECT_EQ(back.run.skin.vertices, o.run.skin.vertices);
  EXPECT_EQ(back.run.spec.name, "M4");
  EXPECT_EQ(back.run.spec.meshing.coarseSkinTriangles, 6000);

  const auto read = [&] { readCohortResult(file, spec); };
  rewrite(file, [](json& j) { j["skin"]["triangles"][0] = 1; });
  expectBadFile(read, "/skin: not the rest skin deformed");
  writeCohortResult(file, o);
  rewrite(file, [](json& j) { j["solve_times_s"] = json::array(); });
  expectBadFile(read, "/solve_times_s: must hold at least one time");
  writeCohortResult(file, o);
  rewrite(file, [](json& j) { j["tets"] = -3; });
  expectBadFile(read, "/tets: must be a non-negative integer");
  writeCohortResult(file, o);
  rewrite(file, [](json& j) { j["rest"]["vertices"].erase(0); });
  expectBadFile(read, "/rest/vertices: 11 numbers, not x y z triples");
  fs::remove_all(file.parent_path());
}

}  // namespace
}  // namespace orthosim::server
