// A user's program linking towsim::scenario and towsim::output: a built-in
// example read and compiled into a Model, and the timeseries.csv header.
#include <cstdio>
#include <string>

#include "towsim/output/output.hpp"
#include "towsim/scenario/examples.hpp"
#include "towsim/scenario/scenario.hpp"

int main() {
  using namespace towsim::scenario;
  using namespace towsim::output;
  const Example* ex = find_example(kDefaultExample);
  if (!ex) return std::printf("no built-in example %s\n", kDefaultExample), 1;
  const LoadedScenario sc = load_scenario_text(ex->yaml, ex->name + ".yaml", ex->name, ".");
  if (!sc.ok()) return std::printf("%s does not compile\n", ex->name.c_str()), 1;
  const std::string header = timeseries_header(*sc.model);
  std::printf("%s: %d elements; timeseries.csv starts \"%s\"\n", ex->name.c_str(), sc.model->cable.n(),
              header.substr(0, 20).c_str());
  return sc.model->cable.n() > 0 && header.rfind("time", 0) == 0 ? 0 : 1;
}
