// Reading a network: lines:, bodies:, junctions: and vessel.tow_points
// (docs/scenario.md "Networks").
#include <string>
#include <vector>

#include "parse_sections.hpp"

namespace towsim::scenario {

void parse_points(MapReader& r, const std::string& key, std::vector<NamedPointSpec>& points, bool& given, Where& where,
                  Diagnostics& d) {
  const YNode* n = r.get(key);
  if (n == nullptr) return;
  given = true;
  where = r.where(*n, key);
  if (!n->is_map()) {
    d.error(n->loc, where.path, "expected a mapping NAME: [x, y, z] (got " + n->describe() + ")");
    return;
  }
  for (const YNode& v : n->items) {
    const YNode* first = n->find(v.key);
    const std::string path = join_path(where.path, v.key);
    if (first != &v) {
      d.error(v.key_loc, path, "duplicate key (first given at line " + std::to_string(first->key_loc.line) + ")");
      continue;
    }
    NamedPointSpec p;
    p.name.value = v.key;
    p.name.where = Where{v.key_loc, path};
    p.name.given = true;
    p.point.where = Where{v.loc, path};
    Vec3 x = Vec3::Zero();
    if (convert(v, path, d, x)) {
      p.point.value = x;
      p.point.given = true;
    }
    points.push_back(p);
  }
}

namespace {

void parse_junction(MapReader& r, JunctionSpec& j) {
  j.where = r.where();
  r.read("name", j.name, true);
  r.read("mass", j.mass);
  r.read("volume", j.volume);
  r.read("drag_area", j.drag_area);
  r.read("added_mass", j.added_mass);
}

void parse_line(MapReader& r, LineSpec& line, Diagnostics& d) {
  line.where = r.where();
  r.read("name", line.name, true);
  r.read("from", line.from, true);
  r.read("to", line.to, true);
  MapReader w(r.get("winch"), r.sub("winch"), d);
  line.winch.present = w.present();
  if (line.winch.present) parse_winch(w, line.winch, d);
  w.finish();
  parse_cable(r, line.cable, d);
}

/// A list that must not be empty: "the list is empty (...)" at `key`.
void check_not_empty(const YNode& root, const std::string& key, const std::string& advice, Diagnostics& d) {
  const YNode* n = root.find(key);
  if (n == nullptr) return;
  if (n->is_null() || (n->is_seq() && n->items.empty()))
    d.error(n->is_null() ? n->key_loc : n->loc, key, "the list is empty (" + advice + ")");
}

}  // namespace

void parse_network(MapReader& r, const YNode& root, ScenarioSpec& s, Diagnostics& d) {
  const YNode* lines = root.find("lines");
  const YNode* bodies = root.find("bodies");
  const YNode* junctions = root.find("junctions");
  if (!s.network) {
    // Accepted names for "did you mean" (not listed among a cable's keys).
    for (const char* key : {"lines", "bodies", "junctions"}) r.alias(key);
    if (bodies != nullptr)
      d.error(bodies->key_loc, "bodies",
              "needs lines: (bodies are the nodes of a network of lines; a single cable: takes one body:)");
    if (junctions != nullptr)
      d.error(junctions->key_loc, "junctions", "needs lines: (junctions join the lines of a network)");
    return;
  }
  s.lines_where = Where{lines->key_loc, "lines"};
  if (root.find("cable") != nullptr) d.error(lines->key_loc, "lines", "give either 'cable' or 'lines', not both");
  if (const YNode* body = root.find("body")) {
    if (bodies != nullptr)
      d.error(bodies->key_loc, "bodies", "give either 'body' or 'bodies', not both");
    else
      d.error(body->key_loc, "body",
              "a network names its bodies: give bodies: [{name: NAME, ...}] and to: NAME.<point>");
  }
  check_not_empty(root, "lines", "give at least one line, from: vessel.<tow point>", d);
  r.list("lines", [&](MapReader& item, std::size_t) {
    s.lines.emplace_back();
    parse_line(item, s.lines.back(), d);
  });
  if (bodies != nullptr) s.bodies_where = Where{bodies->key_loc, "bodies"};
  r.list("bodies", [&](MapReader& item, std::size_t) {
    s.bodies.emplace_back();
    NetworkBodySpec& b = s.bodies.back();
    item.get("name", true);
    b.body.present = true;
    parse_body(item, b.body, d, false);
    parse_points(item, "points", b.points, b.points_given, b.points_where, d);
  });
  if (junctions != nullptr) s.junctions_where = Where{junctions->key_loc, "junctions"};
  r.list("junctions", [&](MapReader& item, std::size_t) {
    s.junctions.emplace_back();
    parse_junction(item, s.junctions.back());
  });
}

void parse_tow_points(MapReader& r, const YNode* vessel, ScenarioSpec& s, Diagnostics& d) {
  if (vessel == nullptr || !vessel->is_map()) return;
  VesselSpec& v = s.vessel;
  if (!s.network) {
    if (const YNode* n = vessel->find("tow_points"))
      d.error(n->key_loc, "vessel.tow_points", "needs lines: (a single cable: hangs from vessel.tow_point)");
    r.alias("tow_points");
    return;
  }
  if (v.tow_point.given)
    d.error(v.tow_point.where.loc, v.tow_point.where.path,
            "a network names its tow points: give vessel.tow_points: {NAME: [x, y, z]} and from: vessel.NAME");
  parse_points(r, "tow_points", v.tow_points, v.tow_points_given, v.tow_points_where, d);
}

}  // namespace towsim::scenario
