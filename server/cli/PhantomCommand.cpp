// `orthosim phantom --out DIR [--variant N] [--ct CTDIR [--ct-spacing MM]]`: the built-in phantom
// head as a case on disk, and as a CT's DICOM series to try the import of a scan.
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
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

void addPhantomCommand(CLI::App& parent) {
  struct Args {
    int variant = 0;
    std::string out = "phantom", ct;
    double ctSpacing = 0;
  };
  auto args = std::make_shared<Args>();
  auto* phantom = parent.add_subcommand("phantom", "Write the built-in phantom head as a surface-based case");
  phantom->add_option("--out", args->out, "Output folder")->required();
  addVariantOption(*phantom, args->variant, "Morphology variant (see --help of the case: 0 class I, ...)");
  phantom->add_option("--ct", args->ct,
                      "Also write the phantom as a CT's DICOM series into this folder (to try a scan's import)");
  phantom->add_option("--ct-spacing", args->ctSpacing, "With --ct: isotropic voxel size in mm (default 0.5 x 0.5 x 1)")
      ->check(CLI::Range(0.3, 3.0));
  runWhenChosen(*phantom, [args] { return runPhantom(args->variant, args->out, args->ct, args->ctSpacing); });
}

}  // namespace orthosim::cli
