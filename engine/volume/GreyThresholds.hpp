#pragma once
// Grey-value thresholds for segmentation. A CT in Hounsfield units has air at -1000; a CBCT's grey
// values are not calibrated (shifted and scaled by machine and field of view), so its thresholds
// come from the histogram instead: two-class Otsu between air and the rest, then between soft
// tissue and bone among the rest.
#include <vector>

#include "volume/CtVolume.hpp"

namespace orthosim {

// Whether air sits where Hounsfield units put it (the darkest percent of voxels near -1000).
bool hounsfieldCalibrated(const CtVolume& volume);

// The value between `lo` and `hi` that best splits `values` in that range into two classes (Otsu's
// between-class variance), on `bins` bins; values outside the range are clamped into it.
double otsuThreshold(const std::vector<float>& values, double lo, double hi, int bins = 256);

// The `q` quantile (0..1) of the values.
double quantile(std::vector<float> values, double q);

}  // namespace orthosim
