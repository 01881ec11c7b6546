#include "render/ImageFile.hpp"

#include <turbojpeg.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "render/JpegEncoder.hpp"
#include "render/PngFile.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

std::vector<unsigned char> readBytes(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RenderError(path + ": image file not found");
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.eof() && in.fail()) throw RenderError(path + ": cannot read the image file");
  return bytes;
}

RgbImage decodeJpeg(const std::vector<unsigned char>& bytes, const std::string& path) {
  std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), tjDestroy);
  if (!tj) throw RenderError(path + ": cannot start the JPEG decoder");
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(tj.get(), bytes.data(), bytes.size(), &width, &height, &subsampling, &colorspace) != 0)
    throw RenderError(path + ": not a readable JPEG file: " + tjGetErrorStr2(tj.get()));
  RgbImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  if (tjDecompress2(tj.get(), bytes.data(), bytes.size(), image.pixels.data(), width, 0, height, TJPF_RGB, 0) != 0)
    throw RenderError(path + ": cannot decode the JPEG file: " + tjGetErrorStr2(tj.get()));
  return image;
}

}  // namespace

RgbImage readImage(const std::string& path) {
  const std::vector<unsigned char> bytes = readBytes(path);
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return decodeJpeg(bytes, path);
  static const unsigned char pngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() >= 8 && std::equal(pngSignature, pngSignature + 8, bytes.begin())) return readPng(path);
  throw RenderError(path + ": not a JPEG or PNG image");
}

void writeImage(const RgbImage& image, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return writePng(image, path);
  if (ext != ".jpg" && ext != ".jpeg") throw RenderError(path + ": the image file must end in .png, .jpg or .jpeg");
  const std::vector<unsigned char> bytes = JpegEncoder(92).encode(image);
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw RenderError(path + ": cannot write the image file");
}

}  // namespace orthosim::render
