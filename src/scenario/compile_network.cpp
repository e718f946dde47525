// ScenarioSpec with lines: -> Network (docs/scenario.md "Networks"): the
// names and ends checked, the lines put in tree order, and each line
// compiled as a single chain (cable: the line, body: the body at its end,
// winch: its winch) so that every check of a chain applies to it.
#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "checks.hpp"
#include "reader.hpp"
#include "towsim/scenario/compile.hpp"

namespace towsim::scenario {
namespace {

const std::string kLink = "link_point";
const std::string kLower = "lower_link_point";

std::size_t idx(int i) { return static_cast<std::size_t>(i); }

bool is_identifier(const std::string& n) {
  if (n.empty()) return false;
  return std::all_of(n.begin(), n.end(),
                     [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
}

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

void report(const Where& w, Diagnostics& d, const std::string& msg) { d.error(w.loc, w.path, msg); }

/// " (did you mean 'x'?)" or " (" + what + ": a, b)" or " (" + none + ")".
std::string hint(const std::string& word, const std::vector<std::string>& candidates, const std::string& what,
                 const std::string& none) {
  const std::string m = closest_match(word, candidates);
  if (!m.empty()) return " (did you mean '" + m + "'?)";
  if (candidates.empty()) return " (" + none + ")";
  return " (" + what + ": " + join(candidates) + ")";
}

/// A node of the network that lines may name.
struct Node {
  enum class Kind { Junction, Body, Inline } kind = Kind::Junction;
  int index = -1;  // junction, network body, or (Inline) the line holding it (spec order)
  int sub = -1;    // Inline: its index among that line's in-line bodies
  Where where;     // where it is named
};

/// A line's end as resolved.
struct End {
  enum class Kind { None, Vessel, Junction, Body, Inline, Free } kind = Kind::None;
  int index = -1;          // tow point, junction, network body; Inline: the line holding it
  int sub = -1;            // Inline: index among that line's in-line bodies
  std::string point;       // Body, Inline: the point's name
  Vec3 at = Vec3::Zero();  // tow point [vessel axes] or body point [body axes]
  Where at_where;          // where that point's value is written
  std::string name;        // the junction's or body's name
  bool ok() const { return kind != Kind::None; }
  bool node() const { return kind == Kind::Junction || kind == Kind::Body || kind == Kind::Inline; }
  /// Identity of the node (junction or body) for ownership.
  std::string key() const {
    switch (kind) {
      case Kind::Junction:
        return "j" + std::to_string(index);
      case Kind::Body:
        return "b" + std::to_string(index);
      case Kind::Inline:
        return "i" + std::to_string(index) + "." + std::to_string(sub);
      default:
        return "";
    }
  }
};

struct Context {
  const ScenarioSpec& s;
  std::map<std::string, Node> nodes;  // junctions, network bodies, named in-line bodies
  std::vector<std::string> tow_point_names;
};

/// A network body's named points: its `points`, and link_point and
/// lower_link_point when given.
std::vector<std::pair<std::string, const Field<Vec3>*>> body_points(const NetworkBodySpec& b) {
  std::vector<std::pair<std::string, const Field<Vec3>*>> out;
  for (const NamedPointSpec& p : b.points) out.emplace_back(p.name.value, &p.point);
  if (b.body.link_point.given) out.emplace_back(kLink, &b.body.link_point);
  if (b.body.lower_link_point.given) out.emplace_back(kLower, &b.body.lower_link_point);
  return out;
}

/// Resolve `from` (to = false) or `to`; reports and returns Kind::None when it names nothing usable.
End resolve(const Field<std::string>& f, bool to, const Context& c, Diagnostics& d) {
  End e;
  if (!f.given) return e;
  const std::string& text = f.value;
  const Where& w = f.where;
  if (text == "free") {
    if (to)
      e.kind = End::Kind::Free;
    else
      report(w, d, "'free' is only for to: (a line's top hangs from vessel.<tow point>, a junction or a body's point)");
    return e;
  }
  const auto dot = text.find('.');
  const std::string head = text.substr(0, dot);
  const std::string tail = dot == std::string::npos ? "" : text.substr(dot + 1);
  if (head == "vessel") {
    if (to) {
      report(w, d, "a line cannot end at the vessel (write it from the vessel: from: " + text + ")");
      return e;
    }
    const auto& names = c.tow_point_names;
    if (dot == std::string::npos) {
      report(w, d,
             "give the tow point: vessel.<tow point>" +
                 (names.empty() ? std::string(" (the vessel has none: give vessel.tow_points: {NAME: [x, y, z]})")
                                : " (one of " + join(names) + ")"));
      return e;
    }
    const auto it = std::find(names.begin(), names.end(), tail);
    if (it == names.end()) {
      report(w, d,
             "unknown tow point '" + tail + "'" +
                 hint(tail, names, "tow points", "the vessel has none: give vessel.tow_points: {NAME: [x, y, z]}"));
      return e;
    }
    e.kind = End::Kind::Vessel;
    e.index = static_cast<int>(it - names.begin());
    const NamedPointSpec& tp = c.s.vessel.tow_points[idx(e.index)];
    e.at = tp.point.value;
    e.at_where = tp.point.where;
    e.point = tail;
    return e;
  }
  const auto n = c.nodes.find(head);
  if (n == c.nodes.end()) {
    std::vector<std::string> names;
    for (const auto& [name, node] : c.nodes) names.push_back(name);
    std::vector<std::string> candidates = names;
    candidates.push_back("vessel");
    if (to) candidates.push_back("free");
    const std::string m = closest_match(head, candidates);
    report(w, d,
           "unknown junction or body '" + head + "'" +
               (!m.empty()      ? " (did you mean '" + m + "'?)"
                : names.empty() ? std::string(" (there are no junctions or bodies)")
                                : " (junctions and bodies: " + join(names) + ")"));
    return e;
  }
  const Node& node = n->second;
  e.name = head;
  if (node.kind == Node::Kind::Junction) {
    if (dot != std::string::npos) {
      report(w, d, "'" + head + "' is a junction: write " + head + " (a junction has no points)");
      return e;
    }
    e.kind = End::Kind::Junction;
    e.index = node.index;
    return e;
  }
  // A body: one of its points.
  std::vector<std::pair<std::string, const Field<Vec3>*>> points;
  if (node.kind == Node::Kind::Body) {
    points = body_points(c.s.bodies[idx(node.index)]);
  } else {
    const BodySpec& b = c.s.lines[idx(node.index)].cable.inline_bodies[idx(node.sub)];
    points = {{kLink, &b.link_point}, {kLower, &b.lower_link_point}};
  }
  std::vector<std::string> names;
  for (const auto& p : points) names.push_back(p.first);
  const std::string what = node.kind == Node::Kind::Body ? "body" : "in-line body";
  if (dot == std::string::npos) {
    report(w, d,
           "'" + head + "' is a " + what + ": give one of its points, " + head + ".<point>" +
               (names.empty() ? " (it has none: give " + head + ".points: {NAME: [x, y, z]})"
                              : " (one of " + join(names) + ")"));
    return e;
  }
  const auto p = std::find_if(points.begin(), points.end(), [&](const auto& x) { return x.first == tail; });
  if (p == points.end()) {
    const bool link_key = tail == kLink || tail == kLower;
    report(w, d,
           link_key ? "the " + what + " '" + head + "' has no " + tail + " (give it the key " + tail + ")"
                    : "unknown point '" + tail + "' of " + what + " '" + head + "'" +
                          hint(tail, names, "its points", "it has none: give " + head + ".points: {NAME: [x, y, z]}"));
    return e;
  }
  e.kind = node.kind == Node::Kind::Body ? End::Kind::Body : End::Kind::Inline;
  e.index = node.index;
  e.sub = node.sub;
  e.point = tail;
  e.at = p->second->value;
  e.at_where = p->second->where;
  return e;
}

/// Names: identifiers, distinct, none reserved; fills the node table.
void check_names(Context& c, Diagnostics& d) {
  const ScenarioSpec& s = c.s;
  const auto ident = [&](const Field<std::string>& f, const std::string& why) {
    if (!f.given) return false;
    if (is_identifier(f.value)) return true;
    report(f.where, d, "must be letters, digits and _ (" + why + ")");
    return false;
  };
  // Tow points.
  for (const NamedPointSpec& tp : s.vessel.tow_points) {
    if (ident(tp.name, "lines name it as vessel." + tp.name.value))
      c.tow_point_names.push_back(tp.name.value);
    else
      c.tow_point_names.push_back("");
  }
  // Lines.
  std::map<std::string, std::size_t> lines;
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const Field<std::string>& n = s.lines[i].name;
    if (!ident(n, "it prefixes output columns")) continue;
    const auto [it, fresh] = lines.emplace(n.value, i);
    if (!fresh)
      report(n.where, d,
             "'" + n.value + "' is already the name of lines." + std::to_string(it->second) +
                 " (line names must be distinct)");
  }
  // Junctions, bodies and named in-line bodies share one set of names.
  const auto add = [&](const Field<std::string>& n, const Node& node, const std::string& what) {
    if (!ident(n, "it prefixes output columns")) return;
    if (n.value == "vessel" || n.value == "free") {
      report(n.where, d, "'" + n.value + "' is reserved (from: vessel.<tow point>, to: free)");
      return;
    }
    const auto [it, fresh] = c.nodes.emplace(n.value, node);
    if (!fresh)
      report(n.where, d,
             "'" + n.value + "' is already the name of " + it->second.where.path +
                 " (junction and body names must be distinct" + what + ")");
  };
  for (std::size_t j = 0; j < s.junctions.size(); ++j)
    add(s.junctions[j].name, Node{Node::Kind::Junction, static_cast<int>(j), -1, s.junctions[j].where}, "");
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const NetworkBodySpec& nb = s.bodies[b];
    add(nb.body.name, Node{Node::Kind::Body, static_cast<int>(b), -1, nb.body.where}, "");
    for (const NamedPointSpec& p : nb.points) {
      if (!ident(p.name, "lines name it as " + nb.body.name.value + "." + p.name.value)) continue;
      if (p.name.value == kLink || p.name.value == kLower)
        report(p.name.where, d, "'" + p.name.value + "' is the body's own key (give the point another name)");
    }
  }
  for (std::size_t i = 0; i < s.lines.size(); ++i) {
    const auto& inl = s.lines[i].cable.inline_bodies;
    for (std::size_t k = 0; k < inl.size(); ++k)
      if (inl[k].present && inl[k].name.given && is_identifier(inl[k].name.value))
        add(inl[k].name, Node{Node::Kind::Inline, static_cast<int>(i), static_cast<int>(k), inl[k].where},
            ", in-line bodies' too");
  }
}

/// The total length of a line as written [m].
double line_length(const CableSpec& c) {
  if (c.sections.empty()) return c.length.value;
  double total = 0;
  for (const SectionSpec& s : c.sections) total += s.length.value;
  return total;
}

/// Copy d's new errors (after `from`) of `local` into d, each once.
void merge(const Diagnostics& local, std::size_t from, std::set<std::string>& seen, Diagnostics& d) {
  for (std::size_t k = from; k < local.size(); ++k) {
    const Diagnostic& e = local.list()[k];
    if (seen.insert(e.str()).second) d.error(e.loc, e.path, e.message);
  }
}

}  // namespace

std::optional<Network> compile_network(const ScenarioSpec& s, Diagnostics& d) {
  const std::size_t nl = s.lines.size();
  if (nl == 0) {
    if (d.ok()) report(s.lines_where, d, "the list is empty (give at least one line, from: vessel.<tow point>)");
    return std::nullopt;
  }
  Context c{s, {}, {}};
  check_names(c, d);
  // Network-wide rules.
  if (s.tow.mode.value == "force")
    report(s.tow.mode.where, d, "a network is towed by its motion (use mode: motion; a force pulls a single cable)");
  if (s.simulation.formulation.value == "paper")
    report(s.simulation.formulation.where, d,
           "a network needs formulation: default (the paper formulation has one cable)");
  for (const JunctionSpec& j : s.junctions) {
    check_non_negative(j.mass, d);
    check_non_negative(j.volume, d);
    check_non_negative(j.drag_area, d);
    check_non_negative(j.added_mass, d);
  }
  // Ends.
  std::vector<End> from(nl), to(nl);
  bool ends_ok = true, any_root = false;
  for (std::size_t i = 0; i < nl; ++i) {
    from[i] = resolve(s.lines[i].from, false, c, d);
    to[i] = resolve(s.lines[i].to, true, c, d);
    ends_ok = ends_ok && from[i].ok() && to[i].ok();
    any_root = any_root || from[i].kind == End::Kind::Vessel;
    if (from[i].node() && to[i].node() && from[i].key() == to[i].key())
      report(s.lines[i].to.where, d,
             "the line starts and ends at '" + to[i].name + "' (a line joins two different nodes)"),
          ends_ok = false;
  }
  if (ends_ok && !any_root)
    report(s.lines_where, d, "no line hangs from the vessel (give one from: vessel.<tow point>)");
  // Two lines into one point of a body.
  std::map<std::string, std::size_t> into_point;  // body key + point -> the first line into it
  for (std::size_t i = 0; i < nl; ++i) {
    if (to[i].kind != End::Kind::Body && to[i].kind != End::Kind::Inline) continue;
    for (std::size_t k = 0; k < i; ++k) {
      if (to[k].key() != to[i].key()) continue;
      if (to[k].point == to[i].point || to[k].at == to[i].at) {
        report(s.lines[i].to.where, d,
               "line " + s.lines[k].name.value + " already ends at " + s.lines[k].to.value +
                   (to[k].point == to[i].point ? "" : " (the same point)") +
                   ": two lines into one point of a body, use a junction");
        ends_ok = false;
        break;
      }
    }
  }
  // Every body and junction reached by a line.
  const auto touched = [&](End::Kind kind, int index) {
    for (std::size_t i = 0; i < nl; ++i)
      if ((from[i].kind == kind && from[i].index == index) || (to[i].kind == kind && to[i].index == index)) return true;
    return false;
  };
  for (std::size_t j = 0; j < s.junctions.size(); ++j)
    if (s.junctions[j].name.given && !touched(End::Kind::Junction, static_cast<int>(j)))
      report(s.junctions[j].where, d,
             "'" + s.junctions[j].name.value +
                 "' is not reached from the vessel (no line has to: " + s.junctions[j].name.value + ")");
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const BodySpec& body = s.bodies[b].body;
    if (!body.name.given || touched(End::Kind::Body, static_cast<int>(b))) continue;
    report(body.where, d,
           "'" + body.name.value + "' is not reached from the vessel (no line has to: " + body.name.value +
               ".<point>)");
    check_body(body, d);  // its values reported too
  }
  // Winches only from the vessel.
  for (std::size_t i = 0; i < nl; ++i)
    if (s.lines[i].winch.present && from[i].ok() && from[i].kind != End::Kind::Vessel)
      report(s.lines[i].winch.where, d,
             "a winch is only at a line's top on the vessel (this line hangs from " + s.lines[i].from.value + ")");
  // Tree order: a line after the line whose end (or body) it hangs from;
  // the first line into a junction or body carries it, a later one closes a loop.
  std::vector<int> tree_of(nl, -1);  // spec index -> tree index
  std::vector<std::size_t> order;    // tree index -> spec index
  std::map<std::string, std::size_t> owner;
  std::vector<bool> closes(nl, false);
  const auto available = [&](std::size_t i) {
    switch (from[i].kind) {
      case End::Kind::Vessel:
        return true;
      case End::Kind::Junction:
      case End::Kind::Body:
        return owner.count(from[i].key()) > 0;
      case End::Kind::Inline:
        return tree_of[idx(from[i].index)] >= 0;
      default:
        return false;
    }
  };
  if (ends_ok) {
    for (bool progress = true; progress;) {
      progress = false;
      for (std::size_t i = 0; i < nl; ++i) {
        if (tree_of[i] >= 0 || !available(i)) continue;
        tree_of[i] = static_cast<int>(order.size());
        order.push_back(i);
        progress = true;
        if (to[i].kind == End::Kind::Inline || (to[i].node() && owner.count(to[i].key())))
          closes[i] = true;
        else if (to[i].node())
          owner.emplace(to[i].key(), i);
      }
    }
    // The lines left: below a node no line reaches, or in a cycle that does not reach the vessel.
    const auto into = [&](std::size_t i) {  // the lines that hold line i's top node
      std::vector<std::size_t> out;
      if (from[i].kind == End::Kind::Inline) {
        out.push_back(idx(from[i].index));
        return out;
      }
      for (std::size_t k = 0; k < nl; ++k)
        if (to[k].node() && to[k].key() == from[i].key()) out.push_back(k);
      return out;
    };
    for (std::size_t i = 0; i < nl; ++i) {
      if (tree_of[i] >= 0) continue;
      const std::vector<std::size_t> above = into(i);
      if (above.empty()) {
        report(s.lines[i].from.where, d,
               "nothing holds '" + from[i].name + "': no line ends at it (give a line to: " +
                   (from[i].kind == End::Kind::Junction ? from[i].name : from[i].name + ".<point>") + ")");
        continue;
      }
      // Up the lines above: back to this line = a cycle.
      std::set<std::size_t> seen;
      std::vector<std::size_t> stack = above;
      bool cycle = false;
      while (!stack.empty() && !cycle) {
        const std::size_t k = stack.back();
        stack.pop_back();
        if (k == i) cycle = true;
        if (!seen.insert(k).second) continue;
        for (std::size_t u : into(k)) stack.push_back(u);
      }
      if (cycle)
        report(s.lines[i].from.where, d,
               "'" + from[i].name +
                   "' hangs below this line itself (its lines form a cycle that does not reach the vessel)");
    }
    // Winches: not on a line of a loop (its length is a side of the loop).
    std::vector<int> parent(nl, -1);  // spec index -> spec index of the line above, -1 = the vessel
    for (std::size_t i = 0; i < nl; ++i) {
      if (from[i].kind == End::Kind::Inline)
        parent[i] = from[i].index;
      else if (from[i].node() && owner.count(from[i].key()))
        parent[i] = static_cast<int>(owner.at(from[i].key()));
    }
    const auto path_up = [&](std::size_t i) {
      std::set<std::size_t> p;
      for (int k = static_cast<int>(i); k >= 0 && p.insert(idx(k)).second; k = parent[idx(k)]) {
      }
      return p;
    };
    for (std::size_t i = 0; i < nl; ++i) {
      if (!closes[i]) continue;
      const std::size_t node_line = to[i].kind == End::Kind::Inline ? idx(to[i].index) : owner.at(to[i].key());
      const std::set<std::size_t> a = path_up(i), b = path_up(node_line);
      for (std::size_t k = 0; k < nl; ++k)
        if ((a.count(k) != b.count(k)) && s.lines[k].winch.present && from[k].kind == End::Kind::Vessel)
          report(s.lines[k].winch.where, d,
                 "not on a line of a loop (line " + s.lines[i].name.value + " closes a loop at " + s.lines[i].to.value +
                     " that this line is part of)");
    }
  }
  // Each line as a single chain: every check of a cable, body and winch,
  // under the line's own keys. Errors common to the lines (environment,
  // tow, simulation) are reported once.
  std::set<std::string> seen;
  for (const Diagnostic& e : d.list()) seen.insert(e.str());
  const bool vessel_motion = s.vessel.present && (s.vessel.raos_given || s.vessel.motions_given);
  Network net;
  net.name = s.name;
  std::vector<std::size_t> spec_of;  // tree order, or file order when the tree is not built
  if (d.ok() && order.size() == nl) {
    spec_of = order;
  } else {
    for (std::size_t i = 0; i < nl; ++i) spec_of.push_back(i);
  }
  for (const std::size_t i : spec_of) {
    const LineSpec& line = s.lines[i];
    ScenarioSpec ls;
    ls.name = line.name.value;
    ls.description = s.description;
    ls.base_dir = s.base_dir;
    ls.root = s.root;
    ls.environment = s.environment;
    ls.tow = s.tow;
    ls.initial = s.initial;
    ls.simulation = s.simulation;
    ls.waves = s.waves;
    ls.vessel = s.vessel;
    ls.vessel.present = vessel_motion;
    ls.vessel.tow_points.clear();
    ls.vessel.tow_points_given = false;
    ls.vessel.tow_point = Field<Vec3>(Vec3::Zero());
    if (from[i].kind == End::Kind::Vessel) {
      // The root's tow point as the vessel's sheave; without a vessel
      // motion, a record of zero motions carries it (none for [0, 0, 0]:
      // the tow law's point itself).
      ls.vessel.tow_point.value = from[i].at;
      ls.vessel.tow_point.where = from[i].at_where;
      ls.vessel.tow_point.given = true;
      if (!vessel_motion && from[i].at != Vec3::Zero() && s.tow.mode.value == "motion") {
        ls.vessel.present = true;
        ls.vessel.where = Where{from[i].at_where.loc, "vessel"};
        ls.vessel.rotations = Field<std::string>("small_angle");
        ls.vessel.raos_given = false;
        ls.vessel.raos.clear();
        ls.vessel.motions_given = true;
        ls.vessel.motions_where = from[i].at_where;
        ls.vessel.motions = {RowSpec{{0, 0, 0, 0, 0, 0, 0}, from[i].at_where}};
      }
    }
    ls.cable = line.cable;
    ls.winch = line.winch;
    if (to[i].kind == End::Kind::Body && !closes[i]) {
      ls.body = s.bodies[idx(to[i].index)].body;
      ls.body.link_point.value = to[i].at;
      ls.body.link_point.where = to[i].at_where;
      ls.body.link_point.given = true;
      ls.body.lower_link_point.given = false;  // a point lines below may hang from
    }
    if (to[i].kind == End::Kind::Junction && !closes[i]) {
      const JunctionSpec& j = s.junctions[idx(to[i].index)];
      AttachmentSpec a;
      a.where = j.where;
      a.at.value = line_length(line.cable);
      a.at.where = j.where;  // not `given`: the line's end, by construction
      a.mass = j.mass;
      a.volume = j.volume;
      a.drag_area = j.drag_area;
      a.added_mass = j.added_mass;
      ls.cable.attachments.push_back(a);
    }
    Diagnostics local = d;
    const std::size_t before = local.size();
    std::optional<Model> m = compile(ls, local);
    merge(local, before, seen, d);
    if (!m || !d.ok()) continue;
    // Body names: the end body's, an unnamed in-line body's prefixed by the line.
    for (std::size_t k = 0; k < line.cable.inline_bodies.size() && k < m->bodies.size(); ++k)
      if (!line.cable.inline_bodies[k].name.given) m->bodies[k].name = line.name.value + "_" + m->bodies[k].name;
    if (ls.body.present) m->bodies.back().name = ls.body.name.value;
    net.tree.lines.push_back(std::move(*m));
  }
  if (!d.ok() || order.size() != nl || net.tree.lines.size() != nl) return std::nullopt;
  // Tops, loops and names.
  const auto body_of = [&](const End& e) {  // the node's body index in its line's Model
    if (e.kind == End::Kind::Inline) return e.sub;
    return static_cast<int>(net.tree.lines[idx(tree_of[owner.at(e.key())])].bodies.size()) - 1;
  };
  const auto line_of = [&](const End& e) {
    return e.kind == End::Kind::Inline ? tree_of[idx(e.index)] : tree_of[owner.at(e.key())];
  };
  std::set<std::string> names;
  for (std::size_t t = 0; t < nl; ++t) {
    const std::size_t i = order[t];
    const End& f = from[i];
    LineTop top;
    if (f.node()) {
      top.line = line_of(f);
      top.body = f.kind == End::Kind::Junction ? -1 : body_of(f);
      top.point = f.kind == End::Kind::Junction ? Vec3::Zero() : f.at;
    }
    net.tree.tops.push_back(top);
    if (closes[i]) {
      const End& e = to[i];
      LoopJoint j;
      j.line = static_cast<int>(t);
      j.node_line = line_of(e);
      j.body = e.kind == End::Kind::Junction ? -1 : body_of(e);
      j.point = e.kind == End::Kind::Junction ? Vec3::Zero() : e.at;
      net.tree.loops.push_back(j);
    }
    net.line_names.push_back(s.lines[i].name.value);
    net.line_from.push_back(s.lines[i].from.value);
    net.line_to.push_back(s.lines[i].to.value);
    net.tow_point.push_back(f.kind == End::Kind::Vessel ? f.point : "");
    const Model& m = net.tree.lines[t];
    for (std::size_t k = 0; k < m.bodies.size(); ++k) {
      net.bodies.push_back(NetworkBody{m.bodies[k].name, static_cast<int>(t), static_cast<int>(k)});
      if (!names.insert(m.bodies[k].name).second)
        report(s.lines[i].where, d,
               "the in-line body name '" + m.bodies[k].name + "' is already used (give the body a name: key)");
    }
  }
  for (std::size_t j = 0; j < s.junctions.size(); ++j) {
    End e;
    e.kind = End::Kind::Junction;
    e.index = static_cast<int>(j);
    net.junctions.push_back(NetworkJunction{s.junctions[j].name.value, line_of(e)});
  }
  if (!d.ok()) return std::nullopt;
  return net;
}

}  // namespace towsim::scenario
