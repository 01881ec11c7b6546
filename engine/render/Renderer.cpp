#include "render/Renderer.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>

#include "render/ColorScale.hpp"
#include "render/FrameLayout.hpp"
#include "render/Framebuffer.hpp"
#include "render/GlContext.hpp"
#include "render/GlTexture.hpp"
#include "render/GpuMesh.hpp"
#include "render/Legend.hpp"
#include "render/Overlay.hpp"
#include "render/RenderError.hpp"
#include "render/Shader.hpp"
#include "render/ShaderSources.hpp"

namespace orthosim::render {
namespace {

const Eigen::Vector3f kSkinTone(0.87f, 0.70f, 0.60f);
const Eigen::Vector3f kFixedBone(0.90f, 0.87f, 0.78f);
// Moving fragments in distinct light tints, so each piece of a cut reads as its own.
const Eigen::Vector3f kFragmentTints[] = {{0.55f, 0.75f, 0.95f}, {0.62f, 0.86f, 0.62f}, {0.96f, 0.76f, 0.46f},
                                          {0.80f, 0.66f, 0.92f}, {0.95f, 0.62f, 0.62f}, {0.55f, 0.88f, 0.85f}};

enum ColorSource { kFlat = 0, kTexture = 1, kRamp = 2 };
enum ValueSource { kNoValue = 0, kDisplacement = 1, kScalar = 2 };

Eigen::Matrix4f poseMatrix(const RigidPose& p) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = p.R;
  m.topRightCorner<3, 1>() = p.b;
  return m.cast<float>();
}

Eigen::Vector4f withAlpha(const Eigen::Vector3f& c, float a) { return Eigen::Vector4f(c[0], c[1], c[2], a); }

struct BoneDraw {
  GpuMesh mesh;
  int fragment;
  Eigen::Vector3f color;
};

}  // namespace

// GL objects of one context; destroyed while that context is bound (Impl's destructor).
struct GpuState {
  GpuState(int width, int height, int samples)
      : samples(samples),
        framebuffer(width, height, samples),
        surface("surface", shaders::kSurfaceVertex, shaders::kSurfaceFragment),
        displacementRamp(GlTexture::ramp(displacementScale().sample())),
        differenceRamp(GlTexture::ramp(differenceScale().sample())),
        bandRamp(GlTexture::ramp(bandScale().sample())) {}

  int samples;
  Framebuffer framebuffer;
  Shader surface;
  Overlay overlay;
  GlTexture displacementRamp, differenceRamp, bandRamp;
  std::optional<GpuMesh> skin;
  GlTexture skinTexture;
  bool skinValues = false;
  std::vector<BoneDraw> bones;
  std::vector<RigidPose> poses;
};

struct Renderer::Impl {
  GlContext context;  // declared first: outlives the GL objects
  std::unique_ptr<GpuState> gpu;

  Impl(int width, int height, int samples) {
    GlContext::Binding bound(context);
    gpu = std::make_unique<GpuState>(width, height, samples);
  }
  ~Impl() {
    GlContext::Binding bound(context);
    gpu.reset();
  }

  void drawBones(bool atRest);
  void drawSkin(const RenderOptions& options, bool atRest);
  void setSkinUniforms(const RenderOptions& options, bool atRest);
  void drawView(const Camera& camera, const RenderOptions& options, double aspect, bool atRest);
  void drawLabels(const RenderOptions& options, const FrameLayout& layout, const Camera& camera);
};

void Renderer::Impl::drawBones(bool atRest) {
  const Shader& s = gpu->surface;
  glDisable(GL_CULL_FACE);  // pieces are open where the cuts split them
  s.set("uAtRest", 0);
  s.set("uValueSource", static_cast<int>(kNoValue));
  s.set("uColorSource", static_cast<int>(kFlat));
  s.set("uSpecular", 0.08f);
  for (const BoneDraw& b : gpu->bones) {
    const bool posed = !atRest && b.fragment < static_cast<int>(gpu->poses.size());
    s.set("uModel",
          posed ? poseMatrix(gpu->poses[static_cast<size_t>(b.fragment)]) : Eigen::Matrix4f::Identity().eval());
    s.set("uColor", withAlpha(b.color, 1.0f));
    b.mesh.draw();
  }
}

void Renderer::Impl::setSkinUniforms(const RenderOptions& o, bool atRest) {
  const Shader& s = gpu->surface;
  const ColorMap map = atRest ? ColorMap::None : o.colorMap;  // "before" is shown as it looks
  s.set("uModel", Eigen::Matrix4f::Identity().eval());
  s.set("uAtRest", atRest ? 1 : 0);
  s.set("uSpecular", map == ColorMap::None ? 0.12f : 0.05f);
  s.set("uColor", withAlpha(kSkinTone, o.skinOpacity));
  s.set("uValueSource", static_cast<int>(map == ColorMap::Displacement                          ? kDisplacement
                                         : map == ColorMap::Difference || map == ColorMap::Band ? kScalar
                                                                                                : kNoValue));
  if (map == ColorMap::None) {
    s.set("uColorSource", static_cast<int>(gpu->skinTexture.valid() ? kTexture : kFlat));
    return;
  }
  s.set("uColorSource", static_cast<int>(kRamp));
  const ColorScale scale = scaleOf(o);
  s.set("uRange", Eigen::Vector2f(float(scale.min), float(scale.max)));
  s.set("uNoValue", withAlpha(kNoValueColor, 1.0f));
  (map == ColorMap::Displacement ? gpu->displacementRamp
   : map == ColorMap::Band       ? gpu->bandRamp
                                 : gpu->differenceRamp)
      .bind(1);
}

// A translucent skin blends only its nearest layer over the bones: a depth-only pass first, then
// colour where the depth matches.
void Renderer::Impl::drawSkin(const RenderOptions& o, bool atRest) {
  setSkinUniforms(o, atRest);
  glEnable(GL_CULL_FACE);  // a closed skin: back faces are hidden anyway
  if (o.skinOpacity >= 1.0f) {
    gpu->skin->draw();
    return;
  }
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gpu->skin->draw();
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gpu->skin->draw();
  glDisable(GL_BLEND);
  glDepthFunc(GL_LESS);
}

void Renderer::Impl::drawView(const Camera& camera, const RenderOptions& o, double aspect, bool atRest) {
  const Shader& s = gpu->surface;
  s.use();
  s.set("uView", camera.view().cast<float>().eval());
  s.set("uProjection", camera.projection(aspect).cast<float>().eval());
  s.set("uTexture", 0);
  s.set("uRamp", 1);
  if (gpu->skinTexture.valid()) gpu->skinTexture.bind(0);
  glEnable(GL_DEPTH_TEST);
  if (o.showBones) drawBones(atRest);
  if (o.showSkin && gpu->skin) drawSkin(o, atRest);
}

void Renderer::Impl::drawLabels(const RenderOptions& o, const FrameLayout& layout, const Camera& camera) {
  const int w = gpu->framebuffer.width(), h = gpu->framebuffer.height();
  const double s = layout.fontScale;
  Overlay& overlay = gpu->overlay;
  overlay.clear();
  if (o.colorMap != ColorMap::None && o.legend) {
    addLegend(overlay, scaleOf(o), layout.legend, s);
  }
  if (o.beforeAfter) {
    const PixelRect& after = layout.views.back();
    overlay.rect(after.x - 0.5 * s, 0, after.x + 0.5 * s, after.height, Eigen::Vector4f(1, 1, 1, 0.5f));
    for (const auto& [x, label] : {std::make_pair(0, "before"), std::make_pair(after.x, "after")}) {
      overlay.rect(x, 0, x + Overlay::textWidth(label, s) + 12 * s, 17 * s, Eigen::Vector4f(0, 0, 0, 0.35f));
      overlay.text(x + 6 * s, 5 * s, label, s, Eigen::Vector4f::Ones());
    }
  }
  const PixelRect& view = layout.views.back();  // markers go on the current (after) face
  for (const Marker& m : o.markers) {
    const ProjectedPoint p = camera.project(m.position, view.width, view.height);
    if (!p.inFront) continue;
    const double x = view.x + p.x, y = view.y + p.y, r = 3 * s;
    overlay.rect(x - r - s, y - r - s, x + r + s, y + r + s, Eigen::Vector4f(0, 0, 0, 0.8f));
    overlay.rect(x - r, y - r, x + r, y + r, Eigen::Vector4f(1.0f, 0.85f, 0.1f, 1.0f));
    overlay.text(x + r + 3 * s, y - 3.5 * s, m.label, s, Eigen::Vector4f(1.0f, 0.85f, 0.1f, 1.0f));
  }
  glViewport(0, 0, w, h);
  overlay.draw(w, h);
}

Renderer::Renderer(int width, int height, int samples) : impl_(std::make_unique<Impl>(width, height, samples)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

void Renderer::resize(int width, int height) {
  GlContext::Binding bound(impl_->context);
  impl_->gpu->framebuffer = Framebuffer(width, height, impl_->gpu->samples);
}

int Renderer::width() const { return impl_->gpu->framebuffer.width(); }
int Renderer::height() const { return impl_->gpu->framebuffer.height(); }
const std::string& Renderer::description() const { return impl_->context.description(); }

void Renderer::setSkin(const SurfaceMesh& rest, const RgbImage& texture) {
  const bool textured = texture.width > 0 || texture.height > 0 || !texture.pixels.empty();
  if (textured && !rest.hasUv())
    throw RenderError("skin: a texture is given but the skin has no texture coordinates (uv)");
  GlContext::Binding bound(impl_->context);
  GpuState& g = *impl_->gpu;
  GpuMesh mesh(rest, "skin");
  GlTexture tex = textured ? GlTexture::fromImage(texture) : GlTexture();
  g.skin.emplace(std::move(mesh));
  g.skinTexture = std::move(tex);
  g.skinValues = false;
}

void Renderer::updateSkin(const Eigen::Matrix3Xd& positions) {
  if (!impl_->gpu->skin) throw RenderError("updateSkin: no skin set (setSkin first)");
  GlContext::Binding bound(impl_->context);
  impl_->gpu->skin->updatePositions(positions);
}

void Renderer::setSkinValues(const Eigen::VectorXd& valuesMm, const std::vector<char>& inMap) {
  if (!impl_->gpu->skin) throw RenderError("setSkinValues: no skin set (setSkin first)");
  if (!valuesMm.allFinite()) throw RenderError("skin colour-map values: a value is not finite");
  GlContext::Binding bound(impl_->context);
  impl_->gpu->skin->updateScalars(valuesMm, inMap);
  impl_->gpu->skinValues = true;
}

const Eigen::Matrix3Xd& Renderer::skinPositions() const {
  if (!impl_->gpu->skin) throw RenderError("skinPositions: no skin set (setSkin first)");
  return impl_->gpu->skin->positions();
}

void Renderer::setBones(const std::vector<BonePiece>& pieces) {
  GlContext::Binding bound(impl_->context);
  std::vector<BoneDraw> bones;
  int moving = 0;
  for (const BonePiece& p : pieces) {
    const Eigen::Vector3f color = p.fixed ? kFixedBone : kFragmentTints[moving++ % std::size(kFragmentTints)];
    bones.push_back({GpuMesh(p.surface, "bone piece '" + p.fragment + "'"), p.fragmentIndex, color});
  }
  impl_->gpu->bones = std::move(bones);
  impl_->gpu->poses.clear();
}

void Renderer::setFragmentPoses(const std::vector<RigidPose>& poses) {
  for (const RigidPose& p : poses)
    if (!p.R.allFinite() || !p.b.allFinite()) throw RenderError("fragment poses: a pose is not finite");
  impl_->gpu->poses = poses;
}

double Renderer::viewAspect(const RenderOptions& options) const {
  return frameLayout(width(), height(), options).viewAspect();
}

void Renderer::render(const Camera& camera, const RenderOptions& o, RgbImage& out) {
  if (!(o.skinOpacity > 0.0f && o.skinOpacity <= 1.0f)) throw RenderError("skin opacity must lie in (0, 1]");
  if ((o.colorMap == ColorMap::Difference || o.colorMap == ColorMap::Band) && !impl_->gpu->skinValues)
    throw RenderError(std::string(o.colorMap == ColorMap::Band ? "band" : "difference") +
                      " colour map: no values set for the skin (setSkinValues)");
  GlContext::Binding bound(impl_->context);
  GpuState& g = *impl_->gpu;
  const FrameLayout layout = frameLayout(g.framebuffer.width(), g.framebuffer.height(), o);
  g.framebuffer.bindForDrawing();
  glClearColor(o.background[0], o.background[1], o.background[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (size_t v = 0; v < layout.views.size(); ++v) {
    const PixelRect& r = layout.views[v];
    glViewport(r.x, g.framebuffer.height() - r.y - r.height, r.width, r.height);  // GL counts rows from the bottom
    impl_->drawView(camera, o, layout.viewAspect(), o.beforeAfter && v == 0);
  }
  impl_->drawLabels(o, layout, camera);
  g.framebuffer.readColor(out);
}

RgbImage Renderer::render(const Camera& camera, const RenderOptions& options) {
  RgbImage out;
  render(camera, options, out);
  return out;
}

std::vector<float> Renderer::lastDepth() {
  GlContext::Binding bound(impl_->context);
  return impl_->gpu->framebuffer.readDepth();
}

}  // namespace orthosim::render
