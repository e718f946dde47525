#include "towsim/io/output.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace towsim::io {
namespace {

void put(std::string& out, double v) { put_number(out, v); }

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
  j["value"] = std::isnan(e.value) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(tidy(e.value));
  j["time"] = std::isnan(e.time) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(tidy_time(e.time));
  return j;
}

/// A finite number as JSON, anything else as null.
nlohmann::ordered_json num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

/// One timeseries.csv row's values, columns as timeseries_columns(), tidied.
void timeseries_values(const Sample& s, bool has_body, double deployed_length, std::vector<double>& v) {
  const Vec3 end = s.node_pos.empty() ? Vec3::Constant(std::nan("")) : s.node_pos.back();
  v.clear();
  auto add3 = [&v](const Vec3& a) { v.insert(v.end(), {a.x(), a.y(), a.z()}); };
  v.push_back(tidy_time(s.t));
  add3(s.tow_pos);
  add3(s.tow_force);
  add3(end);
  if (has_body) {
    add3(s.body_pos);
    add3(s.body_rpy_deg);
    add3(s.link_force);
  }
  v.push_back(s.tow_force.norm());
  v.push_back(-end.z());
  add3(s.tow_vel);
  if (has_body) {
    v.push_back(-s.body_pos.z());
    v.push_back(s.link_force.norm());
  }
  v.push_back(layback(s));
  v.push_back(deployed_length);
  for (std::size_t i = 1; i < v.size(); ++i) v[i] = tidy(v[i]);
}

/// The nodes.csv rows of one sample: joints 0..n.
void node_rows(const Sample& s, std::string& out) {
  const Vec3 nan3 = Vec3::Constant(std::nan(""));
  for (std::size_t k = 0; k < s.node_pos.size(); ++k) {
    put_time(out, s.t);
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

double tidy(double v) {
  if (!std::isfinite(v)) return v;
  if (std::abs(v) < kZeroBelow) return 0.0;  // also turns -0 into 0
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general, 12);
  double out = v;
  std::from_chars(b, r.ptr, out);
  return out;
}

double tidy_time(double t) {
  if (!std::isfinite(t)) return t;
  const double r = std::round(t * 1e9) / 1e9;  // nanoseconds
  return r == 0 ? 0.0 : r;
}

void put_number(std::string& out, double v) {
  char b[40];
  // 12 significant digits (the shortest form of tidy(v)); std::to_chars is
  // several times faster than snprintf.
  const auto r = std::to_chars(b, b + sizeof b, std::abs(v) < kZeroBelow ? 0.0 : v, std::chars_format::general, 12);
  out.append(b, r.ptr);
}

void put_time(std::string& out, double t) {
  char b[40];
  const auto r = std::to_chars(b, b + sizeof b, tidy_time(t));  // shortest round-trip form
  out.append(b, r.ptr);
}

double layback(const Sample& s) {
  const Vec3 p = s.has_body ? s.body_pos : (s.node_pos.empty() ? Vec3::Constant(std::nan("")) : s.node_pos.back());
  return std::hypot(p.x() - s.tow_pos.x(), p.y() - s.tow_pos.y());
}

void remove_run_outputs(const std::string& dir) {
  namespace fs = std::filesystem;
  for (const char* name : {"timeseries.csv", "nodes.csv", "summary.json", "report.html", "plots"}) {
    std::error_code ec;
    fs::remove_all(fs::path(dir) / name, ec);
    if (ec) throw std::runtime_error("cannot remove the previous run's " + (fs::path(dir) / name).string() + ": " +
                                     ec.message());
  }
}

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

void Extremes::add(const Sample& s) {
  max_tow_tension.max(s.tow_force.norm(), s.t);
  for (double T : s.tension) max_cable_tension.max(T, s.t);
  for (double A : s.axial) min_axial_force.min(A, s.t);
  if (!s.node_pos.empty()) max_end_depth.max(-s.node_pos.back().z(), s.t);
  max_layback.max(tidy(layback(s)), tidy_time(s.t));
  const double depth = s.has_body ? -s.body_pos.z() : (s.node_pos.empty() ? std::nan("") : -s.node_pos.back().z());
  if (!std::isnan(depth)) {
    min_depth.min(tidy(depth), tidy_time(s.t));
    max_depth.max(tidy(depth), tidy_time(s.t));
  }
  if (!s.has_body) return;
  max_link_force.max(s.link_force.norm(), s.t);
  max_body_depth.max(-s.body_pos.z(), s.t);
  for (int i = 0; i < 3; ++i) {
    min_body_deg[i].min(s.body_rpy_deg[i], s.t);
    max_body_deg[i].max(s.body_rpy_deg[i], s.t);
  }
}

std::vector<std::string> timeseries_columns(bool has_body) {
  std::vector<std::string> c{"time",        "tow_x",       "tow_y",       "tow_z", "tow_force_x",
                             "tow_force_y", "tow_force_z", "end_x",       "end_y", "end_z"};
  if (has_body)
    c.insert(c.end(), {"body_x", "body_y", "body_z", "body_roll_deg", "body_pitch_deg", "body_yaw_deg",
                       "link_force_x", "link_force_y", "link_force_z"});
  c.insert(c.end(), {"tow_tension", "end_depth", "tow_vx", "tow_vy", "tow_vz"});
  if (has_body) c.insert(c.end(), {"body_depth", "link_tension"});
  c.insert(c.end(), {"layback", "deployed_length"});
  return c;
}

std::string timeseries_header(bool has_body) {
  std::string h;
  for (const auto& c : timeseries_columns(has_body)) h += (h.empty() ? "" : ",") + c;
  return h;
}

RunWriter::RunWriter(const std::string& dir, bool has_body, bool write_nodes, double deployed_length)
    : has_body_(has_body), deployed_length_(deployed_length) {
  series_ = open_file(dir, "timeseries.csv");
  write_all(series_, timeseries_header(has_body) + "\n");
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
  extremes_.add(s);
  ++samples_;
  buf_.clear();
  timeseries_values(s, has_body_, deployed_length_, last_);
  for (std::size_t i = 0; i < last_.size(); ++i) {
    if (i > 0) buf_ += ',';
    if (i == 0) put_time(buf_, last_[i]);
    else put(buf_, last_[i]);
  }
  buf_ += '\n';
  write_all(series_, buf_);
  if (nodes_ == nullptr) return;
  buf_.clear();
  node_rows(s, buf_);
  write_all(nodes_, buf_);
}

nlohmann::ordered_json RunWriter::final_row() const {
  if (last_.empty()) return nullptr;
  nlohmann::ordered_json j;
  const auto names = timeseries_columns(has_body_);
  for (std::size_t i = 0; i < names.size() && i < last_.size(); ++i) j[names[i]] = num(last_[i]);
  return j;
}

void RunWriter::flush() {
  if (series_ != nullptr) std::fflush(series_);
  if (nodes_ != nullptr) std::fflush(nodes_);
}

nlohmann::ordered_json make_summary(const nlohmann::ordered_json& scenario, const std::string& model_name,
                                    const RunStats& stats, const Extremes& ex, long samples,
                                    bool has_body, bool write_nodes, const nlohmann::ordered_json& final_row) {
  nlohmann::ordered_json j;
  j["model"] = model_name;
  j["status"] = stats.status;
  j["message"] = stats.message;
  j["end_time"] = num(tidy_time(stats.end_time));
  j["wall_seconds"] = num(std::round(stats.wall_seconds * 1e3) / 1e3);  // ms: the clock's useful resolution
  j["steps"] = stats.steps;
  j["rejected_steps"] = stats.rejected_steps;
  j["rhs_evaluations"] = stats.rhs_evaluations;
  j["max_element_drift"] = num(stats.max_element_drift);  // kept unrounded: it is a round-off measure
  j["samples"] = samples;
  j["files"] = {{"timeseries", "timeseries.csv"},
                {"nodes", write_nodes ? nlohmann::ordered_json("nodes.csv") : nlohmann::ordered_json(nullptr)}};
  nlohmann::ordered_json e;
  e["max_tow_tension"] = json_of(ex.max_tow_tension);
  e["max_cable_tension"] = json_of(ex.max_cable_tension);
  e["max_end_depth"] = json_of(ex.max_end_depth);
  e["min_axial_force"] = json_of(ex.min_axial_force);  // < 0: compression (a real cable would go slack)
  e["min_depth"] = json_of(ex.min_depth);    // of the body origin, or of the cable end without a body
  e["max_depth"] = json_of(ex.max_depth);
  e["max_layback"] = json_of(ex.max_layback);
  if (has_body) {
    e["max_link_force"] = json_of(ex.max_link_force);
    e["max_body_depth"] = json_of(ex.max_body_depth);
    const char* names[3] = {"body_roll_deg", "body_pitch_deg", "body_yaw_deg"};
    for (int i = 0; i < 3; ++i)
      e[names[i]] = {{"min", json_of(ex.min_body_deg[i])}, {"max", json_of(ex.max_body_deg[i])}};
  }
  j["extremes"] = e;
  j["final"] = final_row;  // the last timeseries.csv row by column name
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
