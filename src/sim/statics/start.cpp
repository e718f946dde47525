// The start of the steady solve (docs/theory.md §7 "Sweeps"): each element
// along the force it carries, then laid on the seabed when there is one.
#include <cmath>

#include "problem.hpp"
#include "strategies.hpp"
#include "towsim/hydro/loads.hpp"

namespace towsim::statics {

namespace {

/// From the bottom up, each element aligned with the force it carries
/// (moment balance about its top joint, its own load at mid-length); a body
/// passes on the force balancing its own loads, an attachment its load.
void align_from_bottom(SteadyProblem& p) {
  const Model& m = p.model;
  PhysicalState& s = p.base;
  s = PhysicalState::hanging(m);
  s.r0 = m.tow.start;
  s.v0 = p.V;
  // Bodies start facing the tow's heading: their initial attitude is taken
  // relative to it (a fish towed along +y starts yawed 90 deg), so that any
  // heading converges to the body flying nose first.
  if (std::hypot(p.V.x(), p.V.y()) > 0) {
    const Quat heading(Eigen::AngleAxisd(std::atan2(p.V.y(), p.V.x()), Vec3::UnitZ()));
    for (auto& b : s.bodies) b.q = (heading * b.q).normalized();
  }
  compute_kinematics(m, s, p.ws);  // depths of the hanging guess (for a current profile)
  for (auto& v : p.ws.vP) v = p.V;
  attachment_loads(m, 0.0, p.ws);
  Vec3 f = -p.ws.Fa.back();  // force through the joint below the element
  for (int k = p.n - 1; k >= 0; --k) {
    const int bi = p.ws.body_at[static_cast<std::size_t>(k + 1)];
    if (bi >= 0) {
      BodyWork& bw = p.ws.body[static_cast<std::size_t>(bi)];
      bw.vO = p.V;
      bw.w.setZero();
      body_loads(m.fluid, m.bodies[static_cast<std::size_t>(bi)], 0.0, bw);
      f -= bw.Fb;  // link force balancing the body's loads and the cable below
    }
    const Element& el = m.cable.elements[static_cast<std::size_t>(k)];
    Vec3 e = s.e[static_cast<std::size_t>(k)], F, M;
    for (int it = 0; it < 30; ++it) {
      element_loads(m, el, e, Vec3::Zero(), p.V, p.ws.G[static_cast<std::size_t>(k)], 0.0, F, M);
      const Vec3 d = 0.5 * F - f;
      if (d.norm() < 1e-300) break;
      e = d.normalized();
    }
    s.e[static_cast<std::size_t>(k)] = e;
    f -= F + p.ws.Fa[static_cast<std::size_t>(k)];
  }
}

}  // namespace

Start lay_start(SteadyProblem& p) {
  // Each element along the force it carries.
  align_from_bottom(p);
  // On a seabed: the dragged-cable start, else the chain laid on the bottom.
  Start start = Start::Aligned;
  if (lay_along_bottom(p))
    start = Start::DraggedCable;
  else if (lay_on_seabed(p))
    start = Start::BodyTurnedOnSeabed;
  else if (p.model.seabed)
    start = Start::LaidOnSeabed;
  p.accept(Eigen::VectorXd::Zero(p.size()));
  return start;
}

}  // namespace towsim::statics
