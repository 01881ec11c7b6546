#include "volume/CtSegmentation.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "volume/BoneSplit.hpp"
#include "volume/GreyThresholds.hpp"
#include "volume/VolumeFilters.hpp"
#include "volume/VoxelMask.hpp"

namespace orthosim {
namespace {

constexpr double kSkinHu = -400, kBoneHu = 300;
constexpr double kMetalHu = 2900;    // above enamel (2500 and up), below a 12-bit scanner's saturation (3071)
constexpr double kMinAirMm3 = 1000;  // air pockets smaller than 1 cm3 stay tissue
constexpr double kSeedReachMm = 5;   // a seed this close to the bone is moved onto it
constexpr int kBorderClearance = 2;  // voxels of tissue kept between a bone and a cropped side

std::string fixed(double v, int digits = 0) {
  std::ostringstream o;
  o.precision(digits);
  o << std::fixed << v;
  return o.str();
}

std::string point(const Eigen::Vector3d& p) {
  return "(" + fixed(p.x(), 1) + ", " + fixed(p.y(), 1) + ", " + fixed(p.z(), 1) + ")";
}

VoxelMask above(const CtVolume& v, double threshold) {
  VoxelMask m(v.size);
  for (size_t n = 0; n < v.values.size(); ++n) m.on[n] = v.values[n] > threshold;
  return m;
}

void chooseThresholds(const CtVolume& grey, const CtSegmentationOptions& o, CtSegmentation& s) {
  const bool hu = hounsfieldCalibrated(grey);
  const double lo = quantile(grey.values, 0.001), hi = quantile(grey.values, 0.999);
  s.skinThreshold = o.skinThreshold ? *o.skinThreshold : hu ? kSkinHu : otsuThreshold(grey.values, lo, hi);
  if (o.boneThreshold) {
    s.boneThreshold = *o.boneThreshold;
  } else if (hu) {
    s.boneThreshold = kBoneHu;
  } else {
    std::vector<float> tissue;
    for (float v : grey.values)
      if (v > s.skinThreshold) tissue.push_back(v);
    s.boneThreshold = otsuThreshold(tissue, s.skinThreshold, quantile(tissue, 0.999));
  }
  s.metalLevel = hu ? kMetalHu : s.boneThreshold + 6 * (s.boneThreshold - s.skinThreshold);
  s.thresholdSource = o.skinThreshold && o.boneThreshold ? "given"
                      : hu                               ? "Hounsfield units (air/tissue -400, bone 300)"
                           : "the histogram (grey values not in Hounsfield units, as in CBCT)";
  if (!(s.boneThreshold > s.skinThreshold))
    throw std::invalid_argument("bone threshold " + fixed(s.boneThreshold) + " must be above the skin threshold " +
                                fixed(s.skinThreshold));
}

// The soft tissue's envelope: tissue-dense voxels, the largest piece (not the table or headrest),
// the air inside it (airway, mouth, ear canals) filled slice by slice across each axis.
VoxelMask envelope(const CtVolume& grey, double skin) {
  VoxelMask m = largestComponent(above(grey, skin));
  if (m.count() == 0) throw std::invalid_argument("no tissue above the skin threshold " + fixed(skin));
  m = holesFilledInSlices(m, superiorAxis(grey));
  return holesFilled(m);
}

// The voxel of `mask` nearest `p` (LPS mm), within kSeedReachMm; -1 if none.
long nearestOn(const CtVolume& grid, const VoxelMask& mask, const Eigen::Vector3d& p) {
  long best = -1;
  double bestD = kSeedReachMm;
  for (long v = 0; v < long(mask.on.size()); ++v) {
    if (!mask.on[v]) continue;
    const double d = (grid.position(mask.voxel(v).cast<double>()) - p).norm();
    if (d <= bestD) bestD = d, best = v;
  }
  return best;
}

// Seeds as given, else the mandible's at the chin (the lowest bone in front of the bone's centre,
// so the cervical spine behind it is not taken) and the skull's at the top of the bone.
std::pair<long, long> seeds(const CtVolume& grid, const VoxelMask& bone, const CtSegmentationOptions& o,
                            CtSegmentation& s) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  long n = 0;
  for (long v = 0; v < long(bone.on.size()); ++v)
    if (bone.on[v]) centre += grid.position(bone.voxel(v).cast<double>()), ++n;
  if (n == 0) throw std::invalid_argument("no bone above the bone threshold " + fixed(s.boneThreshold));
  centre /= double(n);
  long skull = -1, mandible = -1;
  double top = -1e300, chin = 1e300;
  for (long v = 0; v < long(bone.on.size()); ++v) {
    if (!bone.on[v]) continue;
    const Eigen::Vector3d p = grid.position(bone.voxel(v).cast<double>());
    if (p.z() > top) top = p.z(), skull = v;
    if (p.y() < centre.y() && p.z() < chin) chin = p.z(), mandible = v;  // LPS: anterior is -y
  }
  const auto given = [&](const std::optional<Eigen::Vector3d>& p, long fallback, const char* what) {
    if (!p) return fallback;
    const long v = nearestOn(grid, bone, *p);
    if (v < 0)
      throw std::invalid_argument(std::string(what) + " seed " + point(*p) + ": no bone within " + fixed(kSeedReachMm) +
                                  " mm; click on the " + what);
    return v;
  };
  skull = given(o.skullSeed, skull, "skull");
  mandible = given(o.mandibleSeed, mandible, "mandible");
  if (skull == mandible || mandible < 0) throw std::invalid_argument("the mandible's seed is the skull's");
  s.skullSeed = grid.position(bone.voxel(skull).cast<double>());
  s.mandibleSeed = grid.position(bone.voxel(mandible).cast<double>());
  return {skull, mandible};
}

// Bone voxels within `steps` of the grid's sides cleared: a scan cropped through the skull closes
// the skin there, and the bone must stay inside it.
void clearBorder(VoxelMask& m, int steps) {
  for (long v = 0; v < long(m.on.size()); ++v) {
    if (!m.on[v]) continue;
    const Eigen::Vector3i p = m.voxel(v);
    if ((p.array() < steps).any() || (p.array() >= m.size.array() - steps).any()) m.on[v] = 0;
  }
}

double voxelVolume(const CtVolume& grid) { return std::abs(grid.directions.determinant()); }

// Air inside the envelope, apart from bone and a voxel from the tissue's surfaces, in pieces of at
// least kMinAirMm3.
VoxelMask innerAir(const CtVolume& grey, const VoxelMask& inside, const VoxelMask& bone, double skin) {
  VoxelMask air(grey.size);
  for (size_t n = 0; n < air.on.size(); ++n) air.on[n] = inside.on[n] && !bone.on[n] && grey.values[n] <= skin;
  return withoutSmallComponents(eroded(air, 1), long(kMinAirMm3 / voxelVolume(grey)) + 1);
}

void note(CtSegmentation& s, const std::string& what) { s.notes.push_back(what); }

}  // namespace

CtSegmentation segmentCt(const CtVolume& volume, const CtSegmentationOptions& options) {
  if (!(options.voxelMm > 0 && options.voxelMm <= 5))
    throw std::invalid_argument("voxel size " + fixed(options.voxelMm, 2) + " mm: must be in (0, 5]");
  if (volume.values.size() != size_t(volume.count()) || volume.count() == 0)
    throw std::invalid_argument("the volume has no voxels");
  CtSegmentation s;
  const CtVolume averaged = blockAveraged(volume, options.voxelMm);
  const CtVolume grey = medianInPlane(averaged, superiorAxis(averaged));
  chooseThresholds(grey, options, s);
  const VoxelMask inside = envelope(grey, s.skinThreshold);
  VoxelMask bone = above(grey, s.boneThreshold);
  for (size_t n = 0; n < bone.on.size(); ++n) bone.on[n] = bone.on[n] && inside.on[n];
  clearBorder(bone, kBorderClearance);
  for (size_t n = 0; n < volume.values.size(); ++n) s.metalVoxels += volume.values[n] > s.metalLevel;
  const auto [skullSeed, mandibleSeed] = seeds(grey, bone, options, s);
  BoneSplit split = splitBones(grey, bone, skullSeed, mandibleSeed);
  const VoxelMask skull = holesFilled(largestComponent(split.skull));
  const VoxelMask mandible = holesFilled(largestComponent(split.mandible));
  if (mandible.count() * voxelVolume(grey) < 5000)
    throw std::invalid_argument("the mandible is not parted from the skull (" +
                                fixed(mandible.count() * voxelVolume(grey) / 1000, 1) + " cm3 at the seed " +
                                point(s.mandibleSeed) + "): click on the mandible and on the skull to seed the split");
  VoxelMask bones = skull;
  for (size_t n = 0; n < bones.on.size(); ++n) bones.on[n] |= mandible.on[n];
  const VoxelMask air =
      options.cavities ? innerAir(grey, inside, dilated(bones, 1), s.skinThreshold) : VoxelMask(grey.size);

  LabelMap& map = s.labels;
  map.size = grey.size;
  map.directions = grey.directions;
  map.origin = grey.origin;
  map.orientation = "the DICOM series' patient frame";
  map.voxels.assign(grey.values.size(), 0);
  for (size_t n = 0; n < map.voxels.size(); ++n)
    map.voxels[n] = skull.on[n]      ? CtSegmentation::kSkull
                    : mandible.on[n] ? CtSegmentation::kMandible
                    : air.on[n]      ? CtSegmentation::kAir
                    : inside.on[n]   ? CtSegmentation::kTissue
                                     : 0;
  const double mm3 = voxelVolume(grey);
  note(s, "thresholds from " + s.thresholdSource + ": skin " + fixed(s.skinThreshold) + ", bone " +
              fixed(s.boneThreshold));
  note(s, "worked on " + fixed(grey.spacing().x(), 2) + " x " + fixed(grey.spacing().y(), 2) + " x " +
              fixed(grey.spacing().z(), 2) + " mm voxels (block averages), streaks filtered within slices");
  note(s, "skull " + fixed(skull.count() * mm3 / 1000, 0) + " cm3 from " + point(s.skullSeed) + ", mandible " +
              fixed(mandible.count() * mm3 / 1000, 0) + " cm3 from " + point(s.mandibleSeed) + ", parted at " +
              std::to_string(split.contactVoxels) + " voxels");
  if (split.leftOver > 0)
    note(s, "left as soft tissue: " + fixed(split.leftOver * mm3 / 1000, 1) +
                " cm3 of bone joined to neither jaw (cervical spine, hyoid, streaks)");
  if (s.metalVoxels > 0) note(s, "metal (fillings, brackets): " + std::to_string(s.metalVoxels) + " voxels");
  if (air.count() > 0) note(s, "air inside the face: " + fixed(air.count() * mm3 / 1000, 1) + " cm3, as cavities");
  return s;
}

}  // namespace orthosim
