// The viewer's input events and the script files that replay them (`deepvox view --script`):
// one event a line, `FRAME key NAME`, `FRAME drag DX DY [left|right|middle]`, `FRAME scroll DY`
// or `FRAME screenshot PATH`, applied at the start of frame FRAME (screenshots after it is
// drawn); `#` starts a comment. Interactive input becomes the same events, so a script drives
// exactly the code a person does. Format: docs/viewer.md.
#pragma once

#include <string>
#include <vector>

namespace dv::viewer {

enum class EventKind { key, drag, scroll, screenshot };
enum class MouseButton { left, right, middle };

struct ViewerEvent {
  int frame = 0;
  EventKind kind = EventKind::key;
  std::string key;            // key: a name of viewer_keys.h (upper case)
  double dx = 0.0, dy = 0.0;  // drag: pixels; scroll: dy in wheel steps
  MouseButton button = MouseButton::left;
  std::string path;  // screenshot
};

// Events in frame order (stable for events of one frame). Throws InputError naming the file
// and line for an unknown event, a bad number, a frame before the previous line's, or a key
// that is not one of the viewer's.
std::vector<ViewerEvent> parse_script(const std::string& path);
std::vector<ViewerEvent> parse_script_text(const std::string& text, const std::string& source);

}  // namespace dv::viewer
