#include "sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <ostream>
#include <set>
#include <thread>

#include "../src/scenario/reader.hpp"  // MapReader for the sweep file (scenario-internal)
#include "commands.hpp"
#include "towsim/output/dir_lock.hpp"
#include "towsim/output/output.hpp"
#include "towsim/sim/discretisation.hpp"
#include "towsim/sim/touchdown.hpp"

namespace towsim::cli {

using namespace towsim::scenario;
using namespace towsim::output;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A JSON number as a double, anything else as NaN.
double number_of(const nlohmann::ordered_json& v) { return v.is_number() ? v.get<double>() : kNaN; }

/// The `value` of a {value, time} object, NaN otherwise.
double value_of(const nlohmann::ordered_json& v) {
  return v.is_object() && v.contains("value") ? number_of(v["value"]) : kNaN;
}

/// True when a plain scalar would not read back as itself inside a flow collection.
bool needs_quotes(const std::string& s) {
  if (s.empty() || s.front() == ' ' || s.back() == ' ') return true;
  for (char c : s)
    if (std::string(",[]{}#&*!|>'\"%@`\n\t").find(c) != std::string::npos) return true;
  return s.find(": ") != std::string::npos || s.back() == ':' || (s.front() == '-' && s.size() > 1 && s[1] == ' ');
}

/// A double-quoted YAML scalar.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

/// A YAML value as flow text that reads back as the same value (the VALUE of KEY=VALUE).
std::string yaml_text(const YNode& n) {
  switch (n.kind) {
    case YNode::Kind::Scalar:
      return n.quoted || needs_quotes(n.scalar) ? quoted(n.scalar) : n.scalar;
    case YNode::Kind::Sequence: {
      std::string out = "[";
      for (std::size_t i = 0; i < n.items.size(); ++i) out += (i ? ", " : "") + yaml_text(n.items[i]);
      return out + "]";
    }
    case YNode::Kind::Map: {
      std::string out = "{";
      for (std::size_t i = 0; i < n.items.size(); ++i) {
        const std::string& k = n.items[i].key;
        out += (i ? ", " : "") + (needs_quotes(k) ? quoted(k) : k) + ": " + yaml_text(n.items[i]);
      }
      return out + "}";
    }
    default:
      return "null";
  }
}

/// A dotted key path as `--set` takes it: non-empty parts, no '=' or blanks.
bool valid_key(const std::string& k) {
  if (k.empty() || k.front() == '.' || k.back() == '.' || k.find("..") != std::string::npos) return false;
  for (char c : k)
    if (c == '=' || c == ' ' || c == '\t' || c == '\n') return false;
  return true;
}

/// An override with where its value is written in the sweep file.
struct Override {
  std::string key, value;
  SourceLoc loc;
};

/// Read a mapping of KEY: VALUE overrides at `path`.
std::vector<Override> read_overrides(const YNode& map, const std::string& path, Diagnostics& d) {
  std::vector<Override> out;
  if (!map.is_map()) {
    d.error(map.loc, path, "expected a mapping of KEY: VALUE overrides (got " + map.describe() + ")");
    return out;
  }
  std::set<std::string> seen;
  for (const YNode& v : map.items) {
    const std::string p = join_path(path, v.key);
    if (!valid_key(v.key)) {
      d.error(v.key_loc, p, "not a dotted key path (e.g. cable.length or body.spheres.0.radius)");
    } else if (!seen.insert(v.key).second) {
      d.error(v.key_loc, p, "duplicate key");
    } else {
      out.push_back(Override{v.key, yaml_text(v), v.loc});
    }
  }
  return out;
}

/// Every case's `--set` list and the matching locations in the sweep file.
struct ExpandedCase {
  std::vector<std::string> sets;
  std::vector<SourceLoc> locs;
};

ExpandedCase expand(const SweepSpec& spec, const std::vector<SourceLoc>& common_locs, const SweepCase& c,
                    const std::vector<SourceLoc>& case_locs) {
  ExpandedCase e{spec.common, common_locs};
  for (std::size_t i = 0; i < c.sets.size(); ++i) {
    e.sets.push_back(c.sets[i].first + "=" + c.sets[i].second);
    e.locs.push_back(case_locs[i]);
  }
  return e;
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// "case-0042".
std::string case_name(std::size_t i) {
  char b[32];
  std::snprintf(b, sizeof b, "case-%04zu", i);
  return b;
}

/// The figure names of a run of `model` (what summary_figures gives for it).
std::vector<std::string> figure_names(const Model& model) {
  auto summary = make_summary(nlohmann::ordered_json::object(), "", RunStats{}, RunRecord(model), false);
  summary["final"] = nlohmann::ordered_json::object();
  for (const auto& c : timeseries_columns(model)) summary["final"][c] = nullptr;
  std::vector<std::string> names;
  for (const auto& f : summary_figures(summary)) names.push_back(f.first);
  return names;
}

}  // namespace

std::vector<Figure> summary_figures(const nlohmann::ordered_json& s) {
  std::vector<Figure> out;
  if (s.contains("end_time")) out.emplace_back("end_time", number_of(s["end_time"]));
  if (s.contains("extremes") && s["extremes"].is_object()) {
    for (const auto& [k, v] : s["extremes"].items()) {
      if (v.is_object() && v.contains("min") && v.contains("max")) {
        out.emplace_back(k + "_min", value_of(v["min"]));
        out.emplace_back(k + "_max", value_of(v["max"]));
      } else {
        out.emplace_back(k, v.is_number() ? number_of(v) : value_of(v));
      }
    }
  }
  // Figures other features add at the top level (e.g. max_utilisation).
  for (const auto& [k, v] : s.items()) {
    if (k.rfind("max_", 0) != 0 && k.rfind("min_", 0) != 0) continue;
    if (k == "max_element_drift") continue;  // an integration diagnostic, not a result
    out.emplace_back(k, v.is_number() ? number_of(v) : value_of(v));
  }
  if (s.contains("final") && s["final"].is_object())
    for (const auto& [k, v] : s["final"].items()) out.emplace_back("final_" + k, number_of(v));
  return out;
}

CaseResult run_case(const LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag,
                    const ProgressFn& progress) {
  CaseResult res;
  if (!sc.ok()) {
    res.status = "invalid";
    res.message = sc.diags.str();
    while (!res.message.empty() && res.message.back() == '\n') res.message.pop_back();
    return res;
  }
  if (sc.is_network()) return run_network_case(sc, out_dir, stop_flag, progress);
  // One case per core already: each case on one thread (simulation.threads: 1).
  Model own = *sc.model;
  own.sim.threads = 1;
  const Model& model = own;
  try {
    std::unique_ptr<DirLock> lock;
    std::unique_ptr<RunRecord> rec;
    if (out_dir.empty()) {
      rec = std::make_unique<RunRecord>(model);
    } else {
      std::filesystem::create_directories(out_dir);
      lock = std::make_unique<DirLock>(out_dir);  // one towsim at a time in a directory
      remove_run_outputs(out_dir);
      rec = std::make_unique<RunWriter>(out_dir, model, model.sim.write_nodes);
    }
    RunStats stats;
    try {
      stats = simulate(model, *rec, progress, stop_flag);
    } catch (const std::exception& e) {
      stats.status = "failed";
      stats.message = std::string("internal error: ") + e.what();
    }
    rec->flush();
    record_discretisation_estimate(model, stats, stop_flag);
    const auto summary = make_summary(to_json(sc.tree), model.name, stats, *rec, model.sim.write_nodes);
    std::string why;
    if (!out_dir.empty() && !write_summary(out_dir, summary, &why)) throw std::runtime_error(why);
    if (const auto* w = dynamic_cast<const RunWriter*>(rec.get()); w != nullptr && !w->error().empty())
      throw std::runtime_error(w->error());
    res.status = stats.status;
    res.message = stats.message;
    res.figures = summary_figures(summary);
  } catch (const std::exception& e) {
    res.status = "failed";
    res.message = e.what();
  }
  return res;
}

CaseResult statics_case(const LoadedScenario& sc, const std::string& out_dir, const volatile int* stop_flag) {
  CaseResult res;
  if (!sc.ok() || statics_refusal(sc)) {
    res.status = "invalid";
    res.message = sc.ok() ? statics_refusal(sc)->str() : sc.diags.str();
    while (!res.message.empty() && res.message.back() == '\n') res.message.pop_back();
    return res;
  }
  if (sc.is_network()) return statics_network_case(sc, out_dir, stop_flag);
  try {
    // Over a flat seabed with its touchdown joint, as `towsim statics`.
    const TouchdownStatics td = touchdown_statics(*sc.model, final_tow_velocity(sc.model->tow), stop_flag);
    const Model& model = td.model;
    const StaticsResult& r = td.statics;
    std::unique_ptr<RunRecord> rec;
    if (out_dir.empty()) {
      rec = std::make_unique<RunRecord>(model);
    } else {
      std::filesystem::create_directories(out_dir);
      remove_run_outputs(out_dir);
      rec = std::make_unique<RunWriter>(out_dir, model, true);
    }
    const auto summary = statics_summary(sc, r, *rec);
    if (!out_dir.empty() && !write_summary(out_dir, summary))
      throw std::runtime_error("cannot write " + out_dir + "/summary.json");
    res.status = summary["status"].get<std::string>();
    res.message = summary["message"].is_string() ? summary["message"].get<std::string>() : std::string();
    res.figures = summary_figures(summary);
    for (std::size_t b = 0; b < r.equilibria.size(); ++b) {
      const BodyEquilibria& eq = r.equilibria[b];
      if (!eq.analysed || eq.chosen < 0) continue;
      std::size_t stable = 0;
      for (const BodyEquilibrium& e : eq.balances) stable += e.stable ? 1 : 0;
      const Body& body = model.bodies[b];
      res.trims.push_back(BodyTrim{body.inline_body ? "body " + body.name : std::string("the body"),
                                   eq.balances[static_cast<std::size_t>(eq.chosen)].rpy_deg, stable});
    }
  } catch (const std::exception& e) {
    res.status = "failed";
    res.message = std::string("internal error: ") + e.what();
  }
  return res;
}

std::vector<std::string> trim_jumps(const std::vector<SweepCase>& cases, const std::vector<CaseResult>& results) {
  std::vector<std::string> out;
  // "case-0001 (KEY=VALUE, ...)".
  const auto named = [&](std::size_t i) {
    std::string s = case_name(i) + " (";
    for (std::size_t k = 0; k < cases[i].sets.size(); ++k)
      s += (k ? ", " : "") + cases[i].sets[k].first + "=" + cases[i].sets[k].second;
    return s + ")";
  };
  const auto deg = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%+.1f", v);
    return std::string(b);
  };
  const char* const axes[] = {"roll", "pitch", "yaw"};
  for (std::size_t i = 0; i + 1 < cases.size() && i + 1 < results.size(); ++i) {
    const SweepCase &a = cases[i], &b = cases[i + 1];
    if (a.sets.size() != b.sets.size()) continue;
    std::size_t differ = 0;
    bool same_keys = true;
    for (std::size_t k = 0; k < a.sets.size(); ++k) {
      same_keys = same_keys && a.sets[k].first == b.sets[k].first;
      differ += a.sets[k].second != b.sets[k].second ? 1 : 0;
    }
    if (!same_keys || differ != 1 || results[i].status != "ok" || results[i + 1].status != "ok") continue;
    for (const BodyTrim& ta : results[i].trims)
      for (const BodyTrim& tb : results[i + 1].trims) {
        if (ta.body != tb.body) continue;
        std::string what;
        for (int c = 0; c < 3; ++c) {
          double d = tb.rpy_deg[c] - ta.rpy_deg[c];
          if (c != 1) d = std::remainder(d, 360.0);  // roll and yaw wrap; pitch lies in [-90, 90]
          if (std::abs(d) > kTrimJumpDeg)
            what += std::string(what.empty() ? "" : "; ") + axes[c] + " " + deg(ta.rpy_deg[c]) + " to " +
                    deg(tb.rpy_deg[c]) + " deg, a change of more than " + fmt_num(kTrimJumpDeg) + " deg";
        }
        if (ta.stable_count != tb.stable_count)
          what += std::string(what.empty() ? "" : "; ") + "stable equilibria " + std::to_string(ta.stable_count) +
                  " to " + std::to_string(tb.stable_count) + ", a change of branch";
        if (!what.empty())
          out.push_back("trim of " + ta.body + " between neighbouring cases " + named(i) + " and " + named(i + 1) +
                        ": " + what);
      }
  }
  return out;
}

const std::vector<std::string>& towing_table_columns() {
  static const std::vector<std::string> columns{"tow_speed",   "tow_speed_kn",  "depth",      "layback",
                                                "tow_tension", "top_angle_deg", "offset_aft", "offset_starboard"};
  return columns;
}

std::vector<double> towing_row(const std::vector<Figure>& figures) {
  const auto get = [&](const std::string& name) {
    for (const auto& [k, v] : figures)
      if (k == name) return v;
    return kNaN;
  };
  // The end body's figures, else the cable end's (an in-line body is not the end).
  const bool body = !std::isnan(get("final_body_depth"));
  const std::string at = body ? "final_body_" : "final_end_";
  const double vx = get("final_tow_vx"), vy = get("final_tow_vy");
  const double speed = std::hypot(vx, vy);  // horizontal tow speed [m/s]
  // Heading: the tow's horizontal velocity (+x when at rest) [-, R_g].
  const double hx = speed > 0 ? vx / speed : 1.0, hy = speed > 0 ? vy / speed : 0.0;
  const double dx = get(at + "x") - get("final_tow_x"), dy = get(at + "y") - get("final_tow_y");             // [m]
  const double fx = get("final_tow_force_x"), fy = get("final_tow_force_y"), fz = get("final_tow_force_z");  // [N]
  constexpr double kKnot = 1852.0 / 3600.0;                                                                  // [m/s]
  return {speed,
          speed / kKnot,
          get(at + "depth"),
          get("final_layback"),
          get("final_tow_tension"),
          std::atan2(fz, std::hypot(fx, fy)) * 180.0 / M_PI,
          -(dx * hx + dy * hy),
          dx * hy - dy * hx};  // starboard: -y when heading +x (z up)
}

namespace {

/// The sweep file's locations of each case's overrides, kept beside the spec.
struct SweepLocs {
  SourceLoc example;  // the example name's value
  std::vector<SourceLoc> common;
  std::vector<std::vector<SourceLoc>> cases;
};

SweepSpec read_sweep_with_locs(const std::string& path, Diagnostics& d, SweepLocs& locs) {
  SweepSpec spec;
  const YNode tree = load_yaml_file(path, d);
  if (!d.ok()) return spec;
  MapReader root(&tree, "", d);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  const YNode* scen = root.get("scenario");
  const YNode* ex = root.get("example");
  std::string text;
  if (scen != nullptr && convert(*scen, "scenario", d, text)) {
    const std::filesystem::path p(text);
    spec.scenario = p.is_absolute() ? text : (dir / p).string();
  }
  if (ex != nullptr && convert(*ex, "example", d, text)) {
    spec.example = text;
    locs.example = ex->loc;
  }
  if (scen != nullptr && ex != nullptr) d.error(ex->key_loc, "example", "give either scenario or example, not both");
  if (scen == nullptr && ex == nullptr && root.present())
    d.error(tree.loc, "scenario", "missing: give the base scenario (scenario: FILE) or a built-in one (example: NAME)");
  if (const YNode* set = root.get("set"))
    for (const auto& o : read_overrides(*set, "set", d)) {
      spec.common.push_back(o.key + "=" + o.value);
      locs.common.push_back(o.loc);
    }
  if (const YNode* w = root.get("write_cases")) convert(*w, "write_cases", d, spec.write_cases);
  if (const YNode* st = root.get("statics")) convert(*st, "statics", d, spec.statics);

  // grid: KEY: [values...]; the product, the first key varying slowest.
  std::vector<std::string> grid_keys;
  std::vector<std::vector<Override>> grid_values;
  const YNode* grid = root.get("grid");
  if (grid != nullptr) {
    if (!grid->is_map()) {
      d.error(grid->loc, "grid", "expected a mapping of KEY: [values] (got " + grid->describe() + ")");
    } else {
      for (const YNode& v : grid->items) {
        const std::string p = join_path("grid", v.key);
        if (!valid_key(v.key)) {
          d.error(v.key_loc, p, "not a dotted key path (e.g. cable.length or body.spheres.0.radius)");
          continue;
        }
        if (!v.is_seq() || v.items.empty()) {
          d.error(v.loc, p, "expected a non-empty list of values (got " + v.describe() + ")");
          continue;
        }
        bool dup = false;
        for (const auto& k : grid_keys) dup = dup || k == v.key;
        if (dup) {
          d.error(v.key_loc, p, "duplicate key");
          continue;
        }
        grid_keys.push_back(v.key);
        grid_values.emplace_back();
        for (const YNode& item : v.items) grid_values.back().push_back(Override{v.key, yaml_text(item), item.loc});
      }
    }
  }
  // cases: a list of KEY: VALUE mappings.
  std::vector<std::vector<Override>> list;
  const YNode* cases = root.get("cases");
  if (cases != nullptr) {
    if (!cases->is_seq() || cases->items.empty()) {
      d.error(cases->loc, "cases", "expected a non-empty list of KEY: VALUE mappings (got " + cases->describe() + ")");
    } else {
      for (std::size_t i = 0; i < cases->items.size(); ++i) {
        const std::string p = "cases." + std::to_string(i);
        auto ov = read_overrides(cases->items[i], p, d);
        for (const auto& o : ov)
          for (const auto& k : grid_keys)
            if (o.key == k) d.error(o.loc, join_path(p, o.key), "also varied by grid");
        list.push_back(std::move(ov));
      }
    }
  }
  if (grid == nullptr && cases == nullptr && root.present())
    d.error(tree.loc, "grid", "missing: give the values to sweep (grid: {KEY: [values]} and/or cases: [{KEY: VALUE}])");
  root.finish();
  if (!d.ok()) return spec;

  // Count before expanding: the product can be huge.
  double count = list.empty() ? 1.0 : static_cast<double>(list.size());
  for (const auto& g : grid_values) count *= static_cast<double>(g.size());
  if (count > static_cast<double>(kMaxSweepCases)) {
    d.error((grid != nullptr ? grid : cases)->loc, grid != nullptr ? "grid" : "cases",
            "expands to " + fmt_num(count) + " cases (at most " + std::to_string(kMaxSweepCases) + ")");
    return spec;
  }
  // Columns: the grid keys, then the list's keys in order of first appearance.
  spec.keys = grid_keys;
  for (const auto& c : list)
    for (const auto& o : c) {
      bool known = false;
      for (const auto& k : spec.keys) known = known || k == o.key;
      if (!known) spec.keys.push_back(o.key);
    }
  if (list.empty()) list.emplace_back();
  for (const auto& entry : list) {
    std::vector<std::size_t> idx(grid_values.size(), 0);
    while (true) {
      SweepCase c;
      std::vector<SourceLoc> cl;
      for (std::size_t g = 0; g < grid_values.size(); ++g) {
        c.sets.emplace_back(grid_values[g][idx[g]].key, grid_values[g][idx[g]].value);
        cl.push_back(grid_values[g][idx[g]].loc);
      }
      for (const auto& o : entry) {
        c.sets.emplace_back(o.key, o.value);
        cl.push_back(o.loc);
      }
      spec.cases.push_back(std::move(c));
      locs.cases.push_back(std::move(cl));
      // Next grid point, the last key fastest.
      std::size_t g = grid_values.size();
      while (g > 0 && ++idx[g - 1] == grid_values[g - 1].size()) idx[--g] = 0;
      if (g == 0) break;
    }
  }
  return spec;
}

/// A case's inputs for load_input().
InputOptions case_input(const SweepSpec& spec, const std::vector<std::string>& sets) {
  return InputOptions{spec.scenario, spec.example, sets};
}

/// Writes sweep.csv rows in case order as the cases complete.
class SweepTable {
 public:
  SweepTable(const std::string& path, const SweepSpec& spec, std::vector<std::string> figures)
      : spec_(spec), figures_(std::move(figures)), rows_(spec.cases.size()), done_(spec.cases.size(), false) {
    out_.open(path);
    if (!out_) throw std::runtime_error("cannot create " + path);
    std::string h = "case";
    for (const auto& k : spec.keys) h += "," + csv_field(k);
    h += ",status,message";
    for (const auto& f : figures_) h += "," + csv_field(f);
    out_ << h << "\n" << std::flush;
  }
  /// Record case i and write every complete row from the first unwritten one.
  void complete(std::size_t i, CaseResult r) {
    rows_[i] = std::move(r);
    done_[i] = true;
    while (next_ < rows_.size() && done_[next_]) write_row(next_++);
    out_.flush();
  }
  bool good() const { return static_cast<bool>(out_); }
  const std::vector<CaseResult>& rows() const { return rows_; }
  /// Every row as a towing table (towing_table_columns()); throws when it cannot be written.
  void write_towing_table(const std::string& path) const {
    std::ofstream t(path);
    std::string text = "case";
    for (const auto& k : spec_.keys) text += "," + csv_field(k);
    text += ",status";
    for (const auto& c : towing_table_columns()) text += "," + c;
    text += "\n";
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      text += std::to_string(i);
      append_keys(text, i);
      text += "," + csv_field(rows_[i].status);
      for (double v : towing_row(rows_[i].figures)) {
        text += ',';
        if (std::isfinite(v)) append_number(text, v);
      }
      text += "\n";
    }
    t << text;
    if (!t.flush()) throw std::runtime_error("cannot write " + path);
  }

 private:
  void write_row(std::size_t i) {
    const CaseResult& r = rows_[i];
    std::string line = std::to_string(i);
    append_keys(line, i);
    line += "," + csv_field(r.status) + "," + csv_field(r.message);
    for (const auto& name : figures_) {
      line += ',';
      for (const auto& [fname, v] : r.figures)
        if (fname == name && std::isfinite(v)) {
          append_number(line, v);
          break;
        }
    }
    out_ << line << "\n";
  }

  /// The varied keys' values of case i, each after a comma.
  void append_keys(std::string& line, std::size_t i) const {
    for (const auto& k : spec_.keys) {
      line += ',';
      for (const auto& [key, value] : spec_.cases[i].sets)
        if (key == k) line += csv_field(value);
    }
  }

  const SweepSpec& spec_;
  std::vector<std::string> figures_;
  std::vector<CaseResult> rows_;
  std::vector<bool> done_;
  std::size_t next_ = 0;
  std::ofstream out_;
};

}  // namespace

SweepSpec read_sweep(const std::string& path, Diagnostics& diags) {
  SweepLocs locs;
  return read_sweep_with_locs(path, diags, locs);
}

namespace {

/// A sweep file read and checked, as `towsim sweep` runs it.
struct CheckedSweep {
  SweepSpec spec;
  SweepLocs locs;
  LoadedScenario base;  // the base scenario with the common overrides
};

/// Read `file` and load the base scenario and the first `max_cases` cases
/// (each with its overrides; a steady-tow sweep's cases need a tow law):
/// false with every problem in `err` as FILE:LINE:COL messages, a case's
/// override errors at the override in the sweep file.
bool check_sweep(const std::string& file, std::ostream& err, CheckedSweep& c, std::size_t max_cases) {
  Diagnostics d;
  d.set_primary(file);
  c.spec = read_sweep_with_locs(file, d, c.locs);
  if (!d.ok()) {
    err << d.str();
    return false;
  }
  const SweepSpec& spec = c.spec;
  const SweepLocs& locs = c.locs;
  c.base = load_input(case_input(spec, spec.common));
  const LoadedScenario& base = c.base;
  if (!base.ok()) {
    Diagnostics moved;
    moved.set_primary(file);
    for (const auto& e : base.diags.list()) {
      const bool from_set = e.loc.file == "--set" && e.loc.line >= 1 &&
                            static_cast<std::size_t>(e.loc.line) <= locs.common.size();
      if (e.loc.file == "--example")
        moved.error(locs.example, "example", e.message);  // an unknown example: at its name in the sweep file
      else
        moved.error(from_set ? locs.common[static_cast<std::size_t>(e.loc.line) - 1] : e.loc, e.path, e.message);
    }
    err << moved.str();
    return false;
  }
  Diagnostics case_errors;
  case_errors.set_primary(file);
  std::set<std::string> reported;
  for (std::size_t i = 0; i < spec.cases.size() && i < max_cases; ++i) {
    const ExpandedCase e = expand(spec, locs.common, spec.cases[i], locs.cases[i]);
    const LoadedScenario sc = load_input(case_input(spec, e.sets));
    for (const auto& x : sc.diags.list()) {
      const bool from_set = x.loc.file == "--set" && x.loc.line >= 1 &&
                            static_cast<std::size_t>(x.loc.line) <= e.locs.size();
      const SourceLoc at = from_set ? e.locs[static_cast<std::size_t>(x.loc.line) - 1] : x.loc;
      const std::string msg = from_set ? x.message : x.message + " (" + case_name(i) + ")";
      if (reported.insert(Diagnostic{at, x.path, msg}.str()).second) case_errors.error(at, x.path, msg);
    }
    // A steady-tow sweep needs a tow law (mode: motion) in every case.
    if (spec.statics && sc.ok())
      if (const auto refusal = statics_refusal(sc)) {
        const bool from_set = refusal->loc.file == "--set" && refusal->loc.line >= 1 &&
                              static_cast<std::size_t>(refusal->loc.line) <= e.locs.size();
        const SourceLoc at = from_set ? e.locs[static_cast<std::size_t>(refusal->loc.line) - 1] : refusal->loc;
        const std::string msg = from_set ? refusal->message : refusal->message + " (" + case_name(i) + ")";
        if (reported.insert(Diagnostic{at, refusal->path, msg}.str()).second) case_errors.error(at, refusal->path, msg);
      }
  }
  if (!case_errors.ok()) {
    err << case_errors.str();
    return false;
  }
  return true;
}

}  // namespace

bool check_sweep_file(const std::string& file, std::ostream& err, std::size_t max_cases) {
  CheckedSweep c;
  return check_sweep(file, err, c, max_cases);
}

int sweep_command(const SweepOptions& opts, std::ostream& out, std::ostream& err, const volatile int* stop_flag) {
  CheckedSweep checked;
  if (!check_sweep(opts.file, err, checked, std::numeric_limits<std::size_t>::max())) return kExitInvalid;
  const SweepSpec& spec = checked.spec;
  const SweepLocs& locs = checked.locs;
  const LoadedScenario& base = checked.base;

  if (!create_output_dir(opts.out_dir, err)) return kExitError;
  const std::size_t n = spec.cases.size();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t jobs = std::min<std::size_t>(n, opts.jobs > 0 ? static_cast<std::size_t>(opts.jobs) : cores);
  try {
    SweepTable table((std::filesystem::path(opts.out_dir) / "sweep.csv").string(), spec,
                     base.is_network() ? network_figure_names(*base.network) : figure_names(*base.model));
    std::mutex mu;
    std::atomic<std::size_t> next{0};
    std::size_t completed = 0, failed = 0;
    std::vector<bool> started(n, false);
    const auto worker = [&] {
      while (true) {
        const std::size_t i = next++;
        if (i >= n || (stop_flag != nullptr && *stop_flag)) return;
        {
          std::lock_guard<std::mutex> lock(mu);
          started[i] = true;
        }
        const ExpandedCase e = expand(spec, locs.common, spec.cases[i], locs.cases[i]);
        const LoadedScenario sc = load_input(case_input(spec, e.sets));
        const std::string dir = spec.write_cases ? (std::filesystem::path(opts.out_dir) / case_name(i)).string()
                                                 : std::string();
        CaseResult r = spec.statics ? statics_case(sc, dir, stop_flag) : run_case(sc, dir, stop_flag);
        std::lock_guard<std::mutex> lock(mu);
        ++completed;
        if (r.status == "failed") ++failed;
        if (!opts.quiet)
          err << "[" << completed << "/" << n << "] " << case_name(i) << " " << r.status
              << (r.message.empty() ? "" : ": " + r.message) << "\n"
              << std::flush;
        table.complete(i, std::move(r));
      }
    };
    std::vector<std::thread> pool;
    for (std::size_t j = 0; j < jobs; ++j) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
    // Cases never started (interrupted sweep): rows all the same.
    for (std::size_t i = 0; i < n; ++i)
      if (!started[i]) table.complete(i, CaseResult{"not_run", "the sweep was interrupted before this case", {}, {}});
    if (!table.good()) throw std::runtime_error("cannot write " + opts.out_dir + "/sweep.csv");
    table.write_towing_table((std::filesystem::path(opts.out_dir) / "towing_table.csv").string());
    if (!opts.quiet)
      for (const std::string& w : trim_jumps(spec.cases, table.rows())) err << "towsim: sweep: warning: " << w << "\n";
    if (stop_flag != nullptr && *stop_flag) {
      err << "towsim: sweep interrupted after " << completed << " of " << n << " cases (rows so far in " << opts.out_dir
          << "/sweep.csv)\n";
      return kExitInterrupted;
    }
    if (!opts.quiet)
      out << "sweep: " << n << " cases on " << jobs << " threads, " << n - failed << " ok, " << failed << " failed -> "
          << opts.out_dir << "/sweep.csv\n";
  } catch (const std::exception& e) {
    err << "towsim: " << e.what() << "\n";
    return kExitError;
  }
  return kExitOk;
}

}  // namespace towsim::cli
