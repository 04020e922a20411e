// One run of one experiment, the unit the harness plans, shards, runs and records: a scene, a
// strategy and one point of the sweep. Its own header so that the drivers (driver.h), which run
// items, and the suite files (suite_file.h), which expand into them, need not include each other.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace dv {

struct RunItem {
  int index = 0;  // position in the expanded list of the whole suite
  int experiment = 0;
  std::string experiment_name;
  std::string kind;
  std::string scene;       // as written
  std::string scene_path;  // resolved
  std::string strategy;
  std::map<std::string, std::string> params;  // fixed and swept together
  std::map<std::string, std::string> settings;
  // A deliberate duplicate of another item of its experiment (same scene, strategy, params and
  // settings), measured as an A/A control of the timings (aa_controls.h); rows.csv marks it
  // with the term "aa=copy" in `params`, which the strategy never sees.
  bool aa_copy = false;

  // "key=value" each, in key order.
  std::vector<std::string> param_items() const {
    std::vector<std::string> out;
    for (const auto& [key, value] : params) out.push_back(key + "=" + value);
    return out;
  }
  // "key=value key=value" in key order, then "aa=copy" for an A/A copy (the `params` column of
  // rows.csv).
  std::string params_text() const {
    std::string out;
    for (const std::string& item : param_items()) out += (out.empty() ? "" : " ") + item;
    if (aa_copy) out += std::string(out.empty() ? "" : " ") + "aa=copy";
    return out;
  }
  // "experiment: strategy key=value ... on scene", for progress lines and reports.
  std::string describe() const {
    return experiment_name + ": " + strategy + (params_text().empty() ? "" : " " + params_text()) +
           " on " + scene;
  }
};

}  // namespace dv
