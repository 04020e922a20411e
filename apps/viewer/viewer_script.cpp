// Script parsing (see viewer_script.h).
#include "apps/viewer/viewer_script.h"

#include <fstream>
#include <sstream>

#include "apps/viewer/viewer_keys.h"
#include "core/error.h"

namespace dv::viewer {

namespace {

double number(const std::string& word, const std::string& what, const std::string& where) {
  try {
    size_t used = 0;
    const double value = std::stod(word, &used);
    if (used == word.size()) return value;
  } catch (const std::exception&) {
  }
  throw InputError(where, what + " '" + word + "' is not a number");
}

MouseButton button(const std::string& word, const std::string& where) {
  if (word == "left") return MouseButton::left;
  if (word == "right") return MouseButton::right;
  if (word == "middle") return MouseButton::middle;
  throw InputError(where, "unknown mouse button '" + word + "' (left, right or middle)");
}

}  // namespace

std::vector<ViewerEvent> parse_script_text(const std::string& text, const std::string& source) {
  std::vector<ViewerEvent> events;
  std::istringstream lines(text);
  std::string line;
  for (int number_of_line = 1; std::getline(lines, line); ++number_of_line) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (words.empty()) continue;
    const std::string where = source + ":" + std::to_string(number_of_line);
    if (words.size() < 2) throw InputError(where, "expected `FRAME EVENT ...`");
    ViewerEvent e;
    const double frame = number(words[0], "frame", where);
    if (frame < 0 || frame != double(int(frame)))
      throw InputError(where, "frame '" + words[0] + "' is not a frame number");
    e.frame = int(frame);
    if (!events.empty() && e.frame < events.back().frame)
      throw InputError(where, "frame " + words[0] + " comes before the previous line's");
    const std::string& kind = words[1];
    const size_t args = words.size() - 2;
    if (kind == "key" && args == 1) {
      e.kind = EventKind::key;
      e.key = key_from_name(words[2]);
      if (e.key.empty()) throw InputError(where, "unknown key '" + words[2] + "'");
    } else if (kind == "drag" && (args == 2 || args == 3)) {
      e.kind = EventKind::drag;
      e.dx = number(words[2], "drag dx", where);
      e.dy = number(words[3], "drag dy", where);
      if (args == 3) e.button = button(words[4], where);
    } else if (kind == "scroll" && args == 1) {
      e.kind = EventKind::scroll;
      e.dy = number(words[2], "scroll dy", where);
    } else if (kind == "screenshot" && args == 1) {
      e.kind = EventKind::screenshot;
      e.path = words[2];
    } else {
      throw InputError(where,
                       "expected `key NAME`, `drag DX DY [BUTTON]`, `scroll DY` or "
                       "`screenshot PATH` after the frame, got '" +
                           line + "'");
    }
    events.push_back(e);
  }
  return events;
}

std::vector<ViewerEvent> parse_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot read the script");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_script_text(text.str(), path);
}

}  // namespace dv::viewer
