// What experiments, `deepvox advise` and the plots need of a registered strategy beyond its
// parameter table: the plot family it belongs to (with the family's colour) and its marker, the
// parameter that names the strategy it is plotted as (the dsm method by its storage), its size
// knob (a parameter and its values, coarse to fine: what advise searches and a suite's
// "sizes" sweeps) and, for a storage that advise leaves out, why. Each family's registry file
// declares its strategies' traits beside their registration; a strategy without an entry gets
// the family's fallback traits, so it still reaches suites, advise and plots.
#pragma once

#include <string>
#include <vector>

namespace dv {

// Every member has a default initializer, so a table entry names only its leading members.
struct StrategyTraits {
  std::string family{};              // plot family, e.g. "DSM, fixed-size records"
  std::string colour{};              // the family's colour (a matplotlib colour)
  std::string marker{};              // matplotlib marker; empty: the plots pick a spare one
  std::string member_param{};        // a parameter naming the strategy it is plotted as ("storage")
  std::string size_key{};            // the size knob, a parameter of the strategy; empty: none
  std::vector<std::string> sizes{};  // its values, coarse (cheap) to fine
  std::string not_advised{};         // empty: advise searches it; else why not
};

}  // namespace dv
