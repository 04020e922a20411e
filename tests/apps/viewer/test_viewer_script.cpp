// The viewer's script format (docs/viewer.md): every event kind parses, and every mistake is an
// InputError naming the file and line.
#include <gtest/gtest.h>

#include "apps/viewer/viewer_keys.h"
#include "apps/viewer/viewer_script.h"
#include "core/error.h"

namespace dv::viewer {
namespace {

TEST(ViewerScript, ParsesEveryEventKind) {
  const auto events = parse_script_text(
      "# orbit, then switch\n"
      "0 drag 40 -12\n"
      "0 drag 3 4 middle   # pan\n"
      "2 scroll -1.5\n"
      "2 key m\n"
      "2 key LEFT_BRACKET\n"
      "\n"
      "5 screenshot out/a.png\n",
      "keys.txt");
  ASSERT_EQ(events.size(), 6u);
  EXPECT_EQ(events[0].kind, EventKind::drag);
  EXPECT_EQ(events[0].dx, 40.0);
  EXPECT_EQ(events[0].dy, -12.0);
  EXPECT_EQ(events[0].button, MouseButton::left);
  EXPECT_EQ(events[1].button, MouseButton::middle);
  EXPECT_EQ(events[2].kind, EventKind::scroll);
  EXPECT_EQ(events[2].frame, 2);
  EXPECT_EQ(events[2].dy, -1.5);
  EXPECT_EQ(events[3].key, "M");
  EXPECT_EQ(events[4].key, "[");
  EXPECT_EQ(events[5].kind, EventKind::screenshot);
  EXPECT_EQ(events[5].frame, 5);
  EXPECT_EQ(events[5].path, "out/a.png");
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    parse_script_text(text, "keys.txt");
    ADD_FAILURE() << "no error for: " << text;
    return;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ViewerScript, MistakesNameFileAndLine) {
  expect_error("0 key M\n1 key NOPE\n", "keys.txt:2: unknown key 'NOPE'");
  expect_error("x key M\n", "keys.txt:1: frame 'x' is not a number");
  expect_error("-1 key M\n", "keys.txt:1: frame '-1' is not a frame number");
  expect_error("3 key M\n2 key M\n", "keys.txt:2: frame 2 comes before");
  expect_error("0 drag 1\n", "keys.txt:1: expected `key NAME`");
  expect_error("0 drag 1 2 thumb\n", "keys.txt:1: unknown mouse button 'thumb'");
  expect_error("0 scroll up\n", "keys.txt:1: scroll dy 'up' is not a number");
  expect_error("0 jump\n", "keys.txt:1: expected `key NAME`");
  expect_error("# header\n7\n", "keys.txt:2: expected `FRAME EVENT");
}

TEST(ViewerScript, MissingFileIsAnInputError) {
  EXPECT_THROW(parse_script("/nonexistent/keys.txt"), InputError);
}

TEST(ViewerKeys, AliasesAndHelpCoverEveryKey) {
  EXPECT_EQ(key_from_name("escape"), "Q");
  EXPECT_EQ(key_from_name("EQUAL"), "=");
  EXPECT_EQ(key_from_name("?"), "F1");
  EXPECT_EQ(key_from_name("X"), "");
  const std::string help = keys_help();
  for (const KeyInfo& k : viewer_keys())
    EXPECT_NE(help.find(std::string(k.name) + " "), std::string::npos) << k.name;
}

}  // namespace
}  // namespace dv::viewer
