#pragma once
// The real ArtiSynth face (../shared/cases/artisynth_face) as a case, through the same code path
// as user data, and its soft-to-hard movement ratios. The face gives node sets for the skull and
// the mandible but none for the maxilla: the tissue on the maxilla is derived from the deep
// surface near the bone and joins the skull's set as one midface bone, which a Le Fort I cut then
// separates. It has no soft-tissue landmarks: they are the most anterior midline skin vertices in
// height bands read off its midline profile.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "eval/Plausibility.hpp"
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// The case file (docs/scene-format.md) for the face folder with this plan ({fragment: motion});
// its files are named in place, never copied. Fragments: midface (fixed), mandible, maxilla.
nlohmann::json realFaceCaseJson(const std::filesystem::path& faceDir, const nlohmann::json& plan);

// Most anterior (smallest x) midline (|y| <= 4 mm) skin vertex with z in [zLo, zHi]; -1 if none.
// On the face: nose tip about z 136, upper lip 96-112, lower lip 80-91, chin 54-70.
int anteriorMostMidlineVertex(const SurfaceMesh& skin, double zLo, double zHi);

// The face's ratios in ratioBands() order: a 5 mm Le Fort I advancement (upper lip and nose tip
// over the maxilla) and a 5 mm mandibular setback (chin and lower lip over the mandible), pure
// translations, coarse, with lips-teeth contact. The case files are written under workDir.
// Throws std::runtime_error when a solve does not converge.
std::vector<MovementRatio> realFaceRatios(const std::filesystem::path& faceDir, const std::filesystem::path& workDir);

}  // namespace orthosim
