#pragma once
// What one session sees: its own off-screen renderer of the open case, the camera and the frame
// options. Other threads post the newest solved state and view changes; a frame task on the
// render thread takes whatever is newest and draws it, so a burst of poses or mouse moves costs
// one frame, not a backlog. A drag degrades gracefully: a linear state is drawn at half size while
// the render thread is behind, i.e. while the last linear frame came later after its pose than
// the time between the last two poses (slow frames, or other sessions' frames ahead of it), until
// a half-size one comes within half that time; everything else is drawn at the size asked.
#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "image/RgbImage.hpp"
#include "render/Camera.hpp"
#include "render/ClinicalView.hpp"
#include "render/JpegEncoder.hpp"
#include "render/RenderOptions.hpp"
#include "render/Renderer.hpp"
#include "scene/CaseModel.hpp"
#include "session/ViewRequest.hpp"
#include "solver/SimState.hpp"

namespace orthosim::server {

struct Frame {
  std::vector<unsigned char> jpeg;
  // {"width", "height", "render_ms", "encode_ms", "view", "colormap", "shows", "reduced"}
  nlohmann::json info;
};

class SessionView {
 public:
  explicit SessionView(std::shared_ptr<const CaseModel> model);
  ~SessionView();

  // Any thread. `shows` says what the state is (which pose, linear or converged); every frame
  // drawn from it carries it in its info.
  void postState(const SimState& state, nlohmann::json shows);
  void postView(const ViewRequest& request);
  void postDifference(Eigen::VectorXd valuesMm);
  // A prediction band of the case's skin (one value and position per display-skin vertex): its
  // width for the "band" colour map, and the skin at its low and high envelopes and at the nominal
  // prediction, which postBandSurface shows instead of the solved state.
  struct BandSkins {
    Eigen::VectorXd width;
    Eigen::Matrix3Xd nominal, low, high;
    std::vector<RigidPose> fragments;  // the plan's poses, for the bones
    nlohmann::json shows;              // what the band is (its job)
  };
  void postBand(std::shared_ptr<const BandSkins> band);
  // "low", "high", "nominal": that skin of the band drawn; "off": the solved state again.
  void postBandSurface(const std::string& which);

  // The render thread only. Throws RenderError (no EGL, bad texture).
  Frame render();
  // The render thread only: what pixel (x, y) of the last frame shows, {"x", "y", "surface",
  // "point_mm", "rest_mm", "depth_mm"} (docs/protocol.md): the skin, or with the bones shown a bone
  // fragment (its name; through translucent skin the bones come first); surface null for none.
  nlohmann::json pick(double x, double y);

 private:
  void create();  // the renderer, the case uploaded, the frontal camera
  void applyView(const ViewRequest& v);
  void drawAt(int divisor);  // the renderer at the size asked, divided by `divisor`
  // After a linear state was drawn at size_ / divisor: whether the render thread keeps up with the
  // poses, which sets the divisor of the next linear frame.
  void measureLag(std::chrono::steady_clock::time_point posted, int divisor);

  std::shared_ptr<const CaseModel> model_;
  std::mutex mutex_;  // guards the pending fields
  std::optional<SimState> pendingState_;
  nlohmann::json pendingShows_;
  std::chrono::steady_clock::time_point pendingPosted_, lastLinearPosted_;
  double poseIntervalMs_ = 0;                   // between the last two linear states posted
  nlohmann::json shows_ = {{"state", "rest"}};  // render thread: what the drawn state is
  ViewRequest pendingView_;
  std::optional<Eigen::VectorXd> pendingDifference_;
  std::shared_ptr<const BandSkins> pendingBand_;
  std::optional<std::string> pendingBandSurface_;
  // Render thread: the difference and band values (the renderer holds one set of skin values: the
  // colour map shown says which), the band, the skin drawn from the last state.
  Eigen::VectorXd difference_;
  std::shared_ptr<const BandSkins> band_;
  enum class Values { None, Difference, Band } uploaded_ = Values::None;
  std::optional<SimState> lastState_;
  nlohmann::json stateShows_ = {{"state", "rest"}};  // what lastState_ is
  std::string bandSurface_ = "off";

  std::unique_ptr<render::Renderer> renderer_;  // render thread from here on
  Eigen::Vector2i size_;                        // asked; the renderer's may be smaller
  // Linear states are drawn at size_ / lag divisor: 1, 2 or 4, doubled while the frames lag behind
  // the poses and halved again once they keep up.
  int lagDivisor_ = 1;
  std::unique_ptr<render::JpegEncoder> jpeg_;
  render::Camera camera_;
  std::string preset_ = "frontal";
  render::RenderOptions options_;
  RgbImage image_;
  SurfaceMesh restSkin_;                  // what picks map back to
  std::vector<render::BonePiece> bones_;  // at rest, for picks on the bones
  std::vector<RigidPose> fragmentPoses_;  // of the state drawn last
  bool showLandmarks_ = false;
  // Each landmark follows what it lies on: the nearest rest-skin vertex within 2 mm, else the
  // nearest bone piece's fragment (index into bones_; -1: neither, drawn at rest).
  struct LandmarkAnchor {
    std::string name;
    Eigen::Vector3d rest;
    int skinVertex = -1;
    int bonePiece = -1;
  };
  std::vector<LandmarkAnchor> anchors_;
  void placeMarkers();
};

}  // namespace orthosim::server
