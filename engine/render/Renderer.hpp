#pragma once
// Off-screen renderer of a case: the textured, lit skin, bone fragments at their poses, colour maps
// with a legend, before/after. It keeps the skin on the GPU: setSkin uploads topology, uv and the
// rest surface once, and each new solve only uploads positions and normals (updateSkin); bone
// pieces are uploaded once and moved by their fragment's pose.
//
// Threading rule: a Renderer has its own EGL context, and EGL binds a context to one thread at a
// time. Every public call (construction and destruction included) binds the context to the
// calling thread for the call's duration and restores what was current before. So a renderer may
// be owned by a server thread or an Asio strand and called from whichever thread runs it, but by
// ONE thread at a time: calls are not synchronised (overlapping calls are an error, which EGL
// usually reports as a RenderError when it refuses to bind a context current on another thread).
// Several renderers may run in parallel on different threads.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "image/RgbImage.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "render/Camera.hpp"
#include "render/CaseBones.hpp"
#include "render/RenderOptions.hpp"
#include "scene/RigidPose.hpp"

namespace orthosim::render {

class Renderer {
 public:
  // An image of width x height pixels, `samples` x multisampling (0 or 1: none). Throws
  // RenderError when EGL or OpenGL 3.3 is not available, or for a size the GPU cannot hold.
  Renderer(int width, int height, int samples = 4);
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;

  void resize(int width, int height);
  int width() const;
  int height() const;
  // The OpenGL renderer and EGL platform, e.g. "llvmpipe (...), OpenGL 4.5 (Core Profile) ..., EGL surfaceless".
  const std::string& description() const;

  // The skin at rest: triangles, uv and rest positions (the displacement map's reference); the
  // current skin starts at rest. `texture` (rows top first, v = 0 at the bottom row) needs uv;
  // without one the skin is a plain skin tone. Throws RenderError for an empty mesh, an index out
  // of range, a texture on a skin without uv or a malformed image.
  void setSkin(const SurfaceMesh& rest, const RgbImage& texture = {});
  // A new deformed skin: 3 x (rest skin's vertex count) positions; only they and the normals are
  // uploaded. Throws RenderError without a skin or for another vertex count.
  void updateSkin(const Eigen::Matrix3Xd& positions);
  // Values for ColorMap::Difference, one per skin vertex, in mm (e.g. signedDifference()).
  // `inMap` (empty, or one flag per vertex): vertices flagged 0 are drawn grey, as having no
  // value (e.g. outside an error measurement's region of interest).
  void setSkinValues(const Eigen::VectorXd& valuesMm, const std::vector<char>& inMap = {});
  // The skin's current positions (rest until updateSkin), e.g. to frame a camera.
  const Eigen::Matrix3Xd& skinPositions() const;

  // Bone pieces at rest (caseBonePieces); replaces earlier ones. Their poses start at rest.
  void setBones(const std::vector<BonePiece>& pieces);
  // Fragment poses indexed like BonePiece::fragmentIndex (a solve's SimState::fragments).
  void setFragmentPoses(const std::vector<RigidPose>& poses);

  // Width / height of one view, to frame a camera: the image less the legend strip (with a colour
  // map), halved side by side (options.beforeAfter).
  double viewAspect(const RenderOptions& options) const;
  // Draws a frame and reads it back into `out` (storage reused across frames).
  void render(const Camera& camera, const RenderOptions& options, RgbImage& out);
  RgbImage render(const Camera& camera, const RenderOptions& options);
  // Window depth in [0, 1] of the last frame, row-major and top row first; 1 where nothing was drawn.
  std::vector<float> lastDepth();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace orthosim::render
