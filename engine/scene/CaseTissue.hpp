#pragma once
// The tissue of a case at one resolution: tetrahedra, the tissue nodes bonded to each bone, and the
// full-resolution skin to carry along. A surface case is meshed here (Boolean difference of skin
// and bones, simplification to the resolution's skin triangle count, TetGen) and kept in an
// on-disk cache keyed by its inputs, so a second open of a case skips the meshing; a volume case
// reads its tetrahedra and node sets, deriving the bonded nodes of a bone that has none.
#include <string>
#include <vector>

#include "mesh/MeshQuality.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "mesh/TetMesh.hpp"
#include "scene/CaseFile.hpp"

namespace orthosim {

struct CaseTissue {
  TetMesh mesh;
  int indexBase = 0;                        // of a volume case's .node file; 0 for meshed ones
  std::vector<std::vector<int>> boneNodes;  // per CaseSpec::bones: nodes bonded to that bone
  std::vector<int> skinNodes;               // nodes on the skin (surface cases; empty for volume cases)
  int skinTriangles = 0;                    // simplified skin triangles (surface cases)
  SurfaceMesh skin;                         // full-resolution skin, uv when the input has it (may be empty)
  MeshQuality quality;
  std::vector<std::string> report;  // one line per step: counts, quality, derived groups, cache
  double seconds = 0;               // to build or to read from the cache
  bool fromCache = false;
};

struct CaseTissueOptions {
  std::string cacheDir;  // empty: no cache
  bool verbose = false;  // print the report lines as they come
};

// Throws SceneError naming the case file and what is wrong (a missing or bad surface, a meshing
// failure, a bone without bonded tissue).
CaseTissue buildCaseTissue(const CaseSpec& spec, Resolution resolution, const CaseTissueOptions& options = {});

// The cache key of a surface case at a resolution: a hash of the input files' bytes, the meshing
// settings and the cache format; the same inputs give the same key on any machine.
std::string caseTissueKey(const CaseSpec& spec, Resolution resolution);

// Default cache folder: $ORTHOSIM_CACHE, else $XDG_CACHE_HOME/orthosim, else ~/.cache/orthosim.
std::string defaultCacheDir();

}  // namespace orthosim
