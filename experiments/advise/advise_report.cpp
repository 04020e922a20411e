// Tables, JSON and the SVG plot of an advice (advise_report.h).
#include "experiments/advise/advise_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/number_text.h"

namespace dv {

namespace {

// `text` left-aligned in a table column `width` characters wide.
std::string column(std::string text, size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text;
}

}  // namespace

nlohmann::json measurement_json(const AdviseMeasurement& m) {
  if (!m.ok) return {{"ok", false}, {"failure", m.failure}};
  nlohmann::json strata = nlohmann::json::object();
  for (Stratum s : kAllStrata) {
    const StratumError& e = m.strata[size_t(s)];
    strata[to_string(s)] = {{"count", e.count}, {"p95", e.p95}, {"max", e.max}, {"few", e.few}};
  }
  return {{"ok", true},
          {"error_p95", m.error_p95},
          {"error_max", m.error_max},
          {"worst_stratum", to_string(m.worst_stratum())},
          {"strata", strata},
          {"shadows_measured", m.shadows_measured},
          {"rejected_at_fresh_points", m.rejected_at_fresh_points},
          {"image_rmse", m.image_rmse},
          {"image_edge", m.image_edge},
          {"frame_ms", m.frame_ms},
          {"bytes", m.bytes}};
}

std::vector<size_t> stratum_front(const std::vector<AdviseResult>& results, Stratum s) {
  std::vector<size_t> order;
  for (size_t i = 0; i < results.size(); ++i) {
    const AdviseMeasurement& m = results[i].measurement;
    if (m.ok && m.strata[size_t(s)].count > 0 && std::isfinite(m.frame_ms)) order.push_back(i);
  }
  const auto error = [&](size_t i) { return results[i].measurement.strata[size_t(s)].judged(); };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const AdviseMeasurement &x = results[a].measurement, &y = results[b].measurement;
    return x.frame_ms != y.frame_ms ? x.frame_ms < y.frame_ms : error(a) < error(b);
  });
  std::vector<size_t> front;
  for (size_t i : order)
    if (front.empty() || error(i) < error(front.back())) front.push_back(i);
  return front;
}

std::string strata_text(const AdviseMeasurement& m) {
  std::string text = "per stratum:";
  for (Stratum s : kAllStrata) {
    const StratumError& e = m.strata[size_t(s)];
    if (e.count == 0) continue;
    text += std::string(" ") + to_string(s) + (e.few ? " max " : " p95 ") +
            significant_text(e.judged(), 4) + " (" + std::to_string(e.count) + ")";
  }
  return text + "; worst " + to_string(m.worst_stratum()) + " " + significant_text(m.error_p95, 4);
}

std::string advice_table(const Advice& a, const AdviseBudgets& budgets) {
  std::ostringstream out;
  out << "probe strata: " << a.strata_counts << "\n";
  out << "Pareto front (" << a.front.size() << " of " << a.results.size()
      << " measured; p95 |T' - T| per stratum over every light, p95 the worst of them (the max "
         "where a stratum has too few points); image RMSE and edge error at "
      << a.width << "x" << a.height << "):\n";
  out << "   p95       lit       umbra     partial   media     edge     rmse     frame ms   MB  "
         "     configuration\n";
  const auto stratum = [](const AdviseMeasurement& m, Stratum s) {
    const StratumError& e = m.strata[size_t(s)];
    return e.count == 0 ? std::string("-         ")
                        : column(significant_text(e.judged(), 4), 9) + " ";
  };
  for (size_t i : a.front) {
    const AdviseResult& r = a.results[i];
    const AdviseMeasurement& m = r.measurement;
    const bool pick = a.pick && *a.pick == i;
    out << (pick                ? "=> "
            : budgets.met_by(m) ? " + "
                                : "   ")
        << column(significant_text(m.error_p95, 4), 9) + " " << stratum(m, Stratum::lit)
        << stratum(m, Stratum::umbra) << stratum(m, Stratum::partial) << stratum(m, Stratum::media)
        << column(fixed_text(m.image_edge, 4), 8) + " "
        << column(fixed_text(m.image_rmse, 4), 8) + " "
        << column(fixed_text(m.frame_ms, 3), 10) + " "
        << column(fixed_text(m.bytes / 1e6, 2), 8) + " " << r.config.param_line()
        << (a.default_index && *a.default_index == i ? " (default)" : "")
        << (m.rejected_at_fresh_points ? " (rejected at fresh points)" : "") << "\n";
  }
  out << "(=> the pick, + meets the bound " << budgets.error << " in every stratum";
  if (budgets.image_error)
    out << " and edge error " << fixed_text(*budgets.image_error, 4)
        << (a.default_index ? " (the default's)" : "");
  if (budgets.frame_ms) out << " and " << *budgets.frame_ms << " ms";
  if (budgets.bytes) out << " and " << *budgets.bytes / 1e6 << " MB";
  out << ")\n";
  if (a.pick) {
    const AdviseMeasurement& m = a.results[*a.pick].measurement;
    out << "pick: " << a.results[*a.pick].config.param_line() << "\n  search p95 "
        << significant_text(m.error_p95, 4) << ", verified p95 at fresh points (seed "
        << a.verify_seed << ") " << significant_text(a.verified.error_p95, 4)
        << " <= " << budgets.error << ", worst stratum " << to_string(a.verified.worst_stratum())
        << ", edge " << fixed_text(m.image_edge, 4) << ", " << fixed_text(a.chosen_ms(*a.pick), 3)
        << " ms, " << fixed_text(m.bytes / 1e6, 2) << " MB\n";
    out << "  verified " << strata_text(a.verified)
        << "\n  fresh points: " << a.verified_strata_counts << "\n";
  } else if (a.tried) {
    out << "no pick: the cheapest candidates' verified p95 ("
        << significant_text(a.verified.error_p95, 4) << " in "
        << to_string(a.verified.worst_stratum()) << " for "
        << a.results[*a.tried].config.param_line() << ") misses " << budgets.error << "\n";
  } else {
    out << "no pick: no measured configuration meets the bound and budgets\n";
  }
  if (!a.final_timing.empty()) {
    out << "final timing (" << a.final_timing.front().times_ms.size()
        << " interleaved rounds; median ms, search ms):\n";
    for (const Advice::FinalTiming& t : a.final_timing)
      out << (a.pick && *a.pick == t.index ? "=> " : "   ")
          << column(fixed_text(t.median_ms, 3), 9) + " "
          << column(fixed_text(a.results[t.index].measurement.frame_ms, 3), 9) + " "
          << a.results[t.index].config.param_line() << "\n";
  }
  if (a.interrupted) out << "(interrupted: the front holds what was measured)\n";
  return out.str();
}

nlohmann::json pick_notes(const Advice& a, const AdviseOptions& o) {
  nlohmann::json advice = {
      {"scene", o.scene}, {"error_bound", o.budgets.error}, {"metric", kAdviseMetric}};
  if (a.pick) {
    advice["search"] = measurement_json(a.results[*a.pick].measurement);
    advice["verified"] = measurement_json(a.verified);
    advice["verify_seed"] = a.verify_seed;
  }
  return {{"advice", advice}};
}

nlohmann::json advice_json(const Advice& a, const AdviseOptions& o) {
  nlohmann::json j = {{"scene", o.scene},
                      {"image", {a.width, a.height}},
                      {"lights", a.light_count},
                      {"error_bound", o.budgets.error},
                      {"exhaustive", o.exhaustive},
                      {"interrupted", a.interrupted},
                      {"seconds", a.seconds},
                      {"probes", o.settings.probes},
                      {"seed", o.settings.seed},
                      {"results", nlohmann::json::array()},
                      {"front", a.front}};
  j["metric"] = kAdviseMetric;
  j["strata_counts"] = a.strata_counts;
  j["stratum_min"] = o.settings.stratum_min;
  if (a.budgets.image_error) j["image_bound"] = *a.budgets.image_error;
  j["default_index"] = a.default_index ? nlohmann::json(*a.default_index) : nlohmann::json();
  if (o.budgets.frame_ms) j["budget_ms"] = *o.budgets.frame_ms;
  if (o.budgets.bytes) j["budget_bytes"] = *o.budgets.bytes;
  for (const AdviseResult& r : a.results)
    j["results"].push_back({{"shadows", r.config.to_json()["shadows"]},
                            {"param_line", r.config.param_line()},
                            {"measured", measurement_json(r.measurement)}});
  j["strata_fronts"] = nlohmann::json::object();
  for (Stratum st : kAllStrata) j["strata_fronts"][to_string(st)] = stratum_front(a.results, st);
  j["final_timing"] = nlohmann::json::array();
  for (const Advice::FinalTiming& t : a.final_timing)
    j["final_timing"].push_back({{"index", t.index},
                                 {"param_line", a.results[t.index].config.param_line()},
                                 {"times_ms", t.times_ms},
                                 {"median_ms", t.median_ms}});
  j["pick"] = a.pick ? nlohmann::json(*a.pick) : nlohmann::json();
  if (a.pick) j["pick_ms"] = a.chosen_ms(*a.pick);
  if (a.tried) {
    j["verified"] = measurement_json(a.verified);
    j["verified_index"] = *a.tried;
    j["verify_seed"] = a.verify_seed;
    j["verified_strata_counts"] = a.verified_strata_counts;
  }
  return j;
}

std::string advice_svg(const Advice& a, const AdviseBudgets& budgets) {
  constexpr double kW = 640, kH = 400, kLeft = 70, kRight = 20, kTop = 30, kBottom = 50;
  // Log axes: frame ms and error (p95 floored at 1e-5 so exact points show).
  constexpr double kFloor = 1e-5;
  double x0 = 1e300, x1 = 0, y0 = budgets.error, y1 = budgets.error;
  for (const AdviseResult& r : a.results)
    if (r.measurement.ok) {
      x0 = std::min(x0, r.measurement.frame_ms);
      x1 = std::max(x1, r.measurement.frame_ms);
      for (const StratumError& e : r.measurement.strata) {
        if (e.count == 0) continue;
        y0 = std::min(y0, std::max(e.judged(), kFloor));
        y1 = std::max(y1, std::max(e.judged(), kFloor));
      }
    }
  if (x1 <= 0) x0 = 0.1, x1 = 1;
  x0 = std::max(x0, 1e-4) / 1.2, x1 = x1 * 1.2, y0 /= 1.5, y1 *= 1.5;
  const auto px = [&](double x) {
    return kLeft + (std::log(std::max(x, 1e-4)) - std::log(x0)) / (std::log(x1) - std::log(x0)) *
                       (kW - kLeft - kRight);
  };
  const auto py = [&](double y) {
    return kH - kBottom -
           (std::log(std::max(y, kFloor)) - std::log(y0)) / (std::log(y1) - std::log(y0)) *
               (kH - kTop - kBottom);
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kW << "\" height=\"" << kH
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << kLeft << "\" y=\"18\" font-size=\"13\">deepvox advise: p95 |T' - T| "
    << "(worst stratum, blue; each stratum's front dashed) against frame time, log-log</text>\n"
    << "<line x1=\"" << kLeft << "\" y1=\"" << kH - kBottom << "\" x2=\"" << kW - kRight
    << "\" y2=\"" << kH - kBottom << "\" stroke=\"black\"/>\n"
    << "<line x1=\"" << kLeft << "\" y1=\"" << kTop << "\" x2=\"" << kLeft << "\" y2=\""
    << kH - kBottom << "\" stroke=\"black\"/>\n"
    << "<text x=\"" << (kW / 2) << "\" y=\"" << kH - 12 << "\">frame ms ("
    << significant_text(x0, 3) << " .. " << significant_text(x1, 3) << ")</text>\n"
    << "<text x=\"8\" y=\"" << kTop + 10 << "\">" << significant_text(y1, 2) << "</text>\n"
    << "<text x=\"8\" y=\"" << kH - kBottom << "\">" << significant_text(y0, 2) << "</text>\n"
    << "<line x1=\"" << kLeft << "\" x2=\"" << kW - kRight << "\" y1=\"" << py(budgets.error)
    << "\" y2=\"" << py(budgets.error) << "\" stroke=\"#c00\" stroke-dasharray=\"5,4\"/>\n"
    << "<text x=\"" << kW - kRight - 90 << "\" y=\"" << py(budgets.error) - 4
    << "\" fill=\"#c00\">bound " << budgets.error << "</text>\n";
  for (const AdviseResult& r : a.results)
    if (r.measurement.ok)
      s << "<circle cx=\"" << px(r.measurement.frame_ms) << "\" cy=\""
        << py(r.measurement.error_p95) << "\" r=\"3\" fill=\"#999\"><title>"
        << r.config.param_line() << "</title></circle>\n";
  // The front per stratum (its error against frame time), thin and coloured, labelled.
  const char* colours[kStrata] = {"#6a6", "#222", "#d80", "#a3c"};
  for (Stratum st : kAllStrata) {
    const std::vector<size_t> front = stratum_front(a.results, st);
    if (front.empty()) continue;
    const char* colour = colours[size_t(st)];
    s << "<polyline fill=\"none\" stroke=\"" << colour
      << "\" stroke-width=\"1\" stroke-dasharray=\"2,2\" points=\"";
    for (size_t i : front)
      s << px(a.results[i].measurement.frame_ms) << ","
        << py(a.results[i].measurement.strata[size_t(st)].judged()) << " ";
    s << "\"/>\n<text x=\"" << kW - kRight - 90 << "\" y=\"" << kTop + 14 * (1 + int(st))
      << "\" fill=\"" << colour << "\">" << to_string(st) << " front</text>\n";
  }
  s << "<polyline fill=\"none\" stroke=\"#06c\" stroke-width=\"1.5\" points=\"";
  for (size_t i : a.front)
    s << px(a.results[i].measurement.frame_ms) << "," << py(a.results[i].measurement.error_p95)
      << " ";
  s << "\"/>\n";
  for (size_t i : a.front)
    s << "<circle cx=\"" << px(a.results[i].measurement.frame_ms) << "\" cy=\""
      << py(a.results[i].measurement.error_p95) << "\" r=\"4\" fill=\"#06c\"/>\n";
  if (a.pick) {
    const AdviseMeasurement& m = a.results[*a.pick].measurement;
    s << "<circle cx=\"" << px(m.frame_ms) << "\" cy=\"" << py(m.error_p95)
      << "\" r=\"8\" fill=\"none\" stroke=\"#c00\" stroke-width=\"2\"/>\n"
      << "<text x=\"" << px(m.frame_ms) + 10 << "\" y=\"" << py(m.error_p95) + 14
      << "\" fill=\"#c00\">pick: " << a.results[*a.pick].config.param_line() << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace dv
