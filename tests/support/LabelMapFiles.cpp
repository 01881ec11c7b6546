#include "LabelMapFiles.hpp"

#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkSmartPointer.h>
#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace orthosim::test {

void writeNiftiLabels(const LabelGrid& g, const std::string& path) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.n.x(), g.n.y(), g.n.z());
  image->SetSpacing(g.spacing, g.spacing, g.spacing);
  image->SetOrigin(0, 0, 0);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  std::copy(g.labels.begin(), g.labels.end(), static_cast<std::uint8_t*>(image->GetScalarPointer()));
  auto qform = vtkSmartPointer<vtkMatrix4x4>::New();
  qform->Identity();
  qform->SetElement(0, 0, -1);
  qform->SetElement(1, 1, -1);
  qform->SetElement(0, 3, -g.origin.x());
  qform->SetElement(1, 3, -g.origin.y());
  qform->SetElement(2, 3, g.origin.z());
  auto writer = vtkSmartPointer<vtkNIFTIImageWriter>::New();
  writer->SetInputData(image);
  writer->SetQFormMatrix(qform);
  writer->SetFileName(path.c_str());
  writer->Write();
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": not written");
}

void writeNrrdLabels(const LabelGrid& g, const std::string& path, bool gzip, const std::string& space,
                     const Eigen::Matrix3d* directions) {
  const Eigen::Matrix3d d = directions ? *directions : Eigen::Matrix3d(g.spacing * Eigen::Matrix3d::Identity());
  const std::filesystem::path file(path);
  const bool detached = file.extension() == ".nhdr";
  const std::string dataPath = detached ? (file.parent_path() / (file.stem().string() + ".raw")).string() : path;
  std::ostringstream header;
  header.precision(17);
  header << "NRRD0004\n# written by orthosim's tests\ntype: uint8\ndimension: 3\nspace: " << space
         << "\nsizes: " << g.n.x() << " " << g.n.y() << " " << g.n.z() << "\nspace directions:";
  for (int c = 0; c < 3; ++c) header << " (" << d(0, c) << "," << d(1, c) << "," << d(2, c) << ")";
  header << "\nkinds: domain domain domain\nendian: little\nencoding: " << (gzip ? "gzip" : "raw")
         << "\nspace origin: (" << g.origin.x() << "," << g.origin.y() << "," << g.origin.z() << ")\n";
  if (detached) header << "data file: " << std::filesystem::path(dataPath).filename().string() << "\n";
  std::ofstream(path, std::ios::binary) << header.str() << (detached ? "" : "\n");
  if (detached) std::ofstream(dataPath, std::ios::binary);  // empty: the voxels alone follow
  if (!gzip) {
    std::ofstream(dataPath, std::ios::binary | std::ios::app)
        .write(reinterpret_cast<const char*>(g.labels.data()), static_cast<std::streamsize>(g.labels.size()));
    return;
  }
  gzFile z = gzopen(dataPath.c_str(), "ab");
  if (!z) throw std::runtime_error(dataPath + ": cannot open for gzip");
  const int written = gzwrite(z, g.labels.data(), static_cast<unsigned>(g.labels.size()));
  gzclose(z);
  if (written != static_cast<int>(g.labels.size())) throw std::runtime_error(dataPath + ": gzip write failed");
}

void writeNiftiIntensities(const std::string& path) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(12, 12, 12);
  image->AllocateScalars(VTK_FLOAT, 1);
  auto* v = static_cast<float*>(image->GetScalarPointer());
  for (int k = 0; k < 12 * 12 * 12; ++k) v[k] = 0.37f * k;
  auto writer = vtkSmartPointer<vtkNIFTIImageWriter>::New();
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": not written");
}

}  // namespace orthosim::test
