#include "scene/BondedContact.hpp"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "mesh/SurfaceDistance.hpp"

namespace orthosim {

ContactGaps contactGaps(const Scene& scene) {
  ContactGaps gaps;
  std::map<int, int> slot;  // node -> index in gaps
  for (const ContactSpec& c : scene.contacts)
    for (int n : c.nodes)
      if (slot.emplace(n, static_cast<int>(gaps.nodes.size())).second) {
        gaps.nodes.push_back(n);
        gaps.distance.push_back(std::numeric_limits<double>::infinity());
        gaps.contact.push_back(-1);
      }
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(gaps.nodes.size()));
  for (size_t k = 0; k < gaps.nodes.size(); ++k)
    points.col(static_cast<Eigen::Index>(k)) = scene.mesh.rest.col(gaps.nodes[k]);
  for (size_t c = 0; c < scene.contacts.size(); ++c) {
    const ContactSpec& contact = scene.contacts[c];
    if (contact.nodes.empty()) continue;
    const Eigen::VectorXd d = distancesToSurface(contact.surface.vertices, contact.surface.triangles, points);
    // Only this contact's own nodes may bond to its surface (the case gave it those in range).
    for (int n : contact.nodes) {
      const int k = slot.at(n);
      if (d[k] < gaps.distance[static_cast<size_t>(k)]) {
        gaps.distance[static_cast<size_t>(k)] = d[k];
        gaps.contact[static_cast<size_t>(k)] = static_cast<int>(c);
      }
    }
  }
  return gaps;
}

BondedContactReport bondTouchingContactNodes(Scene& scene, double touchDistance) {
  if (!(touchDistance >= 0) || !std::isfinite(touchDistance))
    throw std::invalid_argument("bonded contact: the touch distance must be a finite distance >= 0 mm");
  BondedContactReport report;
  const ContactGaps gaps = contactGaps(scene);
  report.contactNodes = static_cast<int>(gaps.nodes.size());
  report.restDistances = gaps.distance;
  std::set<int> bonded;
  for (size_t k = 0; k < gaps.nodes.size(); ++k) {
    if (gaps.distance[k] > touchDistance) continue;
    const ContactSpec& c = scene.contacts[static_cast<size_t>(gaps.contact[k])];
    const std::optional<int> f = scene.fragmentIndex(c.fragment);
    if (!f)
      throw std::invalid_argument("bonded contact: contact '" + c.name +
                                  "' moves with no fragment, so its nodes have nothing to bond to");
    scene.fragments[static_cast<size_t>(*f)].nodes.push_back(gaps.nodes[k]);
    bonded.insert(gaps.nodes[k]);
  }
  report.bonded = static_cast<int>(bonded.size());
  for (ContactSpec& c : scene.contacts)
    c.nodes.erase(std::remove_if(c.nodes.begin(), c.nodes.end(), [&](int n) { return bonded.count(n) > 0; }),
                  c.nodes.end());
  scene.contacts.erase(std::remove_if(scene.contacts.begin(), scene.contacts.end(),
                                      [](const ContactSpec& c) { return c.nodes.empty(); }),
                       scene.contacts.end());
  return report;
}

}  // namespace orthosim
