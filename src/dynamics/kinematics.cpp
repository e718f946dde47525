// Kinematics of the chain and its bodies from a physical state (docs/theory.md §2, §4).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "towsim/dynamics/state.hpp"

namespace towsim {

Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

PhysicalState PhysicalState::hanging(const Model& model) {
  PhysicalState s;
  s.e.assign(model.cable.elements.size(), -Vec3::UnitZ());
  s.w.assign(model.cable.elements.size(), Vec3::Zero());
  s.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    s.bodies[b].q = model.bodies[b].initial_attitude;
    // Depth controllers start with no integral, at their initial deflection.
    for (const LiftingSurface& ls : model.bodies[b].surfaces)
      if (ls.depth_control) s.bodies[b].controls.push_back({0.0, ls.depth_control->initial_deflection});
  }
  for (const Element& el : model.cable.elements) s.length.push_back(el.length);
  s.length_rate.assign(model.cable.elements.size(), 0.0);
  if (elastic_winch(model)) s.top_unstretched = model.cable.elements.front().length;
  return s;
}

bool lengths_in_state(const Model& model) {
  return std::any_of(model.cable.elements.begin(), model.cable.elements.end(), is_elastic);
}

Workspace::Workspace(const Model& model) {
  const std::size_t n = model.cable.elements.size();
  // Every entry starts at zero: no evaluation ever reads an unset value.
  for (auto* v : {&P, &vP, &b, &Fa, &Fs, &bend}) v->assign(n + 1, Vec3::Zero());
  ls.assign(n + 1, 0.0);
  for (auto* v : {&G, &vG, &edot, &F, &Mom, &Uw, &c}) v->assign(n, Vec3::Zero());
  L.assign(n, 0.0);
  Mt.assign(n, Mat3::Zero());
  Ma.assign(n + 1, Mat3::Zero());
  K.assign(n + 1, Mat3::Zero());
  T.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  GT.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  H.assign(n, Eigen::Matrix<double, 3, 2>::Zero());
  Phi.assign(n, Eigen::Matrix2d::Zero());
  Tr0.assign(n, Eigen::Vector2d::Zero());
  elastic.assign(n, ElasticWork{});
  body.resize(model.bodies.size());
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    body[i].deflection.assign(static_cast<std::size_t>(control_count(model.bodies[i])), 0.0);
  body_at.assign(n + 1, -1);
  bending = std::any_of(model.cable.elements.begin(), model.cable.elements.end(),
                        [](const Element& el) { return el.bending_stiffness > 0; });
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    body_at[static_cast<std::size_t>(body_joint(model, model.bodies[i]))] = static_cast<int>(i);
  acc.alpha.assign(n, Vec3::Zero());
  acc.length_acc.assign(n, 0.0);
  acc.joint_force.assign(n + 1, Vec3::Zero());
  acc.alpha_b.assign(model.bodies.size(), Vec3::Zero());
  acc.link_force.assign(model.bodies.size(), Vec3::Zero());
  acc.lower_link_force.assign(model.bodies.size(), Vec3::Zero());
}

bool Workspace::fits(const Model& model) const {
  const std::size_t n = model.cable.elements.size();
  return P.size() == n + 1 && G.size() == n && K.size() == n + 1 && Phi.size() == n &&
         body.size() == model.bodies.size() && acc.alpha.size() == n && acc.link_force.size() == model.bodies.size() &&
         body_at.size() == n + 1 && std::all_of(model.bodies.begin(), model.bodies.end(), [&](const Body& b) {
           const int k = body_joint(model, b);
           return k >= 1 && k <= static_cast<int>(n) &&
                  body.size() > static_cast<std::size_t>(body_at[static_cast<std::size_t>(k)]) &&
                  body_at[static_cast<std::size_t>(k)] >= 0;
         });
}

namespace {
/// Body b hangs at joint k from Q = (P, vP): its origin, attitude and, for an
/// in-line body, the lower link Q2 from which the next element hangs.
void body_kinematics(const Body& body, const BodyState& bs, const Vec3& Q, const Vec3& vQ, BodyWork& bw) {
  bw.R = bs.q.toRotationMatrix();
  bw.w = bs.w;
  bw.Q = Q;
  bw.vQ = vQ;
  bw.rQ = bw.R * body.link_point;
  bw.O = Q - bw.rQ;
  bw.vO = vQ - bs.w.cross(bw.rQ);
  bw.rQ2 = bw.R * body.lower_link_point;
  for (BodyChild& c : bw.children) c.r = bw.R * c.point;  // lines hanging from its points
  // Controlled surfaces: the servo's deflection within the limits.
  std::size_t c = 0;
  for (const LiftingSurface& ls : body.surfaces)
    if (ls.depth_control) bw.deflection[c] = applied_deflection(*ls.depth_control, bs.controls[c]), ++c;
}
}  // namespace

void compute_kinematics(const Model& model, const PhysicalState& s, Workspace& ws) {
  compute_kinematics(model, s, s.r0, s.v0, ws);
}

void compute_kinematics(const Model& model, const PhysicalState& s, const Vec3& r0, const Vec3& v0, Workspace& ws) {
  const auto& els = model.cable.elements;
  // Joints and centres down the chain: P_k = P_{k-1} + d_k, d_k = l_k e_k,
  // d_k' = l_k' e_k + l_k e_k' (l_k = L_k, l_k' = 0 for an inextensible
  // element); at a body, the chain goes on from its lower link Q2 (in-line)
  // or ends (end body).
  ws.P[0] = r0;
  ws.vP[0] = v0;
  // Winch: the top element's material is fixed to its bottom joint and
  // leaves the sheave at v_0 + l' e_1; its properties scale with l_1.
  ws.winch = model.winch.active() && !els.empty();
  const bool elastic_top = ws.winch && is_elastic(els[0]);
  if (elastic_top) {
    // Elastic: material of unstretched length L_1, stretched uniformly to
    // l_1; the sheave pays out L_1' of it, l_1/L_1 L_1' of stretched length.
    ws.top = scaled_element(els[0], s.top_unstretched);
    ws.v_top = v0 + element_length(model, s, 0) / s.top_unstretched * s.top_unstretched_rate * s.e[0];
  } else if (ws.winch) {
    ws.top = scaled_element(els[0], element_length(model, s, 0));
    ws.v_top = v0 + element_length_rate(s, 0) * s.e[0];
  }
  // The arrays' data through local pointers, the joint above in locals: the
  // compiler cannot tell that the vectors' stores leave the vectors
  // themselves alone, and would reload each one's start per element.
  Vec3 *P = ws.P.data(), *vP = ws.vP.data(), *G = ws.G.data(), *vG = ws.vG.data(), *edot = ws.edot.data();
  double* Ls = ws.L.data();
  const Vec3 *e = s.e.data(), *w = s.w.data();
  const int* body_at = ws.body_at.data();
  const double* lengths = s.length.data();
  const double* rates = s.length_rate.data();
  const std::size_t n_lengths = s.length.size(), n_rates = s.length_rate.size();
  Vec3 p = P[0], vp = vP[0];  // P_k, its velocity [m], [m/s]
  for (std::size_t i = 0; i < els.size(); ++i) {
    // s.length_of(model, i) and s.length_rate_of(i).
    const double L = Ls[i] = i < n_lengths ? lengths[i] : els[i].length, Ld = i < n_rates ? rates[i] : 0.0;
    const Vec3 ed = edot[i] = w[i].cross(e[i]);
    const Vec3 dd = L * ed + Ld * e[i];  // d_k'
    G[i] = p + 0.5 * L * e[i];
    Vec3 vp1;  // vP_{k+1}
    if (i == 0 && elastic_top) {
      // Winch, elastic: material velocity linear from the sheave's to P_1's.
      vp1 = vp + dd;
      vG[i] = 0.5 * (ws.v_top + vp1);
    } else if (i == 0 && ws.winch) {
      // Winch: material moves rigidly with the bottom joint (not stretched).
      vG[i] = ws.v_top + 0.5 * L * ed;
      vp1 = ws.v_top + L * ed;
    } else {
      vG[i] = vp + 0.5 * dd;
      vp1 = vp + dd;
    }
    vP[i + 1] = vp = vp1;
    P[i + 1] = p = p + L * e[i];
    const int b = body_at[i + 1];
    if (b < 0) continue;
    BodyWork& bw = ws.body[static_cast<std::size_t>(b)];
    body_kinematics(model.bodies[static_cast<std::size_t>(b)], s.bodies[static_cast<std::size_t>(b)], ws.P[i + 1],
                    ws.vP[i + 1], bw);
    if (!model.bodies[static_cast<std::size_t>(b)].inline_body) continue;
    P[i + 1] = p = bw.O + bw.rQ2;
    vP[i + 1] = vp = bw.vO + bw.w.cross(bw.rQ2);
  }
}

double kinetic_energy(const Model& model, const PhysicalState& s, const Workspace& ws) {
  double E = 0;
  // Elements: translation of G (added mass normal to e) and rotation about G.
  for (std::size_t k = 0; k < s.e.size(); ++k) {
    const Element& el = current_element(model, ws, k);
    E += 0.5 * ws.vG[k].dot(ws.Mt[k] * ws.vG[k]) + 0.5 * (el.inertia + el.added_inertia) * s.w[k].squaredNorm();
  }
  // Attachments move with their joint.
  for (std::size_t k = 0; k < ws.Ma.size(); ++k) E += 0.5 * ws.vP[k].dot(ws.Ma[k] * ws.vP[k]);
  // Bodies: 1/2 nu^T M nu about O_t (rigid and added mass, R_g).
  for (std::size_t b = 0; b < ws.body.size(); ++b) {
    Vec6 nu;
    nu << ws.body[b].vO, ws.body[b].w;
    E += 0.5 * nu.dot(ws.body[b].Mw * nu);
  }
  return E;
}

Vec3 roll_pitch_yaw(const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  // R = Rz(yaw) Ry(pitch) Rx(roll): R(2,0) = -sin(pitch).
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  // Roll and yaw in (-pi, pi]: atan2 of a round-off zero gives +pi or -pi by
  // the zero's sign, so an attitude on the cut (a planar tow past pitch -90
  // degrees) reads +pi always, in both formulations (kCut: above round-off).
  constexpr double kCut = 1e-9;  // [rad]
  auto wrap = [](double a) { return a <= -std::numbers::pi + kCut ? a + 2 * std::numbers::pi : a; };
  const double roll = wrap(std::atan2(R(2, 1), R(2, 2)));
  const double yaw = wrap(std::atan2(R(1, 0), R(0, 0)));
  return Vec3(roll, pitch, yaw);
}

Quat quat_from_rpy(double roll, double pitch, double yaw) {
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

}  // namespace towsim
