// The JSON scene format (docs/scene-format.md): every bad scene is reported with the file and the
// field, both by loadSceneFile and by `orthosim solve`; a valid scene round-trips its plan.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/SurfaceImport.hpp"
#include "io/TetgenIO.hpp"
#include "math/Angles.hpp"
#include "meshing/BoxMesh.hpp"
#include "meshing/SurfacePrimitives.hpp"
#include "scene/RigidPose.hpp"
#include "scene/SceneFile.hpp"
#include "solver/Model.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A 2x1x1-cell box, 20 x 10 x 10 mm: 12 nodes (z fastest, then y, then x), 12 tetrahedra.
// Nodes 0..3 lie on x = 0, 4..7 on x = 10, 8..11 on x = 20.
TetMesh box() {
  BoxSpec spec;
  spec.size = Eigen::Vector3d(20, 10, 10);
  spec.cells = Eigen::Vector3i(2, 1, 1);
  return makeBoxMesh(spec);
}

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Each test works in its own folder under the system temp folder, removed afterwards.
class SceneFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("orthosim_scenefile_" + std::string(info->name()) + "_" +
                                        std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    writeMesh();
    write("upper.txt", "# upper jaw: the x = 0 face\n0\n1\n2 3\n");
    write("lower.txt", "8 9 10 11\n");
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  fs::path path(const std::string& name) const { return dir_ / name; }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream out(path(name), std::ios::binary);
    out << text;
    ASSERT_TRUE(out.flush()) << path(name);
  }

  // box.node through writeTetgenNodes with index base 1, box.ele by hand with 1-based indices.
  // invertElement >= 0 swaps two nodes of that (0-based) element.
  void writeMesh(int invertElement = -1) const {
    const TetMesh m = box();
    writeTetgenNodes(path("box.node").string(), m.rest, 1);
    std::ostringstream ele;
    ele << m.numTets() << " 4 0\n";
    for (int e = 0; e < m.numTets(); ++e) {
      Eigen::Vector4i t = m.tets.col(e);
      if (e == invertElement) std::swap(t[1], t[2]);
      ele << e + 1 << ' ' << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << ' ' << t[3] + 1 << '\n';
    }
    write("box.ele", ele.str());
  }

  // Two prescribed fragments bonded to the end faces; the lower one moves.
  static json baseScene() {
    return json{
        {"units", "mm"},
        {"tissue",
         {{"node", "box.node"},
          {"ele", "box.ele"},
          {"material", {{"youngs_modulus_kpa", 3.0}, {"poisson_ratio", 0.45}}}}},
        {"fragments",
         json::array({{{"name", "upper"}, {"nodes", "upper.txt"}}, {{"name", "lower"}, {"nodes", "lower.txt"}}})},
        {"plan",
         {{"lower",
           {{"translation_mm", {1.0, 0.0, 0.5}}, {"rotation_deg", {0.0, 0.0, 5.0}}, {"center_mm", {20.0, 5.0, 5.0}}}}}},
    };
  }
  std::string writeScene(const json& scene) const { return writeSceneText(scene.dump(2)); }
  std::string writeSceneText(const std::string& text) const {
    write("scene.json", text);
    return path("scene.json").string();
  }

  // loadSceneFile's SceneError message; fails the test when the scene loads or throws another type.
  static std::string loadError(const std::string& scenePath) {
    try {
      loadSceneFile(scenePath);
    } catch (const SceneError& e) {
      return e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "expected a SceneError, got another exception: " << e.what();
      return e.what();
    }
    ADD_FAILURE() << scenePath << " loaded although it is invalid";
    return "";
  }

  struct CliRun {
    int exitCode = -1;
    std::string out, err;
  };
  CliRun runCli(const std::string& scenePath, const std::string& outDir) const {
    const fs::path so = path("cli.stdout"), se = path("cli.stderr");
    const std::string cmd = std::string("'") + ORTHOSIM_CLI + "' solve '" + scenePath + "' --out '" + outDir + "' > '" +
                            so.string() + "' 2> '" + se.string() + "'";
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
    r.out = readText(so);
    r.err = readText(se);
    return r;
  }

  fs::path dir_;
};

TEST_F(SceneFileTest, MissingNodeFile) {
  json s = baseScene();
  s["tissue"]["node"] = "absent.node";
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue")) << msg;
  EXPECT_TRUE(contains(msg, "absent.node")) << msg;
  EXPECT_TRUE(contains(msg, "cannot open")) << msg;
}

TEST_F(SceneFileTest, MissingNodeSetFile) {
  json s = baseScene();
  s["fragments"][1]["nodes"] = "no_such_set.txt";
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "no_such_set.txt")) << msg;
  EXPECT_TRUE(contains(msg, "fragments[1].nodes")) << msg;
  EXPECT_TRUE(contains(msg, "cannot open")) << msg;
}

TEST_F(SceneFileTest, NodeSetIndexOutOfRange) {
  // Node sets are 0-based whatever the .node file's base: the 12-node box has nodes 0..11.
  write("upper.txt", "0\n# comment line\n1 12\n");
  const std::string msg = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg, "upper.txt:3")) << msg;
  EXPECT_TRUE(contains(msg, "fragments[0].nodes")) << msg;
  EXPECT_TRUE(contains(msg, "12")) << msg;
  EXPECT_TRUE(contains(msg, "0..11")) << msg;
}

TEST_F(SceneFileTest, NodeSetNonNumericToken) {
  write("lower.txt", "8 9\n10 eleven\n");
  const std::string msg = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg, "lower.txt:2")) << msg;
  EXPECT_TRUE(contains(msg, "fragments[1].nodes")) << msg;
  EXPECT_TRUE(contains(msg, "'eleven' is not a node index")) << msg;

  write("lower.txt", "8 9 10 11.5\n");  // not an integer either
  const std::string msg2 = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg2, "lower.txt:1")) << msg2;
  EXPECT_TRUE(contains(msg2, "'11.5'")) << msg2;
}

// A contact pair: tissue nodes from a node set, a surface file (any assimp format) moving with a
// fragment, a stiffness; each field's defect is named.
TEST_F(SceneFileTest, ContactPairsAreReadAndTheirDefectsNamed) {
  const SurfaceMesh plate = makeIcosphere(3, 2, Eigen::Vector3d(10, 5, 14));
  exportSurface(plate, path("plate.stl").string());
  write("top.txt", "1 3 5 7 9 11\n");
  json s = baseScene();
  s["contact"] = json::array({{{"name", "plate"},
                               {"nodes", "top.txt"},
                               {"surface", "plate.stl"},
                               {"fragment", "lower"},
                               {"stiffness_n_per_mm", 2.5}}});
  const Scene scene = loadSceneFile(writeScene(s));
  ASSERT_EQ(scene.contacts.size(), 1u);
  EXPECT_EQ(scene.contacts[0].name, "plate");
  EXPECT_EQ(scene.contacts[0].nodes, (std::vector<int>{1, 3, 5, 7, 9, 11}));
  EXPECT_EQ(scene.contacts[0].fragment, "lower");
  EXPECT_EQ(scene.contacts[0].stiffness, 2.5);
  EXPECT_EQ(scene.contacts[0].surface.numTriangles(), plate.numTriangles());

  json bad = s;
  bad["contact"][0]["fragment"] = "chin";
  EXPECT_TRUE(contains(loadError(writeScene(bad)), "contact[0].fragment: unknown fragment 'chin'"));
  bad = s;
  bad["contact"][0]["surface"] = "missing.stl";
  EXPECT_TRUE(contains(loadError(writeScene(bad)), "contact[0].surface"));
  bad = s;
  bad["contact"][0]["stiffness_n_per_mm"] = -1;
  EXPECT_TRUE(contains(loadError(writeScene(bad)), "contact[0].stiffness_n_per_mm: must be a positive number"));
  bad = s;
  bad["contact"][0]["frobnicate"] = 1;
  EXPECT_TRUE(contains(loadError(writeScene(bad)), "frobnicate"));
}

TEST_F(SceneFileTest, UnknownFragmentInPlan) {
  json s = baseScene();
  s["plan"]["chin"] = {{"translation_mm", {0.0, 2.0, 0.0}}};
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "plan.chin")) << msg;
  EXPECT_TRUE(contains(msg, "unknown fragment 'chin'")) << msg;
}

TEST_F(SceneFileTest, UnknownFragmentInBlendedWeights) {
  json s = baseScene();
  s["blended"] = {{"weights", "weights.txt"}};
  write("weights.txt", "# node fragment weight ...\n5 upper 0.5 lower 0.5\n6 upper 0.5 chin 0.5\n");
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "weights.txt:3")) << msg;
  EXPECT_TRUE(contains(msg, "blended.weights")) << msg;
  EXPECT_TRUE(contains(msg, "unknown fragment 'chin'")) << msg;
}

// JSON has no NaN or infinity: a string in their place is a type error naming the field.
TEST_F(SceneFileTest, NonFiniteNumberInPlanAsString) {
  json s = baseScene();
  s["plan"]["lower"]["translation_mm"] = {1.0, "NaN", 0.0};
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "plan.lower")) << msg;
  EXPECT_TRUE(contains(msg, "translation_mm")) << msg;
  EXPECT_TRUE(contains(msg, "must be an array of 3 numbers")) << msg;

  s = baseScene();
  s["plan"]["lower"]["rotation_deg"] = "inf";
  const std::string msg2 = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg2, "plan.lower")) << msg2;
  EXPECT_TRUE(contains(msg2, "rotation_deg")) << msg2;
}

// nlohmann::json refuses 1e999 while parsing (out_of_range 406 "number overflow"), so the value never
// reaches the finiteness checks. Through the CLI this is bad input (exit 1) naming the scene file.
TEST_F(SceneFileTest, OverflowingNumberInPlanViaCli) {
  std::string text = baseScene().dump(2);
  const std::string five = "5.0";
  const auto at = text.find(five, text.find("rotation_deg"));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, five.size(), "1e999");
  const std::string scene = writeSceneText(text);
  const CliRun r = runCli(scene, path("out").string());
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "scene.json")) << r.err;
  EXPECT_TRUE(contains(r.err, "1e999")) << r.err;
  EXPECT_FALSE(fs::exists(path("out") / "result.json"));
}

TEST_F(SceneFileTest, OverflowingNumberInPlanIsASceneError) {
  std::string text = baseScene().dump(2);
  const auto at = text.find("5.0", text.find("rotation_deg"));
  text.replace(at, 3, "1e999");
  const std::string msg = loadError(writeSceneText(text));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "1e999")) << msg;
}

TEST_F(SceneFileTest, InvertedElement) {
  writeMesh(/*invertElement=*/3);
  const std::string msg = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue")) << msg;
  EXPECT_TRUE(contains(msg, "box.ele")) << msg;
  EXPECT_TRUE(contains(msg, "element 4")) << msg;  // numbered as in the 1-based file
  EXPECT_TRUE(contains(msg, "inverted")) << msg;
}

TEST_F(SceneFileTest, MalformedJson) {
  const std::string scene = writeSceneText("{\n  \"tissue\": {\"node\": \"box.node\", \"ele\": \"box.ele\",}\n}\n");
  const std::string msg = loadError(scene);
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "malformed JSON")) << msg;
  EXPECT_TRUE(contains(msg, "line 2")) << msg;
}

TEST_F(SceneFileTest, UnknownFieldIsRefused) {
  json s = baseScene();
  s["tissue"]["material"]["poisson_ration"] = 0.4;  // typo next to the real field
  std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue.material")) << msg;
  EXPECT_TRUE(contains(msg, "unknown field 'poisson_ration'")) << msg;

  s = baseScene();
  s["solver"] = {{"max_iteration", 5}};
  msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "solver")) << msg;
  EXPECT_TRUE(contains(msg, "unknown field 'max_iteration'")) << msg;

  s = baseScene();
  s["plan"]["lower"]["rotation"] = {0.0, 0.0, 1.0};
  msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "plan.lower")) << msg;
  EXPECT_TRUE(contains(msg, "unknown field 'rotation'")) << msg;

  s = baseScene();
  s["plna"] = s["plan"];
  msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "unknown field 'plna'")) << msg;
}

TEST_F(SceneFileTest, UnknownTopLevelFieldIsNamedBeforeItsConsequences) {
  json s = baseScene();
  s["fragmnts"] = s["fragments"];
  s.erase("fragments");
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "unknown field 'fragmnts'")) << msg;
}

TEST_F(SceneFileTest, WrongType) {
  json s = baseScene();
  s["tissue"]["material"]["youngs_modulus_kpa"] = "3";
  std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue.material.youngs_modulus_kpa")) << msg;
  EXPECT_TRUE(contains(msg, "must be a number")) << msg;

  s = baseScene();
  s["solver"] = {{"substeps", 2.5}};
  msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "solver.substeps")) << msg;
  EXPECT_TRUE(contains(msg, "must be an integer")) << msg;

  s = baseScene();
  s["fragments"][0]["free"] = "yes";
  msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "fragments[0].free")) << msg;
}

TEST_F(SceneFileTest, PoissonRatioOneHalf) {
  json s = baseScene();
  s["tissue"]["material"]["poisson_ratio"] = 0.5;
  const std::string scene = writeScene(s);
  const std::string msg = loadError(scene);
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue.material.poisson_ratio")) << msg;
  EXPECT_TRUE(contains(msg, "(-1, 0.5)")) << msg;

  const CliRun r = runCli(scene, path("out").string());
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "scene.json")) << r.err;
  EXPECT_TRUE(contains(r.err, "poisson_ratio")) << r.err;
  EXPECT_FALSE(fs::exists(path("out") / "result.json"));
}

TEST_F(SceneFileTest, NodeInTwoFragments) {
  write("lower.txt", "8 9 10 11 3\n");  // node 3 is also in upper.txt
  const std::string scene = writeScene(baseScene());
  Scene loaded = loadSceneFile(scene);  // each node set is valid on its own
  try {
    Model model(std::move(loaded));
    ADD_FAILURE() << "a node in two fragments was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_TRUE(contains(msg, "node 3")) << msg;
    EXPECT_TRUE(contains(msg, "'upper'")) << msg;
    EXPECT_TRUE(contains(msg, "'lower'")) << msg;
  }

  const CliRun r = runCli(scene, path("out").string());
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "scene.json")) << r.err;
  EXPECT_TRUE(contains(r.err, "node 3")) << r.err;
  EXPECT_TRUE(contains(r.err, "coupled twice")) << r.err;
  EXPECT_FALSE(fs::exists(path("out") / "result.json"));
}

TEST_F(SceneFileTest, TruncatedNodeFile) {
  // Header promises 12 nodes; the file ends after 10 (index base 1: ids 1..10).
  std::string node = readText(path("box.node"));
  for (int i = 0; i < 2; ++i) node.resize(node.rfind('\n', node.size() - 2) + 1);
  write("box.node", node);
  std::string msg = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg, "scene.json")) << msg;
  EXPECT_TRUE(contains(msg, "tissue")) << msg;
  EXPECT_TRUE(contains(msg, "box.node:11")) << msg;
  EXPECT_TRUE(contains(msg, "ends after 10 of 12 nodes")) << msg;

  // Cut inside the last line: its z coordinate is missing.
  node = readText(path("box.node"));
  node.resize(node.rfind(' '));
  write("box.node", node);
  msg = loadError(writeScene(baseScene()));
  EXPECT_TRUE(contains(msg, "box.node:11")) << msg;
  EXPECT_TRUE(contains(msg, "missing z coordinate")) << msg;
}

TEST_F(SceneFileTest, BlendedNodeListedTwice) {
  json s = baseScene();
  s["blended"] = {{"weights", "weights.txt"}};
  write("weights.txt", "5 upper 0.25 lower 0.75\n5 upper 0.25 lower 0.75\n");
  const std::string msg = loadError(writeScene(s));
  EXPECT_TRUE(contains(msg, "weights.txt:2")) << msg;
  EXPECT_TRUE(contains(msg, "blended.weights")) << msg;
  EXPECT_TRUE(contains(msg, "node 5")) << msg;
}

TEST_F(SceneFileTest, ValidSceneRoundTrips) {
  json s = baseScene();
  s["tissue"]["material"]["model"] = "neo-hookean";
  s["fragments"][1]["free"] = false;
  s["fixed"] = json::array({{{"nodes", "fixed.txt"}, {"components", "z"}},
                            {{"nodes", "pulled.txt"}, {"displacement_mm", {0.0, 0.25, 0.0}}}});
  s["blended"] = {{"weights", "weights.txt"}};
  s["plan"]["upper"] = json::object();  // listed without motion: stays at rest
  s["solver"] = {{"substeps", 2},
                 {"max_iterations", 40},
                 {"max_refinements", 5},
                 {"force_tolerance_n", 1e-7},
                 {"step_tolerance_mm", 1e-6},
                 {"hessian", "projected"}};
  write("fixed.txt", "4\n");
  write("pulled.txt", "7\n");
  write("weights.txt", "5 upper 0.25 lower 0.75\n");
  const Scene scene = loadSceneFile(writeScene(s));

  const TetMesh m = box();
  EXPECT_EQ(scene.indexBase, 1);
  ASSERT_EQ(scene.mesh.numNodes(), 12);
  ASSERT_EQ(scene.mesh.numTets(), 12);
  EXPECT_TRUE(scene.mesh.tets == m.tets);
  EXPECT_TRUE(scene.mesh.rest.isApprox(m.rest, 1e-15));
  EXPECT_DOUBLE_EQ(scene.youngsModulus, 0.003);  // 3 kPa in MPa
  EXPECT_DOUBLE_EQ(scene.poissonRatio, 0.45);

  ASSERT_EQ(scene.fragments.size(), 2u);
  EXPECT_EQ(scene.fragments[0].name, "upper");
  EXPECT_EQ(scene.fragments[0].nodes, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(scene.fragments[0].free);
  EXPECT_EQ(scene.fragments[1].name, "lower");
  EXPECT_EQ(scene.fragments[1].nodes, (std::vector<int>{8, 9, 10, 11}));

  ASSERT_EQ(scene.fixed.size(), 2u);
  EXPECT_EQ(scene.fixed[0].nodes, std::vector<int>{4});
  EXPECT_EQ(scene.fixed[0].components, (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(scene.fixed[0].displacement, Eigen::Vector3d::Zero());
  EXPECT_EQ(scene.fixed[1].components, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(scene.fixed[1].displacement, Eigen::Vector3d(0.0, 0.25, 0.0));

  ASSERT_EQ(scene.blended.size(), 1u);
  EXPECT_EQ(scene.blended[0].node, 5);
  ASSERT_EQ(scene.blended[0].weights.size(), 2u);
  EXPECT_EQ(scene.blended[0].weights[0], (std::pair<int, double>{0, 0.25}));
  EXPECT_EQ(scene.blended[0].weights[1], (std::pair<int, double>{1, 0.75}));

  ASSERT_EQ(scene.plan.size(), 2u);
  const FragmentMotion& lower = scene.plan.at("lower");
  EXPECT_EQ(lower.translation, Eigen::Vector3d(1.0, 0.0, 0.5));
  EXPECT_EQ(lower.center, Eigen::Vector3d(20.0, 5.0, 5.0));
  EXPECT_NEAR(lower.rotation.x(), 0.0, 1e-15);
  EXPECT_NEAR(lower.rotation.y(), 0.0, 1e-15);
  EXPECT_NEAR(lower.rotation.z(), 5.0 * kPi / 180.0, 1e-15);
  const FragmentMotion& upper = scene.plan.at("upper");
  EXPECT_EQ(upper.translation, Eigen::Vector3d::Zero());
  EXPECT_EQ(upper.rotation, Eigen::Vector3d::Zero());

  EXPECT_EQ(scene.solver.substeps, 2);
  EXPECT_EQ(scene.solver.maxIterations, 40);
  EXPECT_EQ(scene.solver.maxRefinements, 5);
  EXPECT_DOUBLE_EQ(scene.solver.forceTolerance, 1e-7);
  EXPECT_DOUBLE_EQ(scene.solver.stepTolerance, 1e-6);
  EXPECT_EQ(scene.solver.hessian, HessianMode::Projected);

  // The plan's pose maps X to c + t + R(X - c), R a 5 degree turn about z.
  const RigidPose pose = lower.pose();
  const Eigen::Vector3d X(20.0, 10.0, 0.0), c(20.0, 5.0, 5.0);
  const double a = 5.0 * kPi / 180.0;
  const Eigen::Vector3d d = X - c;
  const Eigen::Vector3d expected =
      c + Eigen::Vector3d(1.0, 0.0, 0.5) +
      Eigen::Vector3d(std::cos(a) * d.x() - std::sin(a) * d.y(), std::sin(a) * d.x() + std::cos(a) * d.y(), d.z());
  EXPECT_LT((pose.apply(X) - expected).norm(), 1e-12);
}

TEST_F(SceneFileTest, CliSolvesValidScene) {
  const std::string scene = writeScene(baseScene());
  const fs::path out = path("out");
  const CliRun r = runCli(scene, out.string());
  ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "converged")) << r.out;

  const json result = json::parse(readText(out / "result.json"));
  EXPECT_TRUE(result.at("converged").get<bool>());
  EXPECT_DOUBLE_EQ(result.at("load_fraction").get<double>(), 1.0);
  EXPECT_EQ(result.at("model").at("nodes").get<int>(), 12);
  EXPECT_EQ(result.at("model").at("tetrahedra").get<int>(), 12);
  EXPECT_EQ(result.at("model").at("reduced_dofs").get<int>(), 12);  // nodes 4..7 free
  ASSERT_EQ(result.at("fragments").size(), 2u);
  const json& lower = result.at("fragments").at(1);
  EXPECT_EQ(lower.at("name").get<std::string>(), "lower");
  EXPECT_NEAR(lower.at("rotation_deg").at(2).get<double>(), 5.0, 1e-9);

  // deformed.node keeps the input's index base 1; the lower face lies at its planned pose.
  const TetgenMesh deformed = readTetgen((out / "deformed.node").string(), path("box.ele").string());
  EXPECT_EQ(deformed.indexBase, 1);
  const TetMesh m = box();
  const RigidPose pose = RigidPose::fromMotion(Eigen::Vector3d(1.0, 0.0, 0.5), Eigen::Vector3d(0, 0, 5.0 * kPi / 180.0),
                                               Eigen::Vector3d(20.0, 5.0, 5.0));
  for (int i = 8; i < 12; ++i) EXPECT_LT((deformed.mesh.rest.col(i) - pose.apply(m.rest.col(i))).norm(), 1e-9) << i;
  for (int i = 0; i < 4; ++i) EXPECT_LT((deformed.mesh.rest.col(i) - m.rest.col(i)).norm(), 1e-12) << i;
}

}  // namespace
}  // namespace orthosim
