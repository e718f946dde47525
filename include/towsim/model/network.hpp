// A network of lines (docs/theory.md §5.7 "Trees of lines", docs/scenario.md
// "Networks"): lines, each a chain of its own Model, hanging from the
// vessel's tow points, from junctions (a line's cable end carrying a point
// mass) or from points of bodies (a line's end body); loops (a junction or
// body reached by a second line) closed by ball joints.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "towsim/model/model.hpp"

namespace towsim {

/// Where a line's top hangs.
struct LineTop {
  int line = -1;              // the line above (an index before this one), -1 = the vessel (a root)
  int body = -1;              // that line's body whose point it hangs from, -1 = its cable end (a junction)
  Vec3 point = Vec3::Zero();  // the body's point, body axes [m]
};

/// A loop's closing joint: the cable end of line `line` (its last joint
/// P_n, a free end in the tree) held by a ball joint to a node of the tree
/// reached by another path: the cable end of line `node_line` (a junction,
/// body = -1) or the point `point` of that line's body `body`.
struct LoopJoint {
  int line = -1;              // the line whose cable end closes the loop [-]
  int node_line = -1;         // the line whose node it is joined to [-]
  int body = -1;              // node_line's body, -1 = node_line's cable end [-]
  Vec3 point = Vec3::Zero();  // the body's point, body axes [m]
};

/// The compiled tree: lines in an order where each comes after the line it
/// hangs from. Root lines move with their tow law (Model::tow, its vessel
/// carrying the line's tow point); the others' tow laws are unused. A line
/// below the vessel has no winch. `loops` close loops over the tree.
struct TreeModel {
  std::vector<Model> lines;
  std::vector<LineTop> tops;     // one per line
  std::vector<LoopJoint> loops;  // the loops' closing joints (none: a tree)
};

/// A junction: a point mass where lines meet, the cable end of the line
/// into it (that line's Model carries it as the attachment at its end joint).
struct NetworkJunction {
  std::string name;  // output column prefix [-]
  int line = -1;     // the line whose cable end it is (TreeModel::lines index) [-]
};

/// A named body of the network: body `body` of line `line`'s Model (the
/// end body of the line into it, or an in-line body of that line).
struct NetworkBody {
  std::string name;  // output column prefix [-]
  int line = -1;     // TreeModel::lines index [-]
  int body = -1;     // index in that line's Model::bodies [-]
};

/// A compiled network: the tree and the names the outputs use. Every line's
/// Model carries the run's settings (fluid, seabed, simulation, initial).
struct Network {
  std::string name;                     // scenario name (file stem)
  TreeModel tree;                       // lines in tree order
  std::vector<std::string> line_names;  // per tree line [-]
  std::vector<std::string> line_from;   // per tree line, as written: vessel.<point>, <junction>, <body>.<point>
  std::vector<std::string> line_to;     // per tree line, as written: <junction>, <body>.<point>, free
  std::vector<std::string> tow_point;   // per tree line: its tow point's name (root lines), else empty
  std::vector<NetworkJunction> junctions;
  std::vector<NetworkBody> bodies;  // every body of every line, in tree order
  /// The run's settings (simulation, initial, fluid): those of the first line.
  const Model& settings() const { return tree.lines.front(); }
  /// True when a line has a winch (only a line from the vessel can).
  bool has_winch() const {
    return std::any_of(tree.lines.begin(), tree.lines.end(), [](const Model& m) { return m.winch.active(); });
  }
  /// The index of the line named `line` (TreeModel::lines), -1 when none is.
  int line_index(const std::string& line) const {
    const auto it = std::find(line_names.begin(), line_names.end(), line);
    return it == line_names.end() ? -1 : static_cast<int>(it - line_names.begin());
  }
};

}  // namespace towsim
