#include "jobs/BandResultFile.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "eval/PredictionBandJson.hpp"
#include "jobs/ArrayJson.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
using nlohmann::json;

BandOutcome bandOutcome(const PredictionBand& band, double seconds) {
  return {predictionBandJson(band), band.envelope, band.nominal.fragments, seconds};
}

std::string bandResultFileName(const std::string& job) { return "jobs/" + job + ".band.json"; }

void writeBandResult(const std::filesystem::path& file, const BandOutcome& o) {
  const json j = {{"format", kBandResultFormat},
                  {"band", o.band},
                  {"seconds", o.seconds},
                  {"envelope",
                   {{"nominal", surfaceJson(o.envelope.nominal)},
                    {"normals", matrixJson(o.envelope.normals)},
                    {"low", vectorJson(o.envelope.low)},
                    {"high", vectorJson(o.envelope.high)}}},
                  {"fragments", posesJson(o.fragments)}};
  std::filesystem::create_directories(file.parent_path());
  writeFileAtomically(file, j.dump());
}

BandOutcome readBandResult(const std::filesystem::path& file) {
  const std::string name = file.string();
  const json j = readResultJson(file, "the band job's result", kBandResultFormat);
  try {
    BandOutcome o;
    o.band = member(j, "band", "");
    if (!o.band.is_object()) throw BadResultFile("/band: must be an object");
    const json& seconds = member(j, "seconds", "");
    if (!seconds.is_number() || !std::isfinite(seconds.get<double>()))
      throw BadResultFile("/seconds: must be a finite number");
    o.seconds = seconds.get<double>();
    const json& e = member(j, "envelope", "");
    o.envelope.nominal = readSurface(member(e, "nominal", "/envelope"), "/envelope/nominal");
    const long long n = o.envelope.nominal.numVertices();
    o.envelope.normals = readMatrix(member(e, "normals", "/envelope"), "/envelope/normals", n);
    o.envelope.low = readVector(member(e, "low", "/envelope"), "/envelope/low", n);
    o.envelope.high = readVector(member(e, "high", "/envelope"), "/envelope/high", n);
    o.fragments = readPoses(member(j, "fragments", ""), "/fragments");
    return o;
  } catch (const BadResultFile& e) {
    throw BadResultFile(name + ": " + e.what());
  }
}

}  // namespace orthosim::server
