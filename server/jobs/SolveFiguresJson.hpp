#pragma once
// The figures a preview or fine result reports (docs/protocol.md "figures"): solve effort and
// time, skin displacement, soft-tissue landmark displacements in the case's anatomical axes; and
// how far the coarse and fine predictions of the same plan lie apart on the skin.
#include <nlohmann/json.hpp>

#include "eval/SkinFigures.hpp"
#include "scene/CaseModel.hpp"
#include "solver/SolveResult.hpp"

namespace orthosim::server {

nlohmann::json solveFiguresJson(const CaseModel& model, const SkinFigureProbe& probe, const SolveResult& result,
                                const AnatomicalFrame& frame);

// Per skin vertex distance between the two predictions of the full-resolution skin: max, mean
// (area-unweighted) and 95th percentile, mm. Empty when the skins differ.
nlohmann::json skinDifferenceJson(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX, const CaseModel& fine,
                                  const Eigen::Matrix3Xd& fineX);

}  // namespace orthosim::server
