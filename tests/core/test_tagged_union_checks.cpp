// The debug checks of core/tagged_union.h: a tag outside the type list stops dispatch, and
// get<T>() of a type the union does not hold stops, instead of running the first type's code.
// The checks are asserts, so this file compiles the header as a debug build does (NDEBUG
// undefined) in every build type; release builds of the renderer compile them away. The
// union's types are local to this file, so its instantiations are this file's alone.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <type_traits>

#undef NDEBUG
#include <cassert>

#include "core/tagged_union.h"

namespace dv {
namespace {

// Two types of this file only: a count and an interval.
struct Count {
  int n = 0;
};
struct Interval {
  double from = 0, to = 0;
};
using Two = TaggedUnion<Count, Interval>;

// A union whose first byte, the tag, is `tag`: what memory written by something else holds.
Two with_raw_tag(uint8_t tag) {
  static_assert(std::is_standard_layout_v<Two>, "the tag, the first member, is at offset 0");
  unsigned char bytes[sizeof(Two)] = {};
  bytes[0] = tag;
  Two t;
  std::memcpy(static_cast<void*>(&t), bytes, sizeof t);
  return t;
}

int type_number(const Two& t) {
  return t.dispatch(
      [](const auto& m) { return std::is_same_v<std::decay_t<decltype(m)>, Count> ? 0 : 1; });
}

TEST(TaggedUnionChecks, RawTagsInsideTheListDispatch) {
  EXPECT_EQ(type_number(with_raw_tag(0)), 0);
  EXPECT_EQ(type_number(with_raw_tag(1)), 1);
}

TEST(TaggedUnionChecksDeathTest, TagOutsideTheListStopsDispatch) {
  EXPECT_DEATH(type_number(with_raw_tag(2)), "tag outside the type list");
  EXPECT_DEATH(type_number(with_raw_tag(255)), "tag outside the type list");
}

TEST(TaggedUnionChecksDeathTest, GetOfAnotherTypeStops) {
  const Two count(Count{3});
  EXPECT_EQ(count.get<Count>().n, 3);
  EXPECT_DEATH((void)count.get<Interval>(), "does not hold");
  EXPECT_DEATH((void)with_raw_tag(7).get<Count>(), "does not hold");
}

}  // namespace
}  // namespace dv
