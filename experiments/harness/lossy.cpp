// Lossy rows (lossy.h).
#include "experiments/harness/lossy.h"

#include <set>

#include "core/number_text.h"

namespace dv {

bool is_loss_metric(const std::string& metric) {
  return metric.find("overflow") != std::string::npos ||
         metric.find("dropped") != std::string::npos;
}

std::string loss_text(const std::vector<const Row*>& rows) {
  std::string named;
  std::set<std::string> seen;
  for (const Row* r : rows)
    if (is_loss_metric(r->metric) && r->value > 0.0 && seen.insert(r->metric).second)
      named += (named.empty() ? "" : ", ") + r->metric + " = " + table_text(r->value, 3);
  return named;
}

std::map<int, std::string> lossy_items(const std::vector<RunView>& runs) {
  std::map<int, std::string> out;
  for (const RunView& run : runs)
    for (const auto& [index, rows] : run.items)
      if (!out.count(index))
        if (std::string text = loss_text(rows); !text.empty()) out[index] = std::move(text);
  return out;
}

bool body_has_mark(const std::vector<std::vector<std::string>>& body) {
  const std::string mark = kLossyMark;
  for (const auto& line : body)
    for (const std::string& text : line)
      if (text.size() >= mark.size() &&
          text.compare(text.size() - mark.size(), mark.size(), mark) == 0)
        return true;
  return false;
}

void write_lossy_list(std::ostream& md, const std::map<int, std::vector<const Row*>>& items,
                      const std::map<int, std::string>& lossy) {
  bool any = false;
  for (const auto& [index, rows] : items) {
    const auto it = lossy.find(index);
    if (it == lossy.end() || rows.empty()) continue;
    if (!any) md << "\n" << kLossyMeaning << ":\n\n";
    any = true;
    md << "- item " << index << " (" << item_label(*rows.front()) << "): " << it->second << "\n";
  }
}

}  // namespace dv
