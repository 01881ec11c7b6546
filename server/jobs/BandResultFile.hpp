#pragma once
// A prediction band as a worker leaves it in the data folder for the server (`serve --redis`,
// kind "band"): what the session needs of it (the band's JSON of band_done, the skin envelope
// for band_view and export_band, the plan's fragment poses for the bones, the time), in one JSON
// file written atomically:
//
//   {"format": "orthosim-band-result-1", "band": {...predictionBandJson...}, "seconds": 12.3,
//    "envelope": {"nominal": {"vertices": [...], "triangles": [...]}, "normals": [...], "low": [...],
//                 "high": [...]},
//    "fragments": [{"R": [..9], "b": [..3]}, ...]}
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/PredictionBand.hpp"

namespace orthosim::server {

inline constexpr const char* kBandResultFormat = "orthosim-band-result-1";

// A finished band, wherever it was solved.
struct BandOutcome {
  nlohmann::json band;  // predictionBandJson
  SkinEnvelope envelope;
  std::vector<RigidPose> fragments;  // the nominal solve's
  double seconds = 0;                // since the job started, the mesh included
};

BandOutcome bandOutcome(const PredictionBand& band, double seconds);

std::string bandResultFileName(const std::string& job);  // relative to the data folder: jobs/<job>.band.json
// Written to a temporary name and renamed (system/AtomicFile). Throws std::runtime_error.
void writeBandResult(const std::filesystem::path& file, const BandOutcome& outcome);
// Throws BadResultFile (jobs/ArrayJson) naming the file and the defect: missing, not JSON, another
// format, a missing field, a non-finite number, an envelope whose arrays do not match its skin.
BandOutcome readBandResult(const std::filesystem::path& file);

}  // namespace orthosim::server
