#include "io/LabelMapSurfaces.hpp"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNrrdReader.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkQuadricDecimation.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>
#include <unordered_set>

#include "io/VtkMessages.hpp"

namespace orthosim {
namespace {

template <class T>
using Ptr = vtkSmartPointer<T>;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool endsWith(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::string list(const std::vector<int>& values, size_t most = 20) {
  std::string out;
  for (size_t k = 0; k < values.size() && k < most; ++k) out += (k ? ", " : "") + std::to_string(values[k]);
  if (values.size() > most) out += ", ... (" + std::to_string(values.size()) + " in all)";
  return out.empty() ? "none" : out;
}

// The voxels of `image` as whole numbers; throws for fractional values.
std::vector<int> wholeVoxels(vtkImageData* image, const std::string& path) {
  const vtkIdType n = image->GetNumberOfPoints();
  std::vector<int> out(static_cast<size_t>(n));
  bool fractional = false;
  double example = 0;
  switch (image->GetScalarType()) {
    vtkTemplateMacro({
      const auto* data = static_cast<const VTK_TT*>(image->GetScalarPointer());
      for (vtkIdType i = 0; i < n; ++i) {
        const double v = static_cast<double>(data[i]);
        if (!fractional && (v != std::floor(v) || std::abs(v) > 2e9)) {
          fractional = true;
          example = v;
        }
        out[i] = static_cast<int>(v);
      }
    });
    default:
      throw LabelMapError(path + ": voxels of an unsupported type (" + image->GetScalarTypeAsString() + ")");
  }
  if (fractional) {
    std::ostringstream o;
    o << path << ": not a label map: voxel values must be whole label numbers (found " << example
      << "); export the segmentation as a label map volume";
    throw LabelMapError(o.str());
  }
  return out;
}

void requireVolume(const LabelMap& map, int components) {
  if (components != 1)
    throw LabelMapError(map.path + ": " + std::to_string(components) +
                        " values per voxel; a label map has one (a segmentation with overlapping layers? "
                        "export it as a label map volume)");
  if ((map.size.array() < 2).any())
    throw LabelMapError(map.path + ": " + std::to_string(map.size[0]) + " x " + std::to_string(map.size[1]) + " x " +
                        std::to_string(map.size[2]) + " voxels is not a 3-D volume");
}

const Eigen::Matrix3d kRasToLps = Eigen::Vector3d(-1, -1, 1).asDiagonal();

// How a file stores its voxels, for the least bytes it needs for them.
enum class VoxelEncoding { Raw, Gzip, Ascii, Elsewhere };  // Elsewhere: a detached header's data file

// Deflate expands a byte to at most 1032.
constexpr double kMaxDeflateRatio = 1032;
// A label map of 1024^3 voxels is beyond any head scan (CBCT: 512^3 at most) and already takes
// gigabytes as the ints it is read into.
constexpr double kMaxVoxels = 1024.0 * 1024.0 * 1024.0;

// Refuses, before VTK allocates what the header declares, voxels that cannot be in the file: more
// bytes than it holds (raw), than deflate could expand it to (gzip), than its text has values (2
// bytes a value at least), or more voxels than any label map has. Call after UpdateInformation().
// `headerBytes`: what comes before the voxels in the file.
void checkDeclaredVoxels(vtkAlgorithm* reader, const std::string& path, VoxelEncoding encoding,
                         std::uintmax_t headerBytes) {
  vtkInformation* info = reader->GetOutputInformation(0);
  int extent[6] = {0, -1, 0, -1, 0, -1};
  if (info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  double voxels = 1;
  for (int a = 0; a < 3; ++a) voxels *= std::max(0, extent[2 * a + 1] - extent[2 * a] + 1);
  const double values = voxels * std::max(1, vtkImageData::GetNumberOfScalarComponents(info));
  const double bytes = values * std::max(1, vtkDataArray::GetDataTypeSize(vtkImageData::GetScalarType(info)));
  std::error_code ec;
  const std::uintmax_t fileBytes = std::filesystem::file_size(path, ec);
  const double size = static_cast<double>(fileBytes > headerBytes ? fileBytes - headerBytes : 0);
  const auto declared = [&] {
    std::ostringstream s;
    s << path << ": the header declares " << extent[1] - extent[0] + 1 << " x " << extent[3] - extent[2] + 1 << " x "
      << extent[5] - extent[4] + 1 << " voxels (" << std::fixed << std::setprecision(0) << bytes << " bytes)";
    return s.str();
  };
  if (voxels > kMaxVoxels)
    throw LabelMapError(declared() + ": more than 1024^3 voxels, beyond any head scan's label map");
  if (ec) return;
  std::ostringstream have;
  have << std::fixed << std::setprecision(0) << size;
  if (encoding == VoxelEncoding::Raw && bytes > size) {
    std::ostringstream need;
    need << std::fixed << std::setprecision(0) << bytes;
    throw LabelMapError(path + ": truncated: the voxels need " + need.str() + " bytes, the file holds " + have.str());
  }
  if (encoding == VoxelEncoding::Gzip && bytes > kMaxDeflateRatio * size)
    throw LabelMapError(declared() + ", more than its " + have.str() + " compressed bytes can hold");
  if (encoding == VoxelEncoding::Ascii && 2 * values > size + 1)
    throw LabelMapError(declared() + ", more values than its " + have.str() + " bytes of text can hold");
}

LabelMap readNifti(const std::string& path) {
  auto reader = Ptr<vtkNIFTIImageReader>::New();
  if (!reader->CanReadFile(path.c_str())) throw LabelMapError(path + ": not a NIfTI file (no NIfTI header)");
  VtkMessages messages(reader);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  const bool gzip = endsWith(lower(path), ".gz");  // its header is compressed with the voxels
  if (messages.errors.empty())
    checkDeclaredVoxels(
        reader, path, gzip ? VoxelEncoding::Gzip : VoxelEncoding::Raw,
        gzip ? 0 : static_cast<std::uintmax_t>(std::max<vtkTypeInt64>(0, reader->GetNIFTIHeader()->GetVoxOffset())));
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!messages.errors.empty() || !image || image->GetNumberOfPoints() == 0)
    throw LabelMapError(path + ": cannot read the NIfTI image: " +
                        (messages.errors.empty() ? std::string("no voxels") : trim(messages.errors)));
  LabelMap map;
  map.path = path;
  int extent[6];
  image->GetExtent(extent);
  map.size = Eigen::Vector3i(extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1);
  if (reader->GetTimeDimension() > 1)
    throw LabelMapError(path + ": " + std::to_string(reader->GetTimeDimension()) +
                        " time points; a label map is one 3-D volume");
  requireVolume(map, image->GetNumberOfScalarComponents());
  // VTK's data coordinates (origin + spacing * index) and the matrix from them to NIfTI's RAS world:
  // the sform when the file sets one, else the qform, else none (the voxel grid as it is).
  double o[3], s[3];
  image->GetOrigin(o);
  image->GetSpacing(s);
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
  vtkNIFTIImageHeader* header = reader->GetNIFTIHeader();
  vtkMatrix4x4* m = nullptr;
  if (header->GetSFormCode() > 0 && reader->GetSFormMatrix()) {
    m = reader->GetSFormMatrix();
    map.orientation = "NIfTI sform (RAS, turned into LPS)";
  } else if (header->GetQFormCode() > 0 && reader->GetQFormMatrix()) {
    m = reader->GetQFormMatrix();
    map.orientation = "NIfTI qform (RAS, turned into LPS)";
  } else {
    map.orientation = "NIfTI without qform or sform: the voxel grid's axes (spacing and origin only)";
  }
  if (m)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) world(r, c) = m->GetElement(r, c);
  const Eigen::Matrix3d a = world.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = world.topRightCorner<3, 1>();
  const Eigen::Vector3d origin(o[0] + s[0] * extent[0], o[1] + s[1] * extent[2], o[2] + s[2] * extent[4]);
  const Eigen::Matrix3d toLps = m ? kRasToLps : Eigen::Matrix3d::Identity();
  map.directions = toLps * a * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
  map.origin = toLps * (a * origin + t);
  map.voxels = wholeVoxels(image, path);
  return map;
}

std::vector<double> numbers(std::string text) {
  for (char& c : text)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(text);
  std::vector<double> out;
  for (std::string word; in >> word;) {
    try {
      out.push_back(word == "none" || word == "nan" ? std::nan("") : std::stod(word));
    } catch (const std::exception&) {
      out.push_back(std::nan(""));
    }
  }
  return out;
}

// The NRRD header's fields (lower-case keys). VTK's reader reads the voxels but keeps only the
// spacing of "space directions" (not the axes' directions), so the placement is taken from here.
std::map<std::string, std::string> nrrdFields(const std::string& path, bool detached, std::uintmax_t& headerBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LabelMapError(path + ": cannot read the file");
  std::string line;
  std::getline(in, line);
  if (line.rfind("NRRD", 0) != 0) throw LabelMapError(path + ": not an NRRD file (it does not start with NRRD)");
  std::map<std::string, std::string> fields;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      if (detached) continue;
      headerBytes = static_cast<std::uintmax_t>(in.tellg());
      break;  // the data follows
    }
    if (line[0] == '#') continue;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos || line.find(":=") < colon) continue;  // key/value pairs
    fields[lower(trim(line.substr(0, colon)))] = trim(line.substr(colon + 2));
  }
  return fields;
}

LabelMap readNrrd(const std::string& path, bool detached) {
  std::uintmax_t headerBytes = 0;
  std::map<std::string, std::string> f = nrrdFields(path, detached, headerBytes);
  const std::string encoding = lower(f.count("encoding") ? f["encoding"] : "raw");
  if (encoding != "raw" && encoding != "gzip" && encoding != "gz" && encoding != "ascii" && encoding != "text" &&
      encoding != "txt")
    throw LabelMapError(path + ": NRRD encoding '" + encoding +
                        "' is not supported: save it raw or gzip-compressed, or as NIfTI");
  const int dimension = f.count("dimension") ? std::atoi(f["dimension"].c_str()) : 0;
  if (dimension != 3)
    throw LabelMapError(path + ": " + std::to_string(dimension) +
                        "-dimensional NRRD; a label map is 3-D (a segmentation with several layers? export "
                        "it as a label map volume)");
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  LabelMap map;
  map.path = path;
  if (f.count("space") || f.count("space directions")) {
    const std::string space = lower(f.count("space") ? f["space"] : "left-posterior-superior");
    Eigen::Matrix3d toLps;
    if (space == "left-posterior-superior" || space == "lps") {
      toLps.setIdentity();
      map.orientation = "NRRD space left-posterior-superior";
    } else if (space == "right-anterior-superior" || space == "ras") {
      toLps = kRasToLps;
      map.orientation = "NRRD space right-anterior-superior (turned into LPS)";
    } else {
      throw LabelMapError(path + ": NRRD space '" + space +
                          "' is not supported (left-posterior-superior or right-anterior-superior are)");
    }
    const std::vector<double> d = numbers(f["space directions"]);
    if (d.size() != 9 || !std::all_of(d.begin(), d.end(), [](double v) { return std::isfinite(v); }))
      throw LabelMapError(path + ": NRRD 'space directions' must be three 3-D vectors (got '" + f["space directions"] +
                          "')");
    for (int c = 0; c < 3; ++c) directions.col(c) = toLps * Eigen::Vector3d(d[3 * c], d[3 * c + 1], d[3 * c + 2]);
    if (f.count("space origin")) {
      const std::vector<double> p = numbers(f["space origin"]);
      if (p.size() != 3 || !std::isfinite(p[0] + p[1] + p[2]))
        throw LabelMapError(path + ": NRRD 'space origin' must be a 3-D point (got '" + f["space origin"] + "')");
      origin = toLps * Eigen::Vector3d(p[0], p[1], p[2]);
    }
  } else {
    map.orientation = "NRRD without space: the voxel grid's axes taken as LPS";
    if (f.count("spacings")) {
      const std::vector<double> s = numbers(f["spacings"]);
      if (s.size() == 3)
        for (int c = 0; c < 3; ++c)
          if (std::isfinite(s[c]) && s[c] > 0) directions(c, c) = s[c];
    }
  }
  if (std::abs(directions.determinant()) < 1e-12)
    throw LabelMapError(path + ": the voxel axes are degenerate (zero spacing or parallel directions)");

  auto reader = Ptr<vtkNrrdReader>::New();
  VtkMessages messages(reader);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  if (messages.errors.empty())
    checkDeclaredVoxels(reader, path,
                        detached || f.count("data file") || f.count("datafile") ? VoxelEncoding::Elsewhere
                        : encoding == "raw"                                     ? VoxelEncoding::Raw
                        : encoding == "gzip" || encoding == "gz"                ? VoxelEncoding::Gzip
                                                                                : VoxelEncoding::Ascii,
                        headerBytes);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!messages.errors.empty() || !image || image->GetNumberOfPoints() == 0)
    throw LabelMapError(path + ": cannot read the NRRD image: " +
                        (messages.errors.empty() ? std::string("no voxels") : trim(messages.errors)));
  int extent[6];
  image->GetExtent(extent);
  map.size = Eigen::Vector3i(extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1);
  const std::vector<double> sizes = numbers(f["sizes"]);
  requireVolume(map, image->GetNumberOfScalarComponents());
  if (sizes.size() != 3 || sizes[0] != map.size[0] || sizes[1] != map.size[1] || sizes[2] != map.size[2])
    throw LabelMapError(path + ": NRRD sizes '" + f["sizes"] + "' do not match the voxels read");
  // VTK reads raw voxels past the end of a short file without an error: count the bytes.
  if (encoding == "raw") {
    namespace fs = std::filesystem;
    const std::string dataFile = f.count("data file") ? f["data file"] : f.count("datafile") ? f["datafile"] : "";
    const bool single = dataFile.empty() || dataFile.find(' ') == std::string::npos;
    const fs::path data = dataFile.empty() ? fs::path(path) : fs::path(path).parent_path() / dataFile;
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(data, ec);
    const std::uintmax_t needed = static_cast<std::uintmax_t>(image->GetNumberOfPoints()) * image->GetScalarSize();
    const std::uintmax_t have = ec ? 0 : dataFile.empty() ? (bytes > headerBytes ? bytes - headerBytes : 0) : bytes;
    if (single && have < needed)
      throw LabelMapError(path + ": truncated: the voxels need " + std::to_string(needed) + " bytes, " +
                          (dataFile.empty() ? std::string("the file holds ") : data.string() + " holds ") +
                          std::to_string(have));
  }
  map.directions = directions;
  map.origin = origin;
  map.voxels = wholeVoxels(image, path);
  return map;
}

// The mask of `labels` padded by one background voxel on every side (so every surface closes),
// with voids enclosed by it filled when `envelope`.
Ptr<vtkImageData> regionMask(const LabelMap& map, const std::vector<int>& labels, bool envelope) {
  const Eigen::Vector3i n = map.size + Eigen::Vector3i::Constant(2);
  auto mask = Ptr<vtkImageData>::New();
  mask->SetDimensions(n[0], n[1], n[2]);
  mask->SetOrigin(-1, -1, -1);
  mask->SetSpacing(1, 1, 1);
  mask->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* m = static_cast<unsigned char*>(mask->GetScalarPointer());
  std::fill(m, m + static_cast<size_t>(n.prod()), 0);
  const std::unordered_set<int> chosen(labels.begin(), labels.end());
  const int lo = *std::min_element(labels.begin(), labels.end());
  const int hi = *std::max_element(labels.begin(), labels.end());
  size_t v = 0;
  for (int k = 0; k < map.size[2]; ++k)
    for (int j = 0; j < map.size[1]; ++j) {
      unsigned char* row = m + ((static_cast<size_t>(k) + 1) * n[1] + j + 1) * n[0] + 1;
      for (int i = 0; i < map.size[0]; ++i, ++v) {
        const int label = map.voxels[v];
        row[i] = label >= lo && label <= hi && chosen.count(label) ? 1 : 0;
      }
    }
  if (!envelope) return mask;
  // Background reached from the padding (6-connected) stays outside; anything else is inside.
  const size_t sx = 1, sy = n[0], sz = static_cast<size_t>(n[0]) * n[1];
  std::deque<size_t> front = {0};
  m[0] = 2;
  while (!front.empty()) {
    const size_t at = front.front();
    front.pop_front();
    const int i = static_cast<int>(at % sy), j = static_cast<int>((at / sy) % n[1]), k = static_cast<int>(at / sz);
    const auto visit = [&](bool ok, size_t next) {
      if (ok && m[next] == 0) {
        m[next] = 2;
        front.push_back(next);
      }
    };
    visit(i > 0, at - sx);
    visit(i + 1 < n[0], at + sx);
    visit(j > 0, at - sy);
    visit(j + 1 < n[1], at + sy);
    visit(k > 0, at - sz);
    visit(k + 1 < n[2], at + sz);
  }
  for (size_t at = 0; at < static_cast<size_t>(n.prod()); ++at) m[at] = m[at] == 2 ? 0 : 1;
  return mask;
}

SurfaceMesh toSurface(vtkPolyData* poly) {
  SurfaceMesh s;
  s.vertices.resize(3, poly->GetNumberOfPoints());
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p) {
    double x[3];
    poly->GetPoint(p, x);
    s.vertices.col(p) = Eigen::Vector3d(x[0], x[1], x[2]);
  }
  vtkCellArray* polys = poly->GetPolys();
  s.triangles.resize(3, polys->GetNumberOfCells());
  auto ids = Ptr<vtkIdList>::New();
  int t = 0;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    s.triangles.col(t++) = Eigen::Vector3i(ids->GetId(0), ids->GetId(1), ids->GetId(2));
  }
  s.triangles.conservativeResize(3, t);
  return s;
}

}  // namespace

std::vector<int> LabelMap::labels() const {
  if (voxels.empty()) return {};
  const auto [lo, hi] = std::minmax_element(voxels.begin(), voxels.end());
  std::vector<int> out;
  if (static_cast<long long>(*hi) - *lo < (1 << 24)) {
    std::vector<char> seen(static_cast<size_t>(*hi - *lo + 1), 0);
    for (int v : voxels) seen[v - *lo] = 1;
    for (size_t k = 0; k < seen.size(); ++k)
      if (seen[k] && static_cast<int>(k) + *lo != 0) out.push_back(static_cast<int>(k) + *lo);
    return out;
  }
  std::unordered_set<int> seen(voxels.begin(), voxels.end());
  seen.erase(0);
  out.assign(seen.begin(), seen.end());
  std::sort(out.begin(), out.end());
  return out;
}

LabelMap readLabelMap(const std::string& path) {
  namespace fs = std::filesystem;
  quietVtk();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw LabelMapError(path + ": cannot read the label map: no such file");
  const std::string name = lower(fs::path(path).filename().string());
  if (endsWith(name, ".nii") || endsWith(name, ".nii.gz")) return readNifti(path);
  if (endsWith(name, ".nrrd")) return readNrrd(path, false);
  if (endsWith(name, ".nhdr")) return readNrrd(path, true);
  throw LabelMapError(path +
                      ": unsupported label map format: label maps are read from NIfTI (.nii, .nii.gz) or "
                      "NRRD (.nrrd, .nhdr)");
}

std::vector<SurfaceMesh> labelMapSurfaces(const LabelMap& map, const std::vector<LabelRegion>& regions,
                                          const LabelMapSurfaceOptions& options) {
  const std::vector<int> present = map.labels();
  for (const LabelRegion& region : regions) {
    if (region.labels.empty()) throw LabelMapError(map.path + ": no label chosen for the " + region.name);
    for (int label : region.labels)
      if (!std::binary_search(present.begin(), present.end(), label))
        throw LabelMapError(map.path + ": label " + std::to_string(label) + " (chosen for the " + region.name +
                            ") is not in the label map; its labels are " + list(present));
  }
  std::vector<SurfaceMesh> out;
  for (const LabelRegion& region : regions) {
    const Ptr<vtkImageData> mask = regionMask(map, region.labels, region.envelope);
    auto contour = Ptr<vtkDiscreteFlyingEdges3D>::New();
    contour->SetInputData(mask);
    contour->SetValue(0, 1);
    contour->ComputeNormalsOff();
    contour->ComputeGradientsOff();
    contour->ComputeScalarsOff();
    auto smooth = Ptr<vtkWindowedSincPolyDataFilter>::New();
    smooth->SetInputConnection(contour->GetOutputPort());
    smooth->SetNumberOfIterations(options.smoothingIterations);
    smooth->SetPassBand(options.passBand);
    smooth->BoundarySmoothingOff();
    smooth->FeatureEdgeSmoothingOff();
    smooth->NonManifoldSmoothingOn();
    smooth->NormalizeCoordinatesOn();
    VtkMessages messages(smooth);
    smooth->Update();
    vtkPolyData* smoothed = smooth->GetOutput();
    if (!smoothed || smoothed->GetNumberOfPolys() == 0)
      throw LabelMapError(map.path + ": the " + region.name + " (labels " + list(region.labels) + ") gives no surface" +
                          (messages.errors.empty() ? "" : ": " + trim(messages.errors)));
    // Voxel index to LPS millimetres (the mask's points are voxel indices).
    auto placed = Ptr<vtkPolyData>::New();
    auto points = Ptr<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(smoothed->GetNumberOfPoints());
    for (vtkIdType p = 0; p < smoothed->GetNumberOfPoints(); ++p) {
      double x[3];
      smoothed->GetPoint(p, x);
      const Eigen::Vector3d q = map.position(Eigen::Vector3d(x[0], x[1], x[2]));
      points->SetPoint(p, q.x(), q.y(), q.z());
    }
    placed->SetPoints(points);
    placed->SetPolys(smoothed->GetPolys());
    SurfaceMesh surface;
    if (placed->GetNumberOfPolys() > options.maxTriangles) {
      auto decimate = Ptr<vtkQuadricDecimation>::New();
      decimate->SetInputData(placed);
      decimate->SetTargetReduction(1.0 - static_cast<double>(options.maxTriangles) / placed->GetNumberOfPolys());
      decimate->VolumePreservationOn();
      decimate->Update();
      surface = toSurface(decimate->GetOutput());
    } else {
      surface = toSurface(placed);
    }
    if (surface.numTriangles() == 0)
      throw LabelMapError(map.path + ": the " + region.name + " (labels " + list(region.labels) + ") gives no surface");
    if (surface.signedVolume() < 0) surface.triangles.row(1).swap(surface.triangles.row(2));
    out.push_back(std::move(surface));
  }
  return out;
}

}  // namespace orthosim
