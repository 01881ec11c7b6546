// `orthosim import --skin S --skull K --mandible M [--cavity C]... [--texture T] [--landmarks L]
// [--cuts le_fort_1,bsso] [--units auto|mm|m] [--name N] --out DIR`: a patient's segmented surfaces
// as a case folder (scene/CaseImport), checked file by file. `--label-map F --tissue-labels 1
// --skull-labels 2 --mandible-labels 3` takes one label map instead of the three surfaces, `--dicom
// DIR [--series UID]` a CT or CBCT series, segmented here. Without --landmarks they are suggested.
#include <chrono>
#include <iomanip>
#include <iostream>

#include "cli/Commands.hpp"
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

}  // namespace orthosim::cli
