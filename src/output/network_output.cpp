// A network run's files (towsim/output/network_output.hpp).
#include "towsim/output/network_output.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "towsim/dynamics/bending.hpp"
#include "towsim/waves/vessel.hpp"

namespace towsim::output {

namespace {

/// A body of the network: its line, its index in the line's model, its name.
struct NamedBody {
  std::size_t line, body;
  std::string name;
};

/// Every body of every line in tree order, named as the network names them
/// (the model's name where the network gives none).
std::vector<NamedBody> bodies_of(const Network& net) {
  std::vector<NamedBody> out;
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i)
    for (std::size_t b = 0; b < net.tree.lines[i].bodies.size(); ++b) {
      std::string name = net.tree.lines[i].bodies[b].name;
      for (const NetworkBody& nb : net.bodies)
        if (nb.line == static_cast<int>(i) && nb.body == static_cast<int>(b)) name = nb.name;
      out.push_back({i, b, name});
    }
  return out;
}

bool any_breaking_load(const Network& net) {
  return std::any_of(net.tree.lines.begin(), net.tree.lines.end(), [](const Model& m) {
    return std::any_of(m.cable.sections.begin(), m.cable.sections.end(),
                       [](const Section& sec) { return sec.breaking_load > 0; });
  });
}

bool any_bending(const Network& net) {
  return std::any_of(net.tree.lines.begin(), net.tree.lines.end(), [](const Model& m) { return has_bending(m); });
}

}  // namespace

std::vector<std::string> network_timeseries_columns(const Network& net) {
  std::vector<std::string> c{"time"};
  const auto add = [&c](const std::string& p, std::initializer_list<const char*> names) {
    for (const char* n : names) c.push_back(p + n);
  };
  for (std::size_t i = 0; i < net.line_names.size(); ++i) {
    const std::string& l = net.line_names[i];
    add(l, {"_top_x", "_top_y", "_top_z", "_top_force_x", "_top_force_y", "_top_force_z", "_top_tension", "_end_x",
            "_end_y", "_end_z", "_end_depth", "_deployed_length"});
    if (net.tree.lines[i].winch.active()) add(l, {"_payout_speed"});
  }
  for (const NamedBody& b : bodies_of(net)) {
    add(b.name, {"_x", "_y", "_z", "_roll_deg", "_pitch_deg", "_yaw_deg", "_depth", "_link_force_x", "_link_force_y",
                 "_link_force_z", "_link_tension"});
    if (net.tree.lines[b.line].bodies[b.body].inline_body)
      add(b.name, {"_lower_link_force_x", "_lower_link_force_y", "_lower_link_force_z", "_lower_link_tension"});
  }
  for (const NetworkJunction& j : net.junctions) add(j.name, {"_x", "_y", "_z", "_depth"});
  if (net.settings().fluid.waves) c.push_back("wave_elevation");  // (a tow point's own vessel has no waves)
  if (net.settings().seabed)
    for (const std::string& l : net.line_names) add(l, {"_contact_length", "_lying_length"});
  return c;
}

void network_timeseries_values(const Network& net, const NetworkSample& s, std::vector<double>& v) {
  v.clear();
  const auto add3 = [&v](const Vec3& a) { v.insert(v.end(), {a.x(), a.y(), a.z()}); };
  v.push_back(tidy_time(s.t));
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const Sample& l = s.lines[i];
    add3(l.tow_pos);
    add3(l.tow_force);
    v.push_back(l.tow_force.norm());
    add3(l.node_pos.back());
    v.push_back(-l.node_pos.back().z());
    v.push_back(l.deployed_length);
    if (net.tree.lines[i].winch.active()) v.push_back(l.payout_speed);
  }
  for (const NamedBody& b : bodies_of(net)) {
    const BodySample& bs = s.lines[b.line].bodies[b.body];
    add3(bs.pos);
    add3(bs.rpy_deg);
    v.push_back(-bs.pos.z());
    add3(bs.link_force);
    v.push_back(bs.link_force.norm());
    if (net.tree.lines[b.line].bodies[b.body].inline_body) {
      add3(bs.lower_link_force);
      v.push_back(bs.lower_link_force.norm());
    }
  }
  for (const NetworkJunction& j : net.junctions) {
    const Vec3& p = s.lines[static_cast<std::size_t>(j.line)].node_pos.back();
    add3(p);
    v.push_back(-p.z());
  }
  if (net.settings().fluid.waves) v.push_back(s.lines.front().wave_elevation);
  if (net.settings().seabed)
    for (const Sample& l : s.lines) v.insert(v.end(), {l.contact_length, l.lying_length});
}

std::vector<std::string> network_node_columns(const Network& net) {
  std::vector<std::string> c = node_columns();
  if (any_breaking_load(net)) c.push_back("utilisation");
  if (net.settings().seabed) c.push_back("seabed_force");
  if (any_bending(net)) c.push_back("bending_moment");
  return c;
}

void network_node_values(const Network& net, const Sample& line, std::size_t k, std::vector<double>& values) {
  node_values(line, k, values);
  if (any_breaking_load(net)) values.push_back(k < line.utilisation.size() ? tidy(line.utilisation[k]) : 0.0);
  if (net.settings().seabed) values.push_back(k < line.node_seabed.size() ? tidy(line.node_seabed[k].norm()) : 0.0);
  if (any_bending(net)) values.push_back(k < line.bending.size() ? tidy(line.bending[k]) : 0.0);
}

NetworkRecord::NetworkRecord(const Network& net) : net_(net), extremes_(net.tree.lines.size()) {}

void NetworkRecord::write(const NetworkSample& s) {
  for (std::size_t i = 0; i < s.lines.size(); ++i) extremes_[i].add(net_.tree.lines[i], s.lines[i]);
  ++samples_;
  network_timeseries_values(net_, s, row_);
}

std::vector<double> NetworkRecord::last_row() const {
  std::vector<double> row = row_;
  for (std::size_t i = 1; i < row.size(); ++i) row[i] = tidy(row[i]);
  return row;
}

nlohmann::ordered_json NetworkRecord::final_row() const {
  if (row_.empty()) return nullptr;
  nlohmann::ordered_json j;
  const auto names = network_timeseries_columns(net_);
  const std::vector<double> row = last_row();
  for (std::size_t i = 0; i < names.size() && i < row.size(); ++i) j[names[i]] = num(row[i]);
  return j;
}

NetworkWriter::NetworkWriter(const std::string& dir, const Network& net, bool write_nodes) : NetworkRecord(net) {
  series_ = std::make_unique<RowFile>((std::filesystem::path(dir) / "timeseries.csv").string());
  std::string h;
  for (const std::string& c : network_timeseries_columns(net)) h += (h.empty() ? "" : ",") + c;
  series_->append(h + "\n");
  if (!write_nodes) return;
  nodes_ = std::make_unique<RowFile>((std::filesystem::path(dir) / "nodes.csv").string());
  h = net.has_winch() ? "line,time,node,node_id" : "line,time,node";
  for (const std::string& c : network_node_columns(net)) h += "," + c;
  nodes_->append(h + "\n");
}

NetworkWriter::~NetworkWriter() { flush(); }

void NetworkWriter::write(const NetworkSample& s) {
  NetworkRecord::write(s);
  // timeseries.csv: the row just recorded.
  const std::vector<double>& row = raw_row();
  put_time(series_buf_, s.t);
  for (std::size_t i = 1; i < row.size(); ++i) series_buf_ += ',', put_number(series_buf_, row[i]);
  series_buf_ += '\n';
  // nodes.csv: per line, per node; a column a line lacks is 0.
  if (nodes_ != nullptr) {
    const Network& net = network();
    const bool ids = net.has_winch();
    std::string time;
    put_time(time, s.t);
    for (std::size_t i = 0; i < s.lines.size(); ++i) {
      const Sample& l = s.lines[i];
      for (std::size_t k = 0; k < l.node_pos.size(); ++k) {
        values_.clear();
        network_node_values(net, l, k, values_);
        nodes_buf_ += net.line_names[i];
        nodes_buf_ += ',';
        nodes_buf_ += time;
        nodes_buf_ += ',';
        nodes_buf_ += std::to_string(k);
        if (ids)
          nodes_buf_ += ',', nodes_buf_ += std::to_string(k < l.node_id.size() ? l.node_id[k] : static_cast<long>(k));
        for (double v : values_) nodes_buf_ += ',', put_number(nodes_buf_, v);
        nodes_buf_ += '\n';
      }
    }
  }
  if (series_buf_.size() + nodes_buf_.size() >= RunWriter::kWriteBytes) flush();
}

void NetworkWriter::flush() {
  if (!series_buf_.empty()) series_->append(series_buf_);
  if (nodes_ != nullptr && !nodes_buf_.empty()) nodes_->append(nodes_buf_);
  series_buf_.clear();
  nodes_buf_.clear();
}

std::string NetworkWriter::error() const {
  if (!series_->error().empty()) return series_->error();
  return nodes_ != nullptr ? nodes_->error() : std::string();
}

nlohmann::ordered_json make_network_summary(const nlohmann::ordered_json& scenario, const RunStats& stats,
                                            const NetworkRecord& record, bool write_nodes) {
  const Network& net = record.network();
  nlohmann::ordered_json j = run_json(net.name, stats);
  j["samples"] = record.samples();
  j["files"] = {{"timeseries", "timeseries.csv"},
                {"nodes", write_nodes ? nlohmann::ordered_json("nodes.csv") : nlohmann::ordered_json(nullptr)}};
  // The lines: top tension (the load on the tow point or node), cable tension, end depth.
  nlohmann::ordered_json e;
  double max_tow = std::nan("");
  Extreme tow;
  for (std::size_t i = 0; i < net.tree.lines.size(); ++i) {
    const Extremes& ex = record.extremes()[i];
    const std::string& l = net.line_names[i];
    e["max_" + l + "_top_tension"] = json_of(ex.max_tow_tension);
    e["max_" + l + "_cable_tension"] = json_of(ex.max_cable_tension);
    e["max_" + l + "_end_depth"] = json_of(ex.max_end_depth);
    e["min_" + l + "_axial_force"] = json_of(ex.min_axial_force);
    if (net.tree.tops[i].line < 0 && !(ex.max_tow_tension.value <= max_tow)) {
      max_tow = ex.max_tow_tension.value;
      tow = ex.max_tow_tension;
    }
  }
  // The largest top tension of a line from the vessel (sweeps and plots read it).
  e["max_tow_tension"] = json_of(tow);
  // The bodies, by name.
  for (const NamedBody& b : bodies_of(net)) {
    const Extremes& ex = record.extremes()[b.line];
    const Body& body = net.tree.lines[b.line].bodies[b.body];
    const BodyExtremes& be = body.inline_body && b.body < ex.inline_bodies.size() ? ex.inline_bodies[b.body]
                                                                                  : ex.end_body_extremes;
    e["max_" + b.name + "_link_force"] = json_of(be.max_link_force);
    if (body.inline_body) e["max_" + b.name + "_lower_link_force"] = json_of(be.max_lower_link_force);
    e["max_" + b.name + "_depth"] = json_of(be.max_depth);
    const char* names[3] = {"_roll_deg", "_pitch_deg", "_yaw_deg"};
    for (int k = 0; k < 3; ++k)
      e[b.name + names[k]] = {{"min", json_of(be.min_deg[k])}, {"max", json_of(be.max_deg[k])}};
  }
  j["extremes"] = e;
  // With winches: their events (all lines), each line's largest top tension against its rating.
  if (net.has_winch()) {
    nlohmann::ordered_json w;
    w["splits"] = stats.winch_splits;
    w["removals"] = stats.winch_removals;
    w["energy_lost"] = num(tidy(std::max(0.0, stats.winch_energy_lost)));
    w["energy_gained"] = num(tidy(std::max(0.0, -stats.winch_energy_lost)));
    nlohmann::ordered_json lines = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < net.tree.lines.size(); ++i) {
      const Winch& wi = net.tree.lines[i].winch;
      if (!wi.active()) continue;
      const double top = record.extremes()[i].max_tow_tension.value;
      lines[net.line_names[i]] = {{"rating", wi.rating > 0 ? num(wi.rating) : nlohmann::ordered_json(nullptr)},
                                  {"max_load_ratio",
                                   wi.rating > 0 ? num(tidy(top / wi.rating)) : nlohmann::ordered_json(nullptr)}};
    }
    w["lines"] = lines;
    j["winch"] = w;
  }
  j["final"] = record.final_row();
  j["scenario"] = scenario;
  return j;
}

}  // namespace towsim::output
