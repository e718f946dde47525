// Seabed contact on the cable (at its joints, or along its elements) and at
// the bodies' hull points (docs/theory.md §3.2; the contact law:
// towsim/model/seabed.hpp, along a segment: towsim/model/seabed_segment.hpp).
#include "towsim/hydro/loads.hpp"

#include <algorithm>

namespace towsim {

namespace {

/// Add a contact force f at the body point p [m, R_g] to the body's loads.
void add_body_contact(BodyWork& bw, const Vec3& p, const Vec3& f) {
  bw.Fb += f;
  bw.Mb += (p - bw.O).cross(f);
}

/// The contact of each hull point of one body (hull_points).
void hull_contact(const Seabed& sb, const Body& body, BodyWork& bw, double& normal, double& friction) {
  hull_points(sb, body, bw, [&](const Vec3& p, double length) {
    const SeabedForce f = sb.contact(p, bw.vO + bw.w.cross(p - bw.O), length);
    if (f.length > 0) add_body_contact(bw, p, f.total());
    normal += f.normal.norm();
    friction += f.friction.norm();
  });
}

}  // namespace

SegmentContact element_seabed_contact(const Model& model, const Workspace& ws, std::size_t k) {
  const int bi = ws.body_at[k + 1];
  const BodyWork* q = bi >= 0 && model.bodies[static_cast<std::size_t>(bi)].inline_body
                          ? &ws.body[static_cast<std::size_t>(bi)]
                          : nullptr;
  const Element& e = model.cable.elements[k];
  return segment_contact(*model.seabed, ws.P[k], ws.vP[k], q ? q->Q : ws.P[k + 1], q ? q->vQ : ws.vP[k + 1],
                         model.seabed->rest_sink(e.weight / e.length));
}

namespace {

/// The joint law: each joint P_k below the bottom carries the contact of
/// half of each adjacent element, added to ws.Fa[k] (the end body's Fb at Q;
/// an in-line body's upper link Q carries the half-element above).
void joint_contact(const Model& model, const Seabed& sb, Workspace& ws) {
  const auto& els = model.cable.elements;
  const std::size_t n = els.size();
  auto account = [&](const SeabedForce& f) {
    ws.seabed_normal += f.normal.norm();
    ws.seabed_friction += f.friction.norm();
  };
  for (std::size_t k = 0; k <= n; ++k) {
    const int bi = k > 0 ? ws.body_at[k] : -1;
    const Body* body = bi >= 0 ? &model.bodies[static_cast<std::size_t>(bi)] : nullptr;
    // At P_k: half of the element below, and half of the one above unless a
    // body separates them (an in-line body's Q2, or the end body's Q).
    double l = k < n ? 0.5 * els[k].length : 0.0;
    if (k > 0 && !(body && body->inline_body)) l += 0.5 * els[k - 1].length;
    const SeabedForce f = sb.contact(ws.P[k], ws.vP[k], l);
    ws.Fs[k] = f.total();
    ws.ls[k] = f.length;
    account(f);
    if (body && !body->inline_body) {
      BodyWork& bw = ws.body[static_cast<std::size_t>(bi)];
      if (f.length > 0) add_body_contact(bw, ws.P[k], ws.Fs[k]);
    } else {
      ws.Fa[k] += ws.Fs[k];
    }
    if (body && body->inline_body) {
      // The half-element above ends at the body's upper link Q.
      BodyWork& bw = ws.body[static_cast<std::size_t>(bi)];
      const SeabedForce fq = sb.contact(bw.Q, bw.vQ, 0.5 * els[k - 1].length);
      bw.Fs_q = fq.total();
      bw.ls_q = fq.length;
      if (fq.length > 0) add_body_contact(bw, bw.Q, bw.Fs_q);
      account(fq);
    }
  }
}

/// The law along elements: each element's contact (element_seabed_contact)
/// as a force at G and a couple in its loads; its end shares in ws.Fs, ws.ls
/// (BodyWork's Fs_q, ls_q at an in-line body's Q) for the outputs and the
/// stage solve's local Jacobian only.
void element_contact(const Model& model, Workspace& ws) {
  std::fill(ws.Fs.begin(), ws.Fs.end(), Vec3::Zero());
  std::fill(ws.ls.begin(), ws.ls.end(), 0.0);
  for (BodyWork& bw : ws.body) bw.Fs_q.setZero(), bw.ls_q = 0;
  for (std::size_t k = 0; k < model.cable.elements.size(); ++k) {
    const SegmentContact c = element_seabed_contact(model, ws, k);
    if (c.length <= 0) continue;
    const int bi = ws.body_at[k + 1];
    BodyWork* q = bi >= 0 && model.bodies[static_cast<std::size_t>(bi)].inline_body
                      ? &ws.body[static_cast<std::size_t>(bi)]
                      : nullptr;
    ws.F[k] += c.total();
    ws.Mom[k] += c.moment(ws.P[k], q ? q->Q : ws.P[k + 1], ws.G[k]);
    ws.seabed_normal += c.normal;
    ws.seabed_friction += c.friction.norm();
    ws.Fs[k] += c.at_a;
    ws.ls[k] += c.length_a;
    (q ? q->Fs_q : ws.Fs[k + 1]) += c.at_b;
    (q ? q->ls_q : ws.ls[k + 1]) += c.length_b;
  }
}

}  // namespace

void seabed_loads(const Model& model, Workspace& ws) {
  ws.seabed_normal = ws.seabed_friction = 0;
  if (!model.seabed) return;
  const Seabed& sb = *model.seabed;
  if (sb.along_elements)
    element_contact(model, ws);
  else
    joint_contact(model, sb, ws);
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    hull_contact(sb, model.bodies[b], ws.body[b], ws.seabed_normal, ws.seabed_friction);
}

double seabed_normal_stiffness(const Model& model, const Workspace& ws, int k) {
  if (!model.seabed || k < 0 || static_cast<std::size_t>(k) >= ws.ls.size()) return 0.0;
  return model.seabed->stiffness * ws.ls[static_cast<std::size_t>(k)];
}

}  // namespace towsim
