#pragma once
// Summary statistics of timings and distances, one definition for every report.
#include <vector>

namespace orthosim {

// The middle value; for an even count the mean of the two middle ones. NaN for no values.
double median(std::vector<double> values);

}  // namespace orthosim
