// The built-in phantom head (engine/phantom): the geometry contract the tissue Boolean and the
// mesher rely on, the landmarks against the clinical primer's dimensions, the variants, and the
// files writePhantom produces.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/SurfaceImport.hpp"
#include "math/Angles.hpp"
#include "mesh/SelfIntersection.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "phantom/Phantom.hpp"
#include "phantom/PhantomDesign.hpp"
#include "phantom/PhantomSkull.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;

// Each variant is built once for the whole file (about a second each).
const Phantom& phantomOf(int variant) {
  static std::map<int, Phantom> cache;
  auto it = cache.find(variant);
  if (it == cache.end()) it = cache.emplace(variant, makePhantom({variant, 1.5})).first;
  return it->second;
}

const Landmark& find(const std::vector<Landmark>& ls, const std::string& name) {
  for (const Landmark& l : ls)
    if (l.name == name) return l;
  throw std::runtime_error("no landmark " + name);
}
Eigen::Vector3d hard(int v, const std::string& n) { return find(phantomOf(v).hardLandmarks, n).position; }
Eigen::Vector3d soft(int v, const std::string& n) { return find(phantomOf(v).softLandmarks, n).position; }

// Inside test for a closed surface: parity of crossings of a vertical ray, triangles bucketed by
// their xy box. Independent of how the phantom was built.
class InsideTest {
 public:
  explicit InsideTest(const SurfaceMesh& m) : m_(m) {
    const auto box = m.boundingBox();
    lo_ = box.min().head<2>();
    nx_ = static_cast<int>((box.max().x() - lo_.x()) / kCell) + 1;
    ny_ = static_cast<int>((box.max().y() - lo_.y()) / kCell) + 1;
    cells_.resize(static_cast<size_t>(nx_) * ny_);
    for (int t = 0; t < m.numTriangles(); ++t) {
      Eigen::Vector2d a = m.vertices.col(m.triangles(0, t)).head<2>(), b = a;
      for (int k = 1; k < 3; ++k) {
        a = a.cwiseMin(m.vertices.col(m.triangles(k, t)).head<2>());
        b = b.cwiseMax(m.vertices.col(m.triangles(k, t)).head<2>());
      }
      for (int i = cell(a.x(), 0); i <= cell(b.x(), 0); ++i)
        for (int j = cell(a.y(), 1); j <= cell(b.y(), 1); ++j) cells_[static_cast<size_t>(i) * ny_ + j].push_back(t);
    }
  }
  bool inside(Eigen::Vector3d p) const {
    p.x() += 1.234567e-7, p.y() += 2.345671e-7;  // off any edge or vertex of the grid-free input
    if (p.x() < lo_.x() || p.y() < lo_.y()) return false;
    const int i = cell(p.x(), 0), j = cell(p.y(), 1);
    if (i >= nx_ || j >= ny_) return false;
    int crossings = 0;
    for (int t : cells_[static_cast<size_t>(i) * ny_ + j]) {
      const Eigen::Vector3d a = m_.vertices.col(m_.triangles(0, t)), b = m_.vertices.col(m_.triangles(1, t)),
                            c = m_.vertices.col(m_.triangles(2, t));
      const double d = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
      if (d == 0) continue;
      const double u = ((b.x() - p.x()) * (c.y() - p.y()) - (c.x() - p.x()) * (b.y() - p.y())) / d;
      const double v = ((c.x() - p.x()) * (a.y() - p.y()) - (a.x() - p.x()) * (c.y() - p.y())) / d;
      const double w = 1 - u - v;
      if (u < 0 || v < 0 || w < 0) continue;
      if (u * a.z() + v * b.z() + w * c.z() > p.z()) ++crossings;
    }
    return crossings % 2 == 1;
  }

 private:
  static constexpr double kCell = 2.0;
  int cell(double x, int axis) const { return std::max(0, static_cast<int>((x - lo_[axis]) / kCell)); }
  const SurfaceMesh& m_;
  Eigen::Vector2d lo_;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;
};

double minAngleDeg(const SurfaceMesh& m, int t) {
  double best = 180;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = m.vertices.col(m.triangles(k, t)), b = m.vertices.col(m.triangles((k + 1) % 3, t)),
                          c = m.vertices.col(m.triangles((k + 2) % 3, t));
    best = std::min(best, std::acos(std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0)) * 180 / kPi);
  }
  return best;
}

Eigen::Matrix3Xd columns(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Matrix3Xd m(3, pts.size());
  for (size_t i = 0; i < pts.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = pts[i];
  return m;
}

class PhantomVariants : public ::testing::TestWithParam<int> {};

// Contract 1: every surface of every variant is a valid closed solid, free of self-intersections,
// with decent triangles near the requested edge length.
TEST_P(PhantomVariants, SurfacesAreClosedOutwardAndEmbedded) {
  const Phantom& p = phantomOf(GetParam());
  std::vector<std::pair<std::string, const SurfaceMesh*>> surfaces = {
      {"skin", &p.skin}, {"mandible", &p.mandible}, {"oral cavity", &p.oralCavity}};
  // The skull is the same in every variant (VariantsDifferMeasurably checks that): test it once.
  if (GetParam() == 0) surfaces.emplace_back("skull", &p.skull);
  for (const auto& [name, s] : surfaces) {
    SurfaceMesh copy = *s;
    const SurfaceReport r = checkSurface(copy, name, SurfaceRequirement::Closed);  // throws on any defect
    EXPECT_TRUE(r.warnings.empty()) << name << ": " << (r.warnings.empty() ? "" : r.warnings.front());
    EXPECT_TRUE(r.closed() && r.manifold() && r.oriented()) << name;
    EXPECT_EQ(r.selfIntersections, 0) << name;
    EXPECT_GT(r.signedVolume, 0) << name;
    int thin = 0;
    double sum = 0, worst = 180;
    for (int t = 0; t < s->numTriangles(); ++t) {
      const double a = minAngleDeg(*s, t);
      thin += a < 15;
      worst = std::min(worst, a);
      for (int k = 0; k < 3; ++k)
        sum += (s->vertices.col(s->triangles(k, t)) - s->vertices.col(s->triangles((k + 1) % 3, t))).norm();
    }
    const double meanEdge = sum / (3.0 * s->numTriangles());
    EXPECT_GT(worst, 2.0) << name << ": a needle triangle";
    EXPECT_LT(thin, 0.025 * s->numTriangles()) << name << ": too many triangles under 15 degrees";
    EXPECT_GT(meanEdge, 1.1) << name;
    EXPECT_LT(meanEdge, 2.0) << name;
  }
  EXPECT_GE(p.skin.numTriangles(), 30000);
  EXPECT_LE(p.skin.numTriangles(), 80000);
  EXPECT_TRUE(p.skin.hasUv());
  EXPECT_GE(p.skin.uv.minCoeff(), 0.0);
  EXPECT_LE(p.skin.uv.maxCoeff(), 1.0);
}

// Contract 2 and 3: bones apart, mandible (and skull) inside the skin, bone well behind the face.
TEST_P(PhantomVariants, BonesAreApartAndInsideTheSkin) {
  const Phantom& p = phantomOf(GetParam());
  EXPECT_GE(distancesToSurface(p.skull.vertices, p.skull.triangles, p.mandible.vertices).minCoeff(), 1.0);
  EXPECT_GE(distancesToSurface(p.mandible.vertices, p.mandible.triangles, p.skull.vertices).minCoeff(), 1.0);
  const InsideTest skin(p.skin);
  for (int i = 0; i < p.mandible.numVertices(); ++i)
    ASSERT_TRUE(skin.inside(p.mandible.vertices.col(i))) << "mandible vertex " << i;
  for (int i = 0; i < p.skull.numVertices(); ++i)
    ASSERT_TRUE(skin.inside(p.skull.vertices.col(i))) << "skull vertex " << i;
  // The face: skin facing forward, in front of the ears.
  const Eigen::Matrix3Xd n = p.skin.vertexNormals();
  std::vector<Eigen::Vector3d> face;
  for (int i = 0; i < p.skin.numVertices(); ++i)
    if (n(0, i) < -0.5 && p.skin.vertices(0, i) < -40) face.push_back(p.skin.vertices.col(i));
  ASSERT_GT(face.size(), 1000u);
  const Eigen::Matrix3Xd f = columns(face);
  EXPECT_GE(distancesToSurface(p.skull.vertices, p.skull.triangles, f).minCoeff(), 4.0);
  EXPECT_GE(distancesToSurface(p.mandible.vertices, p.mandible.triangles, f).minCoeff(), 4.0);
}

// Contract 4: the oral cavity crosses the skin at the mouth and holds crowns of both arches.
TEST_P(PhantomVariants, OralCavityOpensTheMouthAndHoldsTheCrowns) {
  const Phantom& p = phantomOf(GetParam());
  const InsideTest skin(p.skin), skull(p.skull), mandible(p.mandible), cavity(p.oralCavity);
  int outsideSkin = 0, inSkull = 0, inMandible = 0;
  for (int i = 0; i < p.oralCavity.numVertices(); ++i) {
    const Eigen::Vector3d x = p.oralCavity.vertices.col(i);
    outsideSkin += !skin.inside(x);
    inSkull += skull.inside(x);
    inMandible += mandible.inside(x);
  }
  EXPECT_GT(outsideSkin, 20);
  EXPECT_GT(inSkull, 50);
  EXPECT_GT(inMandible, 50);
  // Crown tips stand in the air; the slit crosses the lips at the stomion and is thin there.
  for (const char* tip : {"upper_incisor_tip", "lower_incisor_tip", "upper_molar_left", "lower_molar_right"})
    EXPECT_TRUE(cavity.inside(hard(GetParam(), tip) +
                              Eigen::Vector3d(0, 0, std::string(tip).rfind("upper", 0) == 0 ? -0.2 : 0.2)))
        << tip;
  const Eigen::Vector3d st = soft(GetParam(), "stomion");
  EXPECT_TRUE(cavity.inside(st + Eigen::Vector3d(-3, 0, 0)));
  EXPECT_TRUE(cavity.inside(st + Eigen::Vector3d(3, 0, 0)));
  EXPECT_FALSE(cavity.inside(st + Eigen::Vector3d(1, 0, 1.5)));
  EXPECT_FALSE(cavity.inside(st + Eigen::Vector3d(1, 0, -1.5)));
  // Lips are tissue: inside the skin, outside the air, a few mm above and below the slit.
  for (double dz : {-3.0, -6.0, 3.0, 6.0}) {
    const Eigen::Vector3d q = st + Eigen::Vector3d(3, 0, dz);
    EXPECT_TRUE(skin.inside(q) && !cavity.inside(q)) << "lip at dz " << dz;
  }
}

// Contract 4: no tissue lies between the arches or around the upper crowns, from the midline to
// behind the second molars: tissue there would be sheared across the 1.5 mm occlusal gap by any
// move of one jaw against the other (a 5 mm Le Fort I then inverts elements).
TEST_P(PhantomVariants, EveryCrownStandsInTheAir) {
  const Phantom& p = phantomOf(GetParam());
  const InsideTest cavity(p.oralCavity);
  const double sEnd = phantom::upperTeeth().back().end;
  for (double s = -sEnd + 0.5; s <= sEnd - 0.5; s += 1.0) {
    const Eigen::Vector3d tip = phantom::upperCrownTip(s);
    for (double dz : {-0.75, 0.0, 3.0})
      EXPECT_TRUE(cavity.inside(tip + Eigen::Vector3d(0, 0, dz)))
          << "arch length " << s << " mm, " << dz << " mm above the tip";
  }
}

// Contract 4: one tissue volume with no thin parts: bone and air keep 3 mm from the skin, except
// where the air leaves through the mouth slit.
TEST_P(PhantomVariants, TissueIsNowhereThin) {
  const Phantom& p = phantomOf(GetParam());
  const Eigen::Vector3d st = soft(GetParam(), "stomion");
  const InsideTest skin(p.skin);
  std::vector<Eigen::Vector3d> away;  // air inside the skin, away from the lips
  for (int i = 0; i < p.oralCavity.numVertices(); ++i) {
    const Eigen::Vector3d x = p.oralCavity.vertices.col(i);
    const bool atMouth = x.x() < st.x() + 12 && std::abs(x.z() - st.z()) < 8 && std::abs(x.y()) < 30;
    if (!atMouth && skin.inside(x)) away.push_back(x);
  }
  ASSERT_GT(away.size(), 1000u);
  // One query against the skin for bone and air together.
  const int ns = p.skull.numVertices(), nm = p.mandible.numVertices();
  Eigen::Matrix3Xd q(3, ns + nm + static_cast<int>(away.size()));
  q << p.skull.vertices, p.mandible.vertices, columns(away);
  const Eigen::VectorXd d = distancesToSurface(p.skin.vertices, p.skin.triangles, q);
  EXPECT_GE(d.head(ns).minCoeff(), 3.0) << "skull";
  EXPECT_GE(d.segment(ns, nm).minCoeff(), 3.0) << "mandible";
  EXPECT_GE(d.tail(static_cast<Eigen::Index>(away.size())).minCoeff(), 3.0) << "oral cavity";
}

// Contract 5: landmarks sit on their surfaces.
TEST_P(PhantomVariants, LandmarksLieOnTheirSurfaces) {
  const Phantom& p = phantomOf(GetParam());
  Eigen::Matrix3Xd h(3, p.hardLandmarks.size()), s(3, p.softLandmarks.size());
  for (size_t i = 0; i < p.hardLandmarks.size(); ++i) h.col(static_cast<Eigen::Index>(i)) = p.hardLandmarks[i].position;
  for (size_t i = 0; i < p.softLandmarks.size(); ++i) s.col(static_cast<Eigen::Index>(i)) = p.softLandmarks[i].position;
  const Eigen::VectorXd ds = distancesToSurface(p.skull.vertices, p.skull.triangles, h);
  const Eigen::VectorXd dm = distancesToSurface(p.mandible.vertices, p.mandible.triangles, h);
  const Eigen::VectorXd dskin = distancesToSurface(p.skin.vertices, p.skin.triangles, s);
  for (size_t i = 0; i < p.hardLandmarks.size(); ++i) {
    const Landmark& l = p.hardLandmarks[i];
    if (l.name.find("apex") != std::string::npos) {  // root tips: inside the bone
      const bool upper = l.name.rfind("upper", 0) == 0;
      EXPECT_TRUE(InsideTest(upper ? p.skull : p.mandible).inside(l.position)) << l.name;
      EXPECT_GT(upper ? ds[i] : dm[i], 1.5) << l.name;
      continue;
    }
    EXPECT_LT(std::min(ds[i], dm[i]), 0.5) << l.name;
  }
  for (size_t i = 0; i < p.softLandmarks.size(); ++i) EXPECT_LT(dskin[i], 0.5) << p.softLandmarks[i].name;
  EXPECT_EQ(p.hardLandmarks.size(), 27u);
  EXPECT_EQ(p.softLandmarks.size(), 12u);
}

INSTANTIATE_TEST_SUITE_P(AllVariants, PhantomVariants, ::testing::Values(0, 1, 2, 3, 4),
                         [](const auto& info) { return "variant" + std::to_string(info.param); });

// Contract 5: class I dimensions within the clinical primer's bands.
TEST(Phantom, ClassIDimensionsArePlausible) {
  const int v = 0;
  EXPECT_NEAR(hard(v, "condylion_left").y(), -hard(v, "condylion_right").y(), 1e-9);
  const double lowerFace = (soft(v, "soft_menton") - soft(v, "subnasale")).norm();
  EXPECT_GE(lowerFace, 60);
  EXPECT_LE(lowerFace, 80);
  const double bigonial = (hard(v, "gonion_left") - hard(v, "gonion_right")).norm();
  EXPECT_GE(bigonial, 85);
  EXPECT_LE(bigonial, 105);
  const double intercondylar = (hard(v, "condylion_left") - hard(v, "condylion_right")).norm();
  EXPECT_GE(intercondylar, 90);
  EXPECT_LE(intercondylar, 110);
  for (const char* side : {"left", "right"}) {
    const double ramus = (hard(v, std::string("condylion_") + side) - hard(v, std::string("gonion_") + side)).norm();
    EXPECT_GE(ramus, 45) << side;
    EXPECT_LE(ramus, 65) << side;
  }
  const double chin = (soft(v, "soft_pogonion") - hard(v, "pogonion")).norm();
  EXPECT_GE(chin, 9);
  EXPECT_LE(chin, 15);
  const Phantom& p = phantomOf(v);
  const double lip =
      distancesToSurface(p.skull.vertices, p.skull.triangles, Eigen::Matrix3Xd(soft(v, "labrale_superius")))[0];
  EXPECT_GE(lip, 10);
  EXPECT_LE(lip, 17);
  const double overjet = hard(v, "lower_incisor_tip").x() - hard(v, "upper_incisor_tip").x();
  EXPECT_GE(overjet, 1.5);
  EXPECT_LE(overjet, 4.0);
  const double bite = hard(v, "upper_incisor_tip").z() - hard(v, "lower_incisor_tip").z();
  EXPECT_GE(bite, 1.0);
  EXPECT_LE(bite, 2.5);
  // Face width: the skin's breadth in front of the ears.
  double half = 0;
  for (int i = 0; i < p.skin.numVertices(); ++i)
    if (p.skin.vertices(0, i) < -30) half = std::max(half, std::abs(p.skin.vertices(1, i)));
  EXPECT_GE(2 * half, 120);
  EXPECT_LE(2 * half, 145);
  // Profile order: the nose ahead of the lips, the lips ahead of the chin's fold.
  EXPECT_LT(soft(v, "pronasale").x(), soft(v, "labrale_superius").x() - 15);
  EXPECT_GT(soft(v, "subnasale").z(), soft(v, "stomion").z() + 15);
  EXPECT_GT(soft(v, "stomion").z(), soft(v, "soft_pogonion").z() + 20);
  const double mouth = (soft(v, "mouth_corner_left") - soft(v, "mouth_corner_right")).norm();
  EXPECT_GE(mouth, 44);
  EXPECT_LE(mouth, 52);
}

// The variants differ where they should, and only there.
TEST(Phantom, VariantsDifferMeasurably) {
  auto overjet = [](int v) { return hard(v, "lower_incisor_tip").x() - hard(v, "upper_incisor_tip").x(); };
  EXPECT_GT(overjet(1), 5.0);                                                 // class II
  EXPECT_LT(overjet(2), 0.0);                                                 // class III: lower incisors ahead
  EXPECT_LT(soft(2, "soft_pogonion").x(), soft(0, "soft_pogonion").x() - 3);  // the chin follows
  EXPECT_GT(soft(1, "soft_pogonion").x(), soft(0, "soft_pogonion").x() + 3);
  EXPECT_NEAR(hard(0, "pogonion").y(), 0.0, 1e-9);
  EXPECT_GT(hard(3, "pogonion").y(), 4.0);  // asymmetric: chin to the right
  EXPECT_GT(soft(3, "soft_pogonion").y(), 4.0);
  auto lowerFace = [](int v) { return (soft(v, "soft_menton") - soft(v, "subnasale")).norm(); };
  EXPECT_GT(lowerFace(4), lowerFace(0) + 4.0);                                          // long face
  EXPECT_GT(hard(4, "upper_incisor_tip").z() - hard(4, "lower_incisor_tip").z(), 3.5);  // open bite
  for (int v = 1; v < 5; ++v) {  // the maxilla is the same in every variant
    EXPECT_EQ(phantomOf(v).skull.vertices, phantomOf(0).skull.vertices);
    EXPECT_LT((hard(v, "condylion_right") - hard(0, "condylion_right")).norm(), 0.5) << v;  // condyles stay
  }
}

TEST(Phantom, IsDeterministic) {
  const Phantom a = makePhantom({0, 1.5});
  const Phantom& b = phantomOf(0);
  for (auto [x, y] : {std::pair{&a.skin, &b.skin},
                      {&a.skull, &b.skull},
                      {&a.mandible, &b.mandible},
                      {&a.oralCavity, &b.oralCavity}}) {
    EXPECT_EQ(x->vertices, y->vertices);  // bit for bit
    EXPECT_EQ(x->triangles, y->triangles);
    EXPECT_EQ(x->uv, y->uv);
  }
  ASSERT_EQ(a.hardLandmarks.size(), b.hardLandmarks.size());
  for (size_t i = 0; i < a.hardLandmarks.size(); ++i)
    EXPECT_EQ(a.hardLandmarks[i].position, b.hardLandmarks[i].position);
  EXPECT_EQ(a.skinTexture.pixels, b.skinTexture.pixels);
}

TEST(Phantom, ScalesWithEdgeLength) {
  const Phantom coarse = makePhantom({0, 3.0});
  // Four times the edge area: about a quarter of the triangles.
  const double ratio = static_cast<double>(phantomOf(0).skin.numTriangles()) / coarse.skin.numTriangles();
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.0);
  SurfaceMesh s = coarse.mandible;
  EXPECT_NO_THROW(checkSurface(s, "coarse mandible", SurfaceRequirement::Closed));
}

// How fast (label perf): a coarse phantom is built in seconds.
TEST(PhantomPerf, ACoarsePhantomIsBuiltInUnderFiveSeconds) {
  const auto t0 = std::chrono::steady_clock::now();
  const Phantom coarse = makePhantom({0, 3.0});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(seconds, 5.0);
  EXPECT_GT(coarse.skin.numTriangles(), 0);
}

TEST(Phantom, TextureShowsLipsOnSkin) {
  const Phantom& p = phantomOf(0);
  const RgbImage& t = p.skinTexture;
  ASSERT_EQ(t.width, 1024);
  ASSERT_EQ(t.height, 1024);
  ASSERT_EQ(t.pixels.size(), 1024u * 1024u * 3u);
  // Colour at a landmark's texture coordinates (nearest skin vertex).
  auto colourAt = [&](const Eigen::Vector3d& x) {
    int best = 0;
    for (int i = 0; i < p.skin.numVertices(); ++i)
      if ((p.skin.vertices.col(i) - x).squaredNorm() < (p.skin.vertices.col(best) - x).squaredNorm()) best = i;
    const int col = std::min(1023, static_cast<int>(p.skin.uv(0, best) * 1024));
    const int row = std::min(1023, static_cast<int>((1 - p.skin.uv(1, best)) * 1024));
    const unsigned char* c = &t.pixels[(static_cast<size_t>(row) * 1024 + col) * 3];
    return Eigen::Vector3d(c[0], c[1], c[2]);
  };
  const Eigen::Vector3d lip = colourAt(soft(0, "labrale_inferius")), cheek = colourAt(soft(0, "cheek_left"));
  EXPECT_GT(lip.x() - lip.y(), cheek.x() - cheek.y() + 25);  // redder
  EXPECT_GT(cheek.x(), 180);                                 // light skin tone
}

TEST(Phantom, WritesFilesThatReadBack) {
  const Phantom& p = phantomOf(0);
  const fs::path dir = fs::temp_directory_path() / ("orthosim_phantom_" + std::to_string(::getpid())) / "nested";
  writePhantom(p, dir.string());
  const SurfaceMesh skin = importSurface((dir / "skin.obj").string());
  EXPECT_EQ(skin.numVertices(), p.skin.numVertices());
  EXPECT_EQ(skin.numTriangles(), p.skin.numTriangles());
  ASSERT_TRUE(skin.hasUv());
  double uvError = 0;  // corner by corner: the reader may number the vertices differently
  for (int t = 0; t < skin.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      uvError = std::max(
          uvError, (skin.uv.col(skin.triangles(k, t)) - p.skin.uv.col(p.skin.triangles(k, t))).cwiseAbs().maxCoeff());
  EXPECT_LT(uvError, 1e-6);
  for (auto [file, mesh] :
       {std::pair{"skull.stl", &p.skull}, {"mandible.stl", &p.mandible}, {"oral_cavity.stl", &p.oralCavity}}) {
    const SurfaceMesh m = importSurface((dir / file).string());
    EXPECT_EQ(m.numVertices(), mesh->numVertices()) << file;
    EXPECT_EQ(m.numTriangles(), mesh->numTriangles()) << file;
  }
  std::ifstream jpg(dir / "skin.jpg", std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(jpg)), {});
  ASSERT_GT(bytes.size(), 10000u);
  EXPECT_EQ(bytes[0], 0xFF);
  EXPECT_EQ(bytes[1], 0xD8);
  std::ifstream js(dir / "landmarks.json");
  const nlohmann::json j = nlohmann::json::parse(js);
  EXPECT_EQ(j["hard"].size(), p.hardLandmarks.size());
  EXPECT_EQ(j["soft"].size(), p.softLandmarks.size());
  EXPECT_DOUBLE_EQ(j["hard"]["menton"][2].get<double>(), hard(0, "menton").z());
  fs::remove_all(dir.parent_path());
}

TEST(Phantom, RefusesBadOptionsClearly) {
  try {
    makePhantom({7, 1.5});
    FAIL() << "variant 7 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown variant 7"), std::string::npos) << e.what();
  }
  EXPECT_THROW(makePhantom({-1, 1.5}), std::invalid_argument);
  EXPECT_THROW(makePhantom({0, 0.0}), std::invalid_argument);
  EXPECT_THROW(makePhantom({0, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(makePhantom({0, 50.0}), std::invalid_argument);
  // A file where the directory should go.
  const fs::path blocker = fs::temp_directory_path() / ("orthosim_phantom_blocker_" + std::to_string(::getpid()));
  std::ofstream(blocker) << "x";
  try {
    writePhantom(phantomOf(0), (blocker / "dir").string());
    FAIL() << "wrote under a file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos) << e.what();
  }
  fs::remove(blocker);
}

}  // namespace
}  // namespace orthosim
