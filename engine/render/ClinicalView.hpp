#pragma once
// The standard views of facial photography, from the case's anatomical frame: frontal; right and
// left profile; right and left three-quarter (45 degrees); worm's eye (from below the chin,
// 45 degrees under the horizontal, the nose tip about level with the brows: nostrils, chin and
// cheek symmetry); bird's eye (45 degrees above: cheek and nasal projection). A preset sets the
// angles and frames the given points.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "render/Camera.hpp"

namespace orthosim::render {

enum class ClinicalView { Frontal, Profile, ProfileLeft, ThreeQuarter, ThreeQuarterLeft, WormsEye, BirdsEye };

// "frontal", "profile" (the right profile), "profile_left", "three_quarter" (right),
// "three_quarter_left", "worms_eye", "birds_eye".
const std::vector<std::string>& clinicalViewNames();
// Throws RenderError naming the bad name and the valid ones.
ClinicalView parseClinicalView(const std::string& name);
const std::string& clinicalViewName(ClinicalView view);

// The camera of `view` aimed at `points` (e.g. the skin's vertices) and as close as keeps them all
// in an image of `aspect` (width / height) with a small margin. Throws RenderError without points.
Camera clinicalCamera(ClinicalView view, const AnatomicalFrame& frame, const Eigen::Matrix3Xd& points, double aspect);

// Centres `camera` on `points` as seen from its current direction and sets its distance and scene
// radius so that they fill the image (aspect = width / height) with `margin` (0.05: 5%) to spare.
void frameCamera(Camera& camera, const Eigen::Matrix3Xd& points, double aspect, double margin = 0.05);

}  // namespace orthosim::render
