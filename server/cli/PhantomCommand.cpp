// `orthosim phantom --out DIR [--variant N]`: the built-in phantom head as a case on disk.
#include <iostream>

#include "cli/Commands.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim::cli {

int runPhantom(int variant, const std::string& outDir) {
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
  return 0;
}

}  // namespace orthosim::cli
