// Built case models within the library's memory budget (cases/CaseLibrary, cases/ModelCache): a
// model no one holds is evicted, least recently used first, and opens again from the mesh cache
// with the same results; a model in use survives and is shared, never built twice.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "cases/CaseLibrary.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;

// A data folder whose mesh cache is the tests' shared one, so that the phantoms are meshed once.
fs::path dataFolder() {
  const fs::path cache = ORTHOSIM_TEST_CACHE_DIR;
  const fs::path dir = cache.parent_path() / "case-library-eviction";
  fs::create_directories(dir);
  fs::create_directories(cache);
  std::error_code ec;
  if (!fs::exists(dir / "cache", ec)) fs::create_directory_symlink(cache, dir / "cache");
  return dir;
}

const std::string kA = "phantom-0", kB = "phantom-1", kC = "phantom-2";

TEST(CaseLibrary, UnusedModelIsEvictedAndReopens) {
  CaseLibrary library(builtInCases(), dataFolder(), /*modelBudgetBytes=*/1);
  std::weak_ptr<const CaseModel> firstA;
  std::weak_ptr<const Model> firstPrototype;
  Eigen::Matrix3Xd rest;
  Eigen::Index matrixNonzeros = 0;
  std::size_t factorEntries = 0;
  {
    const std::shared_ptr<const Model> prototype = library.coarsePrototype(kA);
    const std::shared_ptr<const CaseModel> a = library.model(kA, Resolution::Coarse);
    firstA = a;
    firstPrototype = prototype;
    rest = a->scene.mesh.rest;
    matrixNonzeros = prototype->system().matrix().nonZeros();
    factorEntries = prototype->restFactor().entries();
  }  // released: kept until the next request
  EXPECT_TRUE(library.isResident(kA, ModelPart::Coarse));
  const std::shared_ptr<const CaseModel> b = library.model(kB, Resolution::Coarse);
  EXPECT_FALSE(library.isResident(kA, ModelPart::Coarse));
  EXPECT_FALSE(library.isResident(kA, ModelPart::Prototype));
  EXPECT_TRUE(firstA.expired()) << "gone from memory, not only from the library";
  EXPECT_TRUE(firstPrototype.expired());

  const std::shared_ptr<const CaseModel> again = library.model(kA, Resolution::Coarse);
  EXPECT_TRUE(again->tissue.fromCache) << "read from the mesh cache, not meshed again";
  EXPECT_EQ(again->scene.mesh.rest, rest);
  const std::shared_ptr<const Model> prototype = library.coarsePrototype(kA);
  EXPECT_EQ(prototype->system().matrix().nonZeros(), matrixNonzeros);
  EXPECT_EQ(prototype->restFactor().entries(), factorEntries);
}

TEST(CaseLibrary, ModelInUseIsSharedNotEvicted) {
  CaseLibrary library(builtInCases(), dataFolder(), /*modelBudgetBytes=*/1);
  const std::shared_ptr<const CaseModel> held = library.model(kA, Resolution::Coarse);
  const std::shared_ptr<const Model> prototype = library.coarsePrototype(kA);
  library.model(kB, Resolution::Coarse);
  library.model(kC, Resolution::Coarse);  // B, unused, goes; A stays
  EXPECT_FALSE(library.isResident(kB, ModelPart::Coarse));
  EXPECT_TRUE(library.isResident(kA, ModelPart::Coarse));
  EXPECT_TRUE(library.isResident(kA, ModelPart::Prototype));
  EXPECT_EQ(library.model(kA, Resolution::Coarse).get(), held.get()) << "the same object, not a second copy";
  EXPECT_EQ(library.coarsePrototype(kA).get(), prototype.get());
}

TEST(CaseLibrary, LeastRecentlyUsedIsEvictedFirst) {
  std::size_t a = 0, b = 0, c = 0;  // estimated bytes of each coarse model
  {
    CaseLibrary measure(builtInCases(), dataFolder(), /*modelBudgetBytes=*/1ull << 40);
    measure.model(kA, Resolution::Coarse);
    a = measure.residentBytes();
    measure.model(kB, Resolution::Coarse);
    b = measure.residentBytes() - a;
    measure.model(kC, Resolution::Coarse);
    c = measure.residentBytes() - a - b;
  }
  RecordProperty("coarse_model_estimated_bytes", std::to_string(a));
  ASSERT_GT(a, 0u);
  ASSERT_GT(b, 0u);
  ASSERT_GT(c, 0u);
  CaseLibrary library(builtInCases(), dataFolder(), a + b + c - 1);  // any two fit, not three
  library.model(kA, Resolution::Coarse);
  library.model(kB, Resolution::Coarse);
  library.model(kA, Resolution::Coarse);  // A used after B
  library.model(kC, Resolution::Coarse);
  EXPECT_TRUE(library.isResident(kA, ModelPart::Coarse));
  EXPECT_FALSE(library.isResident(kB, ModelPart::Coarse)) << "the least recently used goes first";
  EXPECT_TRUE(library.isResident(kC, ModelPart::Coarse));
  EXPECT_LE(library.residentBytes(), a + b + c - 1);
}

}  // namespace
}  // namespace orthosim::server
