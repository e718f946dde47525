#include "towsim/output/output.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "towsim/version.hpp"

namespace towsim::io {
namespace {

void put(std::string& out, double v) {
  char b[40];
  // 12 significant digits; std::to_chars is several times faster than snprintf.
  const auto r = std::to_chars(b, b + sizeof b, v == 0 ? 0.0 : v, std::chars_format::general, 12);  // no "-0"
  out.append(b, r.ptr);
}

void put3(std::string& out, const Vec3& v) {
  for (int i = 0; i < 3; ++i) {
    out += ',';
    put(out, v[i]);
  }
}

std::FILE* open_file(const std::string& dir, const std::string& name) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot create " + path);
  return f;
}

void write_all(std::FILE* f, const std::string& s) {
  std::fwrite(s.data(), 1, s.size(), f);
  std::fflush(f);
}

/// JSON for an extreme: {value, time}, null values when never set.
nlohmann::ordered_json json_of(const Extreme& e) {
  nlohmann::ordered_json j;
  j["value"] = std::isnan(e.value) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e.value);
  j["time"] = std::isnan(e.time) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e.time);
  return j;
}

/// A finite number as JSON, anything else as null.
nlohmann::ordered_json num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

/// One timeseries.csv row (with its newline), columns as timeseries_header():
/// the end body's columns where they always were, in-line bodies' at the end.
void timeseries_row(const Model& model, const Sample& s, std::string& out) {
  const Vec3 end = s.node_pos.empty() ? Vec3::Constant(std::nan("")) : s.node_pos.back();
  const BodySample* eb = end_body(model) ? &s.bodies.back() : nullptr;
  put(out, s.t);
  put3(out, s.tow_pos);
  put3(out, s.tow_force);
  put3(out, end);
  if (eb) {
    put3(out, eb->pos);
    put3(out, eb->rpy_deg);
    put3(out, eb->link_force);
  }
  out += ',';
  put(out, s.tow_force.norm());
  out += ',';
  put(out, -end.z());
  put3(out, s.tow_vel);
  if (eb) {
    out += ',';
    put(out, -eb->pos.z());
    out += ',';
    put(out, eb->link_force.norm());
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].inline_body) continue;
    const BodySample& bs = s.bodies[b];
    put3(out, bs.pos);
    put3(out, bs.rpy_deg);
    put3(out, bs.link_force);
    put3(out, bs.lower_link_force);
    for (double v : {-bs.pos.z(), bs.link_force.norm(), bs.lower_link_force.norm()}) {
      out += ',';
      put(out, v);
    }
  }
  out += '\n';
}

/// The nodes.csv rows of one sample: joints 0..n.
void node_rows(const Sample& s, std::string& out) {
  const Vec3 nan3 = Vec3::Constant(std::nan(""));
  for (std::size_t k = 0; k < s.node_pos.size(); ++k) {
    put(out, s.t);
    out += ',' + std::to_string(k);
    put3(out, s.node_pos[k]);
    put3(out, k < s.node_vel.size() ? s.node_vel[k] : nan3);
    out += ',';
    put(out, k < s.tension.size() ? s.tension[k] : std::nan(""));
    out += ',';
    put(out, k < s.axial.size() ? s.axial[k] : std::nan(""));
    out += '\n';
  }
}

}  // namespace

void Extreme::max(double v, double t) {
  if (std::isnan(value) || v > value) {
    value = v;
    time = t;
  }
}

void Extreme::min(double v, double t) {
  if (std::isnan(value) || v < value) {
    value = v;
    time = t;
  }
}

void Extremes::add(const Model& model, const Sample& s) {
  max_tow_tension.max(s.tow_force.norm(), s.t);
  for (double T : s.tension) max_cable_tension.max(T, s.t);
  for (double A : s.axial) min_axial_force.min(A, s.t);
  if (!s.node_pos.empty()) max_end_depth.max(-s.node_pos.back().z(), s.t);
  inline_bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodySample& bs = s.bodies[b];
    BodyExtremes& e = model.bodies[b].inline_body ? inline_bodies[b] : end_body_extremes;
    e.max_link_force.max(bs.link_force.norm(), s.t);
    e.max_lower_link_force.max(bs.lower_link_force.norm(), s.t);
    e.max_depth.max(-bs.pos.z(), s.t);
    for (int i = 0; i < 3; ++i) {
      e.min_deg[i].min(bs.rpy_deg[i], s.t);
      e.max_deg[i].max(bs.rpy_deg[i], s.t);
    }
  }
}

std::string timeseries_header(const Model& model) {
  const bool has_body = end_body(model) != nullptr;
  std::string h = "time,tow_x,tow_y,tow_z,tow_force_x,tow_force_y,tow_force_z,end_x,end_y,end_z";
  if (has_body)
    h += ",body_x,body_y,body_z,body_roll_deg,body_pitch_deg,body_yaw_deg,"
         "link_force_x,link_force_y,link_force_z";
  h += ",tow_tension,end_depth,tow_vx,tow_vy,tow_vz";
  if (has_body) h += ",body_depth,link_tension";
  for (const Body& b : model.bodies) {
    if (!b.inline_body) continue;
    for (const char* c : {"_x", "_y", "_z", "_roll_deg", "_pitch_deg", "_yaw_deg", "_link_force_x", "_link_force_y",
                          "_link_force_z", "_lower_link_force_x", "_lower_link_force_y", "_lower_link_force_z",
                          "_depth", "_link_tension", "_lower_link_tension"})
      h += "," + b.name + c;
  }
  return h;
}

RunWriter::RunWriter(const std::string& dir, const Model& model, bool write_nodes) : model_(model) {
  series_ = open_file(dir, "timeseries.csv");
  write_all(series_, timeseries_header(model) + "\n");
  if (write_nodes) {
    nodes_ = open_file(dir, "nodes.csv");
    write_all(nodes_, "time,node,x,y,z,vx,vy,vz,tension,axial_force\n");
  }
}

RunWriter::~RunWriter() {
  if (series_ != nullptr) std::fclose(series_);
  if (nodes_ != nullptr) std::fclose(nodes_);
}

void RunWriter::write(const Sample& s) {
  extremes_.add(model_, s);
  ++samples_;
  buf_.clear();
  timeseries_row(model_, s, buf_);
  write_all(series_, buf_);
  if (nodes_ == nullptr) return;
  buf_.clear();
  node_rows(s, buf_);
  write_all(nodes_, buf_);
}

void RunWriter::flush() {
  if (series_ != nullptr) std::fflush(series_);
  if (nodes_ != nullptr) std::fflush(nodes_);
}

nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const Extremes& ex, long samples,
                                    const Model& model, bool write_nodes) {
  nlohmann::ordered_json j;
  j["model"] = model_name;
  j["version"] = kVersion;  // of the program that wrote the file
  j["status"] = stats.status;
  j["message"] = stats.message;
  j["end_time"] = num(stats.end_time);
  j["wall_seconds"] = num(stats.wall_seconds);
  j["steps"] = stats.steps;
  j["rejected_steps"] = stats.rejected_steps;
  j["rhs_evaluations"] = stats.rhs_evaluations;
  j["max_element_drift"] = num(stats.max_element_drift);
  j["samples"] = samples;
  j["files"] = {{"timeseries", "timeseries.csv"},
                {"nodes", write_nodes ? nlohmann::ordered_json("nodes.csv") : nlohmann::ordered_json(nullptr)}};
  nlohmann::ordered_json e;
  e["max_tow_tension"] = json_of(ex.max_tow_tension);
  e["max_cable_tension"] = json_of(ex.max_cable_tension);
  e["max_end_depth"] = json_of(ex.max_end_depth);
  e["min_axial_force"] = json_of(ex.min_axial_force);  // < 0: compression (a real cable would go slack)
  // The end body under today's names, in-line bodies under their own.
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    const BodyExtremes& be = body.inline_body ? ex.inline_bodies[b] : ex.end_body_extremes;
    const std::string p = body.inline_body ? body.name + "_" : "";
    e["max_" + p + "link_force"] = json_of(be.max_link_force);
    if (body.inline_body) e["max_" + p + "lower_link_force"] = json_of(be.max_lower_link_force);
    const std::string name = body.inline_body ? body.name : "body";  // the end body keeps today's names
    e["max_" + name + "_depth"] = json_of(be.max_depth);
    const char* names[3] = {"_roll_deg", "_pitch_deg", "_yaw_deg"};
    for (int i = 0; i < 3; ++i)
      e[name + names[i]] = {{"min", json_of(be.min_deg[i])}, {"max", json_of(be.max_deg[i])}};
  }
  j["extremes"] = e;
  j["scenario"] = scenario;
  return j;
}

bool write_summary(const std::string& dir, const nlohmann::ordered_json& summary) {
  std::ofstream out(std::filesystem::path(dir) / "summary.json");
  // Invalid UTF-8 in the scenario echo (e.g. a `name:` in another encoding)
  // becomes U+FFFD instead of throwing after the whole run.
  out << summary.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace towsim::io
