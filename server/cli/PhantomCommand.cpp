// `orthosim phantom --out DIR [--variant N] [--ct CTDIR [--ct-spacing MM]]`: the built-in phantom
// head as a case on disk, and as a CT's DICOM series to try the import of a scan.
#include <iostream>

#include "cli/Commands.hpp"
#include "phantom/PhantomCase.hpp"
#include "phantom/PhantomCt.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim::cli {

int runPhantom(int variant, const std::string& outDir, const std::string& ctDir, double ctSpacing) {
  bool known = false;
  for (const PhantomVariant& v : phantomVariants()) known = known || v.index == variant;
  if (!known) {
    std::cerr << "orthosim: phantom: unknown variant " << variant << "; variants:\n";
    for (const PhantomVariant& v : phantomVariants())
      std::cerr << "  " << v.index << "  " << v.name << ": " << v.description << "\n";
    return 1;
  }
  const std::string path = writePhantomCase(variant, outDir);
  for (const PhantomVariant& v : phantomVariants())
    if (v.index == variant) std::cout << "phantom " << v.index << " (" << v.name << ": " << v.description << ")\n";
  std::cout << "case written to " << path << "; solve it with `orthosim solve " << path << " --out DIR`\n";
  if (ctDir.empty()) return 0;
  try {
    PhantomScanOptions scan;  // as a head CT is taken: teeth in occlusion, a filling's streak
    if (ctSpacing > 0) scan.spacing = Eigen::Vector3d::Constant(ctSpacing);
    DicomWriteOptions options;
    options.seriesDescription = "orthosim phantom CT";
    writeDicomSeries(phantomCt(outDir, scan).ct, ctDir, options);
  } catch (const std::exception& e) {
    std::cerr << "orthosim: phantom: " << e.what() << "\n";
    return 1;
  }
  std::cout << "CT series written to " << ctDir << "; import it with `orthosim import --dicom " << ctDir
            << " --out DIR` or the page's New patient\n";
  return 0;
}

}  // namespace orthosim::cli
