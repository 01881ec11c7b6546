#include "session/SessionView.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "render/CaseView.hpp"
#include "render/SurfacePick.hpp"

namespace orthosim::server {
namespace {

constexpr int kDefaultWidth = 800, kDefaultHeight = 600;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SessionView::SessionView(std::shared_ptr<const CaseModel> model) : model_(std::move(model)) {}

SessionView::~SessionView() = default;

void SessionView::postState(const SimState& state, nlohmann::json shows) {
  const auto now = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (shows.value("state", "") == "linear") {
    if (lastLinearPosted_ != std::chrono::steady_clock::time_point{})
      poseIntervalMs_ = std::chrono::duration<double, std::milli>(now - lastLinearPosted_).count();
    lastLinearPosted_ = now;
  }
  pendingState_ = state;
  pendingShows_ = std::move(shows);
  pendingPosted_ = now;
}

void SessionView::postView(const ViewRequest& request) {
  const std::lock_guard<std::mutex> lock(mutex_);
  pendingView_.merge(request);
}

void SessionView::postDifference(Eigen::VectorXd valuesMm) {
  const std::lock_guard<std::mutex> lock(mutex_);
  pendingDifference_ = std::move(valuesMm);
}

void SessionView::postBand(std::shared_ptr<const BandSkins> band) {
  const std::lock_guard<std::mutex> lock(mutex_);
  pendingBand_ = std::move(band);
}

void SessionView::postBandSurface(const std::string& which) {
  const std::lock_guard<std::mutex> lock(mutex_);
  pendingBandSurface_ = which;
}

void SessionView::create() {
  renderer_ = std::make_unique<render::Renderer>(kDefaultWidth, kDefaultHeight, 0);  // no MSAA: 2x the fps
  size_ = {kDefaultWidth, kDefaultHeight};
  render::setCase(*renderer_, *model_, render::caseTexture(model_->spec));
  jpeg_ = std::make_unique<render::JpegEncoder>(85);
  restSkin_ = model_->deformedSkin(model_->scene.mesh.rest);
  bones_ = render::caseBonePieces(*model_);
  for (const auto& [name, p] : model_->spec.landmarks) {
    LandmarkAnchor a{name, p};
    Eigen::Index v = 0;
    if (restSkin_.numVertices() > 0 && (restSkin_.vertices.colwise() - p).colwise().squaredNorm().minCoeff(&v) < 4.0)
      a.skinVertex = static_cast<int>(v);
    double best = std::numeric_limits<double>::infinity();
    for (size_t k = 0; a.skinVertex < 0 && k < bones_.size(); ++k) {
      if (bones_[k].surface.numVertices() == 0) continue;
      const double d = (bones_[k].surface.vertices.colwise() - p).colwise().squaredNorm().minCoeff();
      if (d < best) best = d, a.bonePiece = static_cast<int>(k);
    }
    anchors_.push_back(a);
  }
  camera_ = render::clinicalCamera(render::ClinicalView::Frontal, model_->spec.frame, renderer_->skinPositions(),
                                   renderer_->viewAspect(options_));
}

void SessionView::applyView(const ViewRequest& v) {
  if (v.size) {
    size_ = *v.size;
    drawAt(1);
  }
  if (v.colorMap) options_.colorMap = render::parseColorMap(*v.colorMap);
  if (v.bones) options_.showBones = *v.bones;
  if (v.landmarks) showLandmarks_ = *v.landmarks;
  if (v.skinOpacity) options_.skinOpacity = static_cast<float>(*v.skinOpacity);
  if (v.beforeAfter) options_.beforeAfter = *v.beforeAfter;
  if (v.preset || v.size || v.beforeAfter) {  // the framing depends on the view's aspect
    if (v.preset) preset_ = *v.preset;
    camera_ = render::clinicalCamera(render::parseClinicalView(preset_), model_->spec.frame, renderer_->skinPositions(),
                                     renderer_->viewAspect(options_));
  }
  camera_.orbit(v.orbitDeg.x(), v.orbitDeg.y());
  camera_.zoom(v.zoom);
  const double mmPerPixel = camera_.mmPerPixel(size_.y());
  camera_.pan(-v.panPixels.x() * mmPerPixel, v.panPixels.y() * mmPerPixel);  // the face follows the mouse
}

void SessionView::drawAt(int divisor) {
  const Eigen::Vector2i size(std::max(1, size_.x() / divisor), std::max(1, size_.y() / divisor));
  if (size.x() != renderer_->width() || size.y() != renderer_->height()) renderer_->resize(size.x(), size.y());
}

void SessionView::measureLag(std::chrono::steady_clock::time_point posted, int divisor) {
  const double lagMs = msSince(posted);
  double intervalMs = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    intervalMs = poseIntervalMs_;
  }
  if (lagMs > intervalMs)
    lagDivisor_ = std::min(4, 2 * divisor);
  else if (lagMs < 0.5 * intervalMs)
    lagDivisor_ = std::max(1, divisor / 2);
}

Frame SessionView::render() {
  if (!renderer_) create();
  std::optional<SimState> state;
  ViewRequest view;
  std::optional<Eigen::VectorXd> difference;
  std::shared_ptr<const BandSkins> band;
  std::optional<std::string> bandSurface;
  std::chrono::steady_clock::time_point posted;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    state.swap(pendingState_);
    if (state) stateShows_ = std::move(pendingShows_);
    posted = pendingPosted_;
    std::swap(view, pendingView_);
    difference.swap(pendingDifference_);
    band.swap(pendingBand_);
    bandSurface.swap(pendingBandSurface_);
  }
  if (band) band_ = band;
  const auto tUpdate = std::chrono::steady_clock::now();
  if (state) {  // a new solved state: no band surface over it
    lastState_ = state;
    bandSurface_ = "off";
  }
  if (bandSurface && (*bandSurface == "off" || band_)) bandSurface_ = *bandSurface;
  if (bandSurface_ != "off" && band_) {
    renderer_->updateSkin(bandSurface_ == "low" ? band_->low : bandSurface_ == "high" ? band_->high : band_->nominal);
    renderer_->setFragmentPoses(band_->fragments);
    fragmentPoses_ = band_->fragments;
    nlohmann::json shows = band_->shows;
    shows["state"] = "band_" + bandSurface_;
    shows_ = std::move(shows);
  } else if (state || bandSurface) {
    if (lastState_) {
      render::setCaseState(*renderer_, *model_, *lastState_);
      fragmentPoses_ = lastState_->fragments;
    } else {  // nothing solved yet: the rest face
      renderer_->updateSkin(restSkin_.vertices);
      fragmentPoses_.assign(model_->scene.fragments.size(), RigidPose::identity());
      renderer_->setFragmentPoses(fragmentPoses_);
    }
    shows_ = stateShows_;
  }
  if (difference) {
    difference_ = std::move(*difference);
    uploaded_ = Values::None;
  }
  if (band) uploaded_ = uploaded_ == Values::Band ? Values::None : uploaded_;
  applyView(view);
  const bool linear = state && stateShows_.value("state", "") == "linear" && bandSurface_ == "off";
  const int divisor = linear ? lagDivisor_ : 1;
  const bool reduced = divisor > 1;
  drawAt(divisor);
  // The values of the colour map shown: the band's width, else the coarse-vs-fine difference
  // (zeros until there is one, as before).
  const bool showBand = options_.colorMap == render::ColorMap::Band;
  if (showBand && uploaded_ != Values::Band) {
    renderer_->setSkinValues(band_ ? band_->width : Eigen::VectorXd::Zero(renderer_->skinPositions().cols()));
    uploaded_ = Values::Band;
  } else if (!showBand && uploaded_ != Values::Difference &&
             (difference_.size() > 0 || options_.colorMap == render::ColorMap::Difference)) {
    renderer_->setSkinValues(difference_.size() > 0 ? difference_
                                                    : Eigen::VectorXd::Zero(renderer_->skinPositions().cols()));
    uploaded_ = Values::Difference;
  }
  placeMarkers();
  const double updateMs = msSince(tUpdate);
  const auto t0 = std::chrono::steady_clock::now();
  renderer_->render(camera_, options_, image_);
  const double renderMs = msSince(t0);
  const auto t1 = std::chrono::steady_clock::now();
  Frame frame;
  jpeg_->encode(image_, frame.jpeg);
  frame.info = {{"width", renderer_->width()},
                {"height", renderer_->height()},
                {"update_ms", updateMs},
                {"render_ms", renderMs},
                {"encode_ms", msSince(t1)},
                {"bytes", frame.jpeg.size()},
                {"view", preset_},
                {"colormap", render::colorMapNames()[static_cast<size_t>(options_.colorMap)]},
                {"shows", shows_},
                {"reduced", reduced}};
  if (linear) measureLag(posted, divisor);
  return frame;
}

void SessionView::placeMarkers() {
  options_.markers.clear();
  if (!showLandmarks_) return;
  const Eigen::Matrix3Xd& skin = renderer_->skinPositions();
  for (const LandmarkAnchor& a : anchors_) {
    Eigen::Vector3d at = a.rest;
    if (a.skinVertex >= 0) {
      at += skin.col(a.skinVertex) - restSkin_.vertices.col(a.skinVertex);
    } else if (a.bonePiece >= 0) {
      const size_t f = static_cast<size_t>(bones_[static_cast<size_t>(a.bonePiece)].fragmentIndex);
      if (f < fragmentPoses_.size()) at = fragmentPoses_[f].apply(a.rest);
    }
    options_.markers.push_back({at, a.name});
  }
}

nlohmann::json SessionView::pick(double x, double y) {
  if (!renderer_) create();
  nlohmann::json out = {{"x", x}, {"y", y}, {"view", preset_}, {"surface", nullptr}};
  const int w = renderer_->width(), h = renderer_->height();
  // The camera and surfaces of the last frame drawn: what the user clicked on.
  std::optional<render::SurfacePick> hit =
      render::pickSurface(camera_, x, y, w, h, restSkin_, renderer_->skinPositions());
  std::string surface = hit ? "skin" : "";
  if (options_.showBones) {
    const bool throughSkin = options_.skinOpacity < 1.0f;  // the bones show through: they are what is meant
    std::optional<render::SurfacePick> bone;
    for (const render::BonePiece& piece : bones_) {
      const RigidPose pose = piece.fragmentIndex < static_cast<int>(fragmentPoses_.size())
                                 ? fragmentPoses_[static_cast<size_t>(piece.fragmentIndex)]
                                 : RigidPose::identity();
      const Eigen::Matrix3Xd drawn = (pose.R * piece.surface.vertices).colwise() + pose.b;
      const std::optional<render::SurfacePick> p = render::pickSurface(camera_, x, y, w, h, piece.surface, drawn);
      if (p && (!bone || p->depthMm < bone->depthMm)) {
        bone = p;
        surface = piece.fragment;
      }
    }
    if (bone && (throughSkin || !hit || bone->depthMm < hit->depthMm))
      hit = bone;
    else if (hit)
      surface = "skin";
  }
  if (!hit) return out;
  auto vec = [](const Eigen::Vector3d& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); };
  out["surface"] = surface;
  out["point_mm"] = vec(hit->point);
  out["rest_mm"] = vec(hit->rest);
  out["depth_mm"] = hit->depthMm;
  return out;
}

}  // namespace orthosim::server
