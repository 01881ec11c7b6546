#include "cases/CaseLibrary.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

#include "cases/ModelSize.hpp"
#include "eval/RealFace.hpp"
#include "phantom/PhantomCase.hpp"
#include "system/AtomicFile.hpp"
#include "system/TemporaryName.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
namespace {

// Which file is at `path` now: a rename over it (an edit, write-beside-then-rename) makes a new
// inode, and a rewrite in place changes the size or the modification time. Empty when absent.
std::string fileIdentity(const fs::path& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) return "";
  return std::to_string(s.st_dev) + ":" + std::to_string(s.st_ino) + ":" + std::to_string(s.st_size) + ":" +
         std::to_string(s.st_mtim.tv_sec) + "." + std::to_string(s.st_mtim.tv_nsec);
}

ModelPart partOf(Resolution resolution) { return resolution == Resolution::Fine ? ModelPart::Fine : ModelPart::Coarse; }

}  // namespace

CaseLibrary::CaseLibrary(std::vector<CaseEntry> catalog, fs::path dataDir, std::size_t modelBudgetBytes)
    : catalog_(std::move(catalog)), dataDir_(std::move(dataDir)), models_(modelBudgetBytes) {}

void CaseLibrary::discoverWith(Discover discover) {
  const std::lock_guard<std::mutex> lock(catalogMutex_);
  discover_ = std::move(discover);
}

void CaseLibrary::discover() const {
  Discover discover;
  std::set<std::string> known;
  {
    const std::lock_guard<std::mutex> lock(catalogMutex_);
    if (!discover_) return;
    discover = discover_;
    for (const CaseEntry& c : catalog_) known.insert(c.id);
  }
  // Read outside the lock (the folder may be on a network file system).
  std::vector<CaseEntry> found = discover([&](const std::string& id) { return known.count(id) > 0; });
  const std::lock_guard<std::mutex> lock(catalogMutex_);
  for (CaseEntry& f : found)
    if (std::none_of(catalog_.begin(), catalog_.end(), [&](const CaseEntry& c) { return c.id == f.id; }))
      catalog_.push_back(std::move(f));
}

std::vector<CaseEntry> CaseLibrary::catalog() const {
  discover();
  const std::lock_guard<std::mutex> lock(catalogMutex_);
  return catalog_;
}

std::optional<CaseEntry> CaseLibrary::find(const std::string& id) const {
  for (int attempt = 0; attempt < 2; ++attempt) {
    {
      const std::lock_guard<std::mutex> lock(catalogMutex_);
      for (const CaseEntry& c : catalog_)
        if (c.id == id) return c;
    }
    if (attempt == 0) discover();  // imported through another replica?
  }
  return std::nullopt;
}

void CaseLibrary::add(CaseEntry entry) {
  const std::lock_guard<std::mutex> lock(catalogMutex_);
  for (const CaseEntry& c : catalog_)
    if (c.id == entry.id) throw std::invalid_argument("a case '" + entry.id + "' exists already");
  catalog_.push_back(std::move(entry));
}

// The shipped face's case file names the shipped files in place (never copied); written into the
// data folder and rewritten whenever it differs, e.g. after the shipped folder moved.
std::string CaseLibrary::artisynthCaseFile(const CaseEntry& entry) {
  const std::lock_guard<std::mutex> lock(writeMutex_);
  const fs::path dir = dataDir_ / "cases" / entry.id;
  const fs::path file = dir / "case.json";
  const std::string text = realFaceCaseJson(fs::absolute(entry.folder), nlohmann::json::object()).dump(2) + "\n";
  {
    std::ifstream in(file);
    const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in && old == text) return file.string();
  }
  fs::create_directories(dir);
  try {
    AtomicFile out(file, "case.json.writing-");
    out.out() << text;
    out.commit();  // atomic: a reader sees the old file or the new one
  } catch (const AtomicFileError& e) {
    throw std::runtime_error("cannot write the case " + entry.id + " into " + dir.string() + ": " + e.reason());
  }
  return file.string();
}

std::string CaseLibrary::caseFile(const CaseEntry& entry) {
  if (entry.source == "artisynth") return artisynthCaseFile(entry);
  if (entry.source != "phantom") return entry.caseFile.string();
  // Written once per data folder; the phantom is deterministic, so an existing one is reused.
  const std::lock_guard<std::mutex> lock(writeMutex_);
  const fs::path dir = dataDir_ / "cases" / entry.id;
  const fs::path file = dir / "case.json";
  if (fs::is_regular_file(file)) return file.string();
  // Another server on the same data folder may be writing it too: each writes its own folder and
  // the first rename wins (the phantom is deterministic, so either is the same case).
  const fs::path tmp = dataDir_ / "cases" / (entry.id + ".writing-" + temporarySuffix());
  fs::remove_all(tmp);
  try {
    writePhantomCase(entry.phantomVariant, tmp.string());
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);  // nothing half-written stays behind
    throw std::runtime_error("cannot write the case " + entry.id + " into " + (dataDir_ / "cases").string() + ": " +
                             e.what());
  }
  std::error_code ec;
  fs::rename(tmp, dir, ec);  // a folder with case.json is always complete
  if (ec) {
    fs::remove_all(tmp);
    if (!fs::is_regular_file(file))
      throw std::runtime_error("cannot store the phantom in " + dir.string() + ": " + ec.message());
  }
  return file.string();
}

ModelCache::Built CaseLibrary::build(const CaseEntry& entry, Resolution resolution) {
  CaseTissueOptions options;
  options.cacheDir = (dataDir_ / "cache").string();
  auto model = std::make_shared<const CaseModel>(buildCaseModel(loadCaseFile(caseFile(entry)), resolution, options));
  const std::size_t bytes = estimatedBytes(*model);
  return {std::move(model), bytes};
}

void CaseLibrary::invalidate(const std::string& id) { models_.forget(id); }

void CaseLibrary::forgetIfReplaced(const CaseEntry& entry) {
  if (entry.caseFile.empty()) return;  // built-in cases: written by the servers, never edited
  const std::string identity = fileIdentity(entry.caseFile);
  const std::lock_guard<std::mutex> lock(mutex_);
  std::string& builtFrom = builtFrom_[entry.id];
  if (builtFrom == identity) return;
  if (!builtFrom.empty()) models_.forget(entry.id);  // edited since, here or by another process: build it again
  builtFrom = identity;  // read before the build: an edit during it is caught by the next call
}

std::shared_ptr<const CaseModel> CaseLibrary::model(const std::string& id, Resolution resolution) {
  const std::optional<CaseEntry> entry = find(id);
  if (!entry) throw std::invalid_argument("unknown case '" + id + "'");
  forgetIfReplaced(*entry);
  return models_.get<CaseModel>(ModelKey{id, partOf(resolution)}, [&] { return build(*entry, resolution); });
}

std::shared_ptr<const Model> CaseLibrary::coarsePrototype(const std::string& id) {
  const std::shared_ptr<const CaseModel> coarse = model(id, Resolution::Coarse);
  return models_.get<Model>(ModelKey{id, ModelPart::Prototype}, [&]() -> ModelCache::Built {
    auto prototype = std::make_shared<const Model>(coarse->scene);
    const std::size_t bytes = estimatedBytes(*prototype);
    return {std::move(prototype), bytes};
  });
}

CaseSpec CaseLibrary::spec(const std::string& id) {
  const std::optional<CaseEntry> entry = find(id);
  if (!entry) throw std::invalid_argument("unknown case '" + id + "'");
  return loadCaseFile(caseFile(*entry));
}

bool CaseLibrary::isBuilt(const std::string& id, Resolution resolution) const {
  return models_.resident(ModelKey{id, partOf(resolution)});
}

bool CaseLibrary::isResident(const std::string& id, ModelPart part) const {
  return models_.resident(ModelKey{id, part});
}

}  // namespace orthosim::server
