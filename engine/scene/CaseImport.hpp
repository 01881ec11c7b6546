#pragma once
// A surgeon's own patient as a case: the segmented skin, skull (with the maxilla) and
// mandible exported from 3D Slicer, Mimics or ITK-SNAP as STL, OBJ or PLY surfaces, or one label map
// (NIfTI, NRRD) with the label numbers of each (io/LabelMapSurfaces makes the surfaces), optional
// air cavities, texture and landmarks, and the osteotomy templates to cut. Every file is checked (units, closed,
// manifold, self-intersection, bones inside the skin) and every problem comes back naming the file
// and what is wrong; the case folder is written complete or not at all.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "volume/CtSegmentation.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim {

struct CaseImportInput {
  std::string skin;      // closed envelope of the soft tissue
  std::string skull;     // skull with the maxilla: held fixed, cut by the maxilla's templates
  std::string mandible;  // moved as a whole or cut by the mandible's templates
  // Or, instead of the three surfaces: one label map (.nii, .nii.gz, .nrrd, .nhdr) and the labels of
  // the soft tissue, the skull and the mandible in it. The skin is the outer boundary of all three
  // together; the surfaces are in the map's patient frame, LPS mm (io/LabelMapSurfaces.hpp).
  std::string labelMap;
  std::vector<int> tissueLabels, skullLabels, mandibleLabels;
  // Or a CT or CBCT scan: the folder of its DICOM series (searched recursively) and, when it holds
  // several, the series' UID. It is segmented (volume/CtSegmentation) into the skin, the skull and
  // the mandible with their teeth, and the air inside the face as cavities, in its patient frame.
  std::string dicom;
  std::string dicomSeries;
  CtSegmentationOptions segmentation;
  // The series already read (a live check of the segmentation keeps it), with its read report:
  // used instead of reading `dicom` again.
  std::shared_ptr<const CtVolume> scanVolume;
  std::shared_ptr<const DicomReadReport> scanRead;
  // Told each stage as it begins ("reading the series", "segmenting", ..., "writing the case"), for
  // a page or terminal to show while an import of a scan takes its tens of seconds.
  std::function<void(const std::string& stage)> progress;
  std::vector<std::string> cavities;  // closed air spaces inside the skin (e.g. the oral cavity)
  // With no cavity given, "auto" builds the oral cavity a scan with closed lips and teeth in
  // occlusion lacks (scene/OralCavity); "none" leaves the tissue between the jaws whole.
  std::string oralCavity = "auto";
  std::string texture;  // image for the skin's texture coordinates (optional)
  // JSON {name: [x, y, z]} (or grouped under hard/soft), same units; without it they are suggested
  std::string landmarks;
  std::vector<std::string> cuts;  // osteotomy templates: le_fort_1, bsso, genioplasty, usso_left, ...
  std::string units = "auto";     // "mm", "m", or "auto": mm, refusing sizes that look like metres
  std::string name;               // the case's name (default: the folder's)
  // The anatomical frame; default: from the landmarks' Frankfort horizontal when they have it
  // (scene/LandmarkFrame), else the case format's (anterior -x, superior +z), or for a label map
  // its patient frame's (LPS: anterior -y, superior +z).
  std::optional<Eigen::Vector3d> anterior, superior;
  // An accepted case must open. With `checkOpens`, the coarse model is built from the written folder
  // before it is put in place (its tissue cached in `cacheDir`, empty: defaultCacheDir(), so the
  // first opening finds it there), and `opens` (when set) is asked about the folder's case file too
  // (a program's own checks, e.g. its renderer reading the texture; it throws to refuse). A case
  // that would not open is refused with the reason, and nothing is left.
  bool checkOpens = false;
  std::string cacheDir;
  std::function<void(const std::string& caseFile)> opens;
};

struct CaseImportReport {
  std::string caseFile;               // <outDir>/case.json
  double scale = 1.0;                 // applied to every coordinate (1000 for metres)
  std::string frame;                  // where the anatomical frame came from, for the user
  std::string labelMap;               // from a label map: its voxels, their placement, the surfaces made
  std::vector<std::string> warnings;  // repairs made and defects accepted, "<file>: ..."
  std::vector<std::string> built;     // what import made that the files lacked (the oral cavity), and where
  std::vector<std::string> scan;      // from a DICOM series: what was read, and how it was segmented
  // Without a landmarks file: the landmarks placed by rules on the surfaces (scene/SuggestedLandmarks)
  // for the user to confirm or move, and the notes of the rules (those not found, and why).
  std::vector<std::string> suggested;
};

// Thrown for anything wrong with the input; the message names the file (or option) and the defect.
struct CaseImportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes the case into `outDir`, which must not exist: the surfaces in mm (skin.obj, skull.stl,
// mandible.stl, cavity_<k>.stl), the texture, landmarks.json and case.json, which is then loaded
// (and with checkOpens, built) as a check. On any failure nothing is left behind.
CaseImportReport importCase(const CaseImportInput& input, const std::string& outDir);

// The bone a template cuts: the skull for the maxilla's (le_fort_1, le_fort_2, segmented_maxilla),
// the mandible for the others. A unilateral split is named with its side (usso_left, usso_right).
// Throws CaseImportError for an unknown template, and for "usso" without its side.
std::string boneOfTemplate(const std::string& kind);

}  // namespace orthosim
