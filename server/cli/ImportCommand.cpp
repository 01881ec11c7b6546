// `orthosim import --skin S --skull K --mandible M [--cavity C]... [--texture T] [--landmarks L]
// [--cuts le_fort_1,bsso] [--units auto|mm|m] [--name N] --out DIR`: a patient's segmented surfaces
// as a case folder (scene/CaseImport), checked file by file. `--label-map F --tissue-labels 1
// --skull-labels 2 --mandible-labels 3` takes one label map instead of the three surfaces, `--dicom
// DIR [--series UID]` a CT or CBCT series, segmented here. Without --landmarks they are suggested.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "scene/CaseImport.hpp"

namespace orthosim::cli {

int runImport(const CaseImportInput& given, const std::string& outDir) {
  CaseImportInput input = given;
  const auto started = std::chrono::steady_clock::now();
  input.progress = [&](const std::string& stage) {  // a scan takes tens of seconds: say what it is doing
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::cout << "[" << std::fixed << std::setprecision(1) << s << " s] " << stage << "\n" << std::flush;
  };
  try {
    const CaseImportReport report = importCase(input, outDir);
    if (!report.labelMap.empty()) std::cout << report.labelMap << "\n";
    for (const std::string& line : report.scan) std::cout << "scan: " << line << "\n";
    for (const std::string& w : report.warnings) std::cout << "warning: " << w << "\n";
    for (const std::string& b : report.built) std::cout << "built: " << b << "\n";
    for (const std::string& l : report.suggested) std::cout << "suggested: " << l << "\n";
    if (report.scale != 1.0) std::cout << "coordinates scaled by " << report.scale << " to millimetres\n";
    std::cout << "anatomical frame: " << report.frame << "\n";
    std::cout << "case written to " << report.caseFile << "; serve it with `orthosim serve --cases <its parent>`"
              << " or solve it with `orthosim solve " << report.caseFile << " --out DIR`\n";
    return 0;
  } catch (const CaseImportError& e) {
    std::cerr << "orthosim: import: " << e.what() << "\n";
    return 1;
  }
}

namespace {

// "le_fort_1,bsso" as its templates; empty names are skipped.
std::vector<std::string> splitCuts(const std::string& list) {
  std::vector<std::string> cuts;
  for (std::size_t at = 0; at < list.size();) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    if (comma > at) cuts.push_back(list.substr(at, comma - at));
    at = comma + 1;
  }
  return cuts;
}

// An option of three numbers x y z, set only when given.
CLI::Option* addPointOption(CLI::App& command, const std::string& name, std::optional<Eigen::Vector3d>& point,
                            const std::string& description) {
  const auto set = [&point](const std::vector<double>& xyz) { point = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]); };
  return command.add_option_function<std::vector<double>>(name, set, description)->expected(3);
}

// An option of one number, set only when given.
CLI::Option* addNumberOption(CLI::App& command, const std::string& name, std::optional<double>& number,
                             const std::string& description) {
  const auto set = [&number](double value) { number = value; };
  return command.add_option_function<double>(name, set, description);
}

// The patient's anatomy: three surfaces, one label map, or a DICOM series. Returns the label map's
// and the series' options, which the options that go with them need.
std::pair<CLI::Option*, CLI::Option*> addImportSourceOptions(CLI::App& command, CaseImportInput& in) {
  auto* skin = command.add_option("--skin", in.skin, "Closed skin (soft-tissue envelope) surface");
  auto* skull = command.add_option("--skull", in.skull, "Skull with the maxilla (held fixed)");
  auto* mandible = command.add_option("--mandible", in.mandible, "Mandible");
  auto* labelMap =
      command.add_option("--label-map", in.labelMap,
                         "Instead of --skin, --skull, --mandible: one label map (.nii, .nii.gz, .nrrd, .nhdr)");
  for (auto* surface : {skin, skull, mandible}) labelMap->excludes(surface);
  auto* dicom = command.add_option(
      "--dicom", in.dicom,
      "Folder of a CT or CBCT DICOM series (or several: choose with --series), segmented automatically");
  for (auto* other : {skin, skull, mandible, labelMap}) dicom->excludes(other);
  command.add_option("--series", in.dicomSeries, "With --dicom: the SeriesInstanceUID to use")->needs(dicom);
  return {labelMap, dicom};
}

// The segmentation of a DICOM series.
void addImportDicomOptions(CLI::App& command, CtSegmentationOptions& seg, CLI::Option* dicom) {
  addNumberOption(command, "--skin-threshold", seg.skinThreshold,
                  "With --dicom: air/tissue grey value (default -400 HU, or from the histogram)")
      ->needs(dicom);
  addNumberOption(command, "--bone-threshold", seg.boneThreshold,
                  "With --dicom: bone grey value (default 300 HU, or from the histogram)")
      ->needs(dicom);
  addPointOption(command, "--mandible-seed", seg.mandibleSeed, "With --dicom: a point x y z on the mandible (LPS mm)")
      ->needs(dicom);
  addPointOption(command, "--skull-seed", seg.skullSeed, "With --dicom: a point x y z on the skull (LPS mm)")
      ->needs(dicom);
  command.add_option("--voxel", seg.voxelMm, "With --dicom: working voxel size in mm (default 1)")
      ->check(CLI::Range(0.2, 5.0))
      ->needs(dicom);
}

// The label numbers of a label map.
void addImportLabelOptions(CLI::App& command, CaseImportInput& in, CLI::Option* labelMap) {
  command
      .add_option("--tissue-labels", in.tissueLabels,
                  "With --label-map: the soft tissue's label numbers (comma-separated)")
      ->delimiter(',')
      ->needs(labelMap);
  command
      .add_option("--skull-labels", in.skullLabels, "With --label-map: the skull's (with the maxilla) label numbers")
      ->delimiter(',')
      ->needs(labelMap);
  command.add_option("--mandible-labels", in.mandibleLabels, "With --label-map: the mandible's label numbers")
      ->delimiter(',')
      ->needs(labelMap);
}

// What the case holds besides the anatomy, and how the files are read.
void addImportCaseOptions(CLI::App& command, CaseImportInput& in) {
  command.add_option("--cavity", in.cavities, "Closed air cavity inside the skin (repeatable)");
  command
      .add_option(
          "--oral-cavity", in.oralCavity,
          "Without --cavity: auto builds the oral cavity closed lips and teeth in occlusion lack, none does not")
      ->check(CLI::IsMember({"auto", "none"}));
  command.add_option("--texture", in.texture, "Image for the skin's texture coordinates");
  command.add_option("--landmarks", in.landmarks, "JSON file of landmarks {name: [x, y, z]}");
  const auto setCuts = [&in](const std::string& list) { in.cuts = splitCuts(list); };
  command.add_option_function<std::string>("--cuts", setCuts,
                                           "Osteotomy templates, comma-separated (e.g. le_fort_1,bsso)");
  command.add_option("--units", in.units, "Units of the files: auto (mm; refuses metre-sized data), mm, m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  command.add_option("--name", in.name, "Name of the case (default: the folder's)");
  in.checkOpens = true;
  command.add_flag(
      "!--no-open-check", in.checkOpens,
      "Skip building the coarse model before the case is written (it is then checked at its first opening)");
  addPointOption(command, "--anterior", in.anterior, "Anterior direction of the files' axes (default -1 0 0)");
  addPointOption(command, "--superior", in.superior, "Superior direction (default 0 0 1)");
}

}  // namespace

void addImportCommand(CLI::App& parent) {
  struct Args {
    CaseImportInput input;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  auto* command = parent.add_subcommand(
      "import", "Make a case from a patient's segmented surfaces (STL, OBJ, PLY) or label map (NIfTI, NRRD)");
  const auto [labelMap, dicom] = addImportSourceOptions(*command, args->input);
  addImportDicomOptions(*command, args->input.segmentation, dicom);
  addImportLabelOptions(*command, args->input, labelMap);
  addImportCaseOptions(*command, args->input);
  command->add_option("--out", args->out, "Case folder to write (must not exist)")->required();
  runWhenChosen(*command, [args] { return runImport(args->input, args->out); });
}

}  // namespace orthosim::cli
