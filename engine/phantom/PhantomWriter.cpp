// writePhantom: the phantom's surfaces, texture and landmarks as files.
#include <turbojpeg.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>

#include "io/SurfaceImport.hpp"
#include "phantom/Phantom.hpp"

namespace orthosim {
namespace {

void writeJpeg(const RgbImage& img, const std::string& path) {
  std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitCompress(), tjDestroy);
  if (!tj) throw std::runtime_error(path + ": cannot start the JPEG encoder");
  unsigned char* buf = nullptr;
  unsigned long size = 0;
  if (tjCompress2(tj.get(), img.pixels.data(), img.width, 0, img.height, TJPF_RGB, &buf, &size, TJSAMP_444, 92,
                  TJFLAG_ACCURATEDCT) != 0)
    throw std::runtime_error(path + ": JPEG encoding failed: " + tjGetErrorStr2(tj.get()));
  std::unique_ptr<unsigned char, void (*)(unsigned char*)> owned(buf, tjFree);
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(buf), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write the file: " + std::strerror(errno));
}

void writeLandmarks(const Phantom& p, const std::string& path) {
  nlohmann::json j;
  auto put = [](nlohmann::json& o, const std::vector<Landmark>& ls) {
    o = nlohmann::json::object();
    for (const Landmark& l : ls) o[l.name] = {l.position.x(), l.position.y(), l.position.z()};
  };
  put(j["hard"], p.hardLandmarks);
  put(j["soft"], p.softLandmarks);
  j["units"] = "mm";
  j["variant"] = p.variant.name;
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write the file: " + std::strerror(errno));
}

}  // namespace

void writePhantom(const Phantom& p, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error(dir + ": cannot create the directory" + (ec ? ": " + ec.message() : ""));
  const fs::path d(dir);
  exportSurface(p.skin, (d / "skin.obj").string());
  exportSurface(p.skull, (d / "skull.stl").string());
  exportSurface(p.mandible, (d / "mandible.stl").string());
  exportSurface(p.oralCavity, (d / "oral_cavity.stl").string());
  writeJpeg(p.skinTexture, (d / "skin.jpg").string());
  writeLandmarks(p, (d / "landmarks.json").string());
}

}  // namespace orthosim
