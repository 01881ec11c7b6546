#pragma once
// A surface-based case (docs/scene-format.md, "Surface-based cases"): the patient as clinicians
// hand it over - skin and bone surfaces (or a ready tetrahedral tissue with node sets), landmarks,
// osteotomies, the plan - rather than an explicit scene's bonded node lists. scene/CaseBuild.hpp
// turns it into a Scene at coarse or fine resolution.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/JsonReader.hpp"
#include "scene/Osteotomy.hpp"
#include "scene/Scene.hpp"

namespace orthosim {

enum class Resolution { Coarse, Fine };
const char* resolutionName(Resolution r);

struct CaseBone {
  std::string name;
  std::string surface;  // path; closed for surface cases, may be open (cropped) for volume cases
  bool fixed = false;   // held in place (the skull): the plan cannot move what is left of it
  // Volume cases only: the tissue nodes bonded to the bone, from a node set and/or derived: the
  // candidate nodes (a node set, default every boundary node) within bondDistance of the surface,
  // leaving out nodes another bone's node set claims. Derived unless a node set is given, or both
  // when `derive` is set.
  std::string nodes;
  bool derive = true;
  std::string candidates;
  double bondDistance = 2.0;  // mm
};

struct CaseRefine {
  std::string landmark;  // centre: a landmark, or `center` when empty
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 20.0;  // mm
  double density = 3.0;
};

struct CaseMeshing {
  int coarseSkinTriangles = 3000;
  int fineSkinTriangles = 20000;
  std::vector<CaseRefine> refine;
  double maxRadiusEdgeRatio = 1.5;  // TetGen -q

  int skinTriangles(Resolution r) const { return r == Resolution::Coarse ? coarseSkinTriangles : fineSkinTriangles; }
};

struct CaseFixed {
  std::string nodes;
  std::array<bool, 3> components{true, true, true};
};

// Lips and cheeks on teeth and bone: the tissue's free inner-surface nodes (not on the skin)
// within range_mm of a listed bone at rest may not go below that bone's surface, each piece moving
// with its fragment after the cuts.
struct CaseContact {
  std::vector<std::string> bones;
  double rangeMm = 15;
  // Only nodes within this distance of the skin at rest (the lips and cheeks); 0: no limit. The
  // floor of the mouth and the tongue lie deeper and are attached to the jaw (mylohyoid,
  // genioglossus) rather than sliding on it.
  double maxDepthMm = 0;
  double stiffness = 0;  // N/mm per node; 0: the default (20 E h)
};

struct CaseSpec {
  std::string file;  // the case file, absolute
  std::string name;
  AnatomicalFrame frame;
  // Tissue: a closed skin envelope minus bones and cavities (surface case), or tetrahedra.
  std::string skin;  // surface case: the envelope; volume case: the skin shown and embedded (optional)
  std::vector<std::string> cavities;
  std::string texture;         // image for the skin's uv (optional)
  std::string node, ele;       // volume case
  double youngsModulus = 0.1;  // MPa
  double poissonRatio = 0.47;
  std::vector<CaseBone> bones;
  std::vector<CaseFixed> fixed;  // volume case: extra held node sets (bone groups take precedence)
  Landmarks landmarks;
  std::vector<OsteotomySpec> cuts;
  std::vector<FragmentRegion> regions;  // what the cuts make, in order
  double blendWidth = 10.0;             // mm
  CaseMeshing meshing;
  std::vector<CaseContact> contacts;
  std::map<std::string, FragmentMotion> plan;
  SolverSettings solver;

  bool isVolume() const { return !node.empty(); }
  // Every fragment name: the bones, then what the cuts make.
  std::vector<std::string> fragmentNames() const;
  // The bone a fragment was cut from (itself for a bone); empty when unknown.
  std::string boneOf(const std::string& fragment) const;
};

// A scene file is a surface-based case when it has a "bones" section.
bool isCaseJson(const nlohmann::json& j);

// Reads and checks the case file (not the surfaces and meshes it names: CaseBuild reads those).
// Throws SceneError "<file>: <field>: <what>".
CaseSpec loadCaseFile(const std::string& path);

}  // namespace orthosim
