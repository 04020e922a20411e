// TaggedUnion<Ts...>: one value of one of a list of types, held by value with a one-byte tag, and
// dispatch(f) that calls f on the active member through one switch. A family whose members a
// kernel must call without virtual functions (the DSM storages' readers) declares them as one
// type list, and the tag, the union and the dispatch are generated from it (pbrt-v4's
// TaggedPointer does the same for pointers). The union keeps the value as small as its largest
// member, so a kernel's copy of it stays small. Host and device code.
//
// The tag is checked where it is read, with assert: a tag outside the list (memory written by
// something else, a copy made from raw bytes) or get<T>() of a type the union does not hold
// stops a debug build (host or device) there, instead of running another type's code; release
// builds (NDEBUG) compile the checks away, so kernels pay nothing.
#pragma once

#include <cassert>
#include <cstdint>
#include <type_traits>

#include "core/hd.h"

namespace dv {

namespace tagged_union_detail {

// The members of Ts... overlaid: element I is the I-th type.
template <class... Ts>
union Members;
template <class T>
union Members<T> {
  T first;
  DV_HD Members() : first{} {}
};
template <class T, class... Rest>
union Members<T, Rest...> {
  T first;
  Members<Rest...> rest;
  DV_HD Members() : first{} {}
};

template <int I, class... Ts>
DV_HD const auto& member(const Members<Ts...>& m) {
  if constexpr (I == 0) {
    return m.first;
  } else {
    return member<I - 1>(m.rest);
  }
}
template <int I, class... Ts>
DV_HD auto& member(Members<Ts...>& m) {
  if constexpr (I == 0) {
    return m.first;
  } else {
    return member<I - 1>(m.rest);
  }
}

template <class T, class... Ts>
constexpr int index_of() {
  int i = 0;
  const bool found = ((std::is_same_v<T, Ts> ? true : (++i, false)) || ...);
  return found ? i : -1;
}

}  // namespace tagged_union_detail

template <class... Ts>
class TaggedUnion {
 public:
  static constexpr int kTypes = sizeof...(Ts);
  static_assert(kTypes >= 1 && kTypes <= 16, "dispatch() below is written for 1 to 16 types");

  // The index of T in the list (a compile error for a type that is not in it).
  template <class T>
  static constexpr int index_of() {
    constexpr int i = tagged_union_detail::index_of<T, Ts...>();
    static_assert(i >= 0, "the type is not in this TaggedUnion's list");
    return i;
  }

  TaggedUnion() = default;  // the first type, value-initialised
  // From a value of one of the types (only those: a SFINAE-friendly condition, so the copy of a
  // TaggedUnion or of a class derived from it never instantiates the index of a foreign type).
  template <class T, std::enable_if_t<(tagged_union_detail::index_of<T, Ts...>() >= 0), int> = 0>
  DV_HD TaggedUnion(const T& value) : tag_(uint8_t(index_of<T>())) {  // NOLINT: implicit
    tagged_union_detail::member<index_of<T>()>(members_) = value;
  }

  DV_HD int tag() const { return tag_; }
  template <class T>
  DV_HD bool holds() const {
    return tag_ == index_of<T>();
  }
  // The member of type T, which must be the active one.
  template <class T>
  DV_HD const T& get() const {
    assert(holds<T>() && "TaggedUnion::get<T>() of a type the union does not hold");
    return tagged_union_detail::member<index_of<T>()>(members_);
  }

  // f(member) for the active member, through one switch on the tag (a uniform branch when all
  // threads of a warp hold the same type). A tag past the list fails the assert; without it
  // (NDEBUG) such a tag falls through to the first type.
  template <class F>
  DV_HD auto dispatch(F f) const {
    assert(tag_ < kTypes && "TaggedUnion::dispatch on a tag outside the type list");
#define DV_TAGGED_UNION_CASE(i)                                                   \
  case i:                                                                         \
    if constexpr (i < kTypes) return f(tagged_union_detail::member<i>(members_)); \
    [[fallthrough]];
    switch (tag_) {
      DV_TAGGED_UNION_CASE(1)
      DV_TAGGED_UNION_CASE(2)
      DV_TAGGED_UNION_CASE(3)
      DV_TAGGED_UNION_CASE(4)
      DV_TAGGED_UNION_CASE(5)
      DV_TAGGED_UNION_CASE(6)
      DV_TAGGED_UNION_CASE(7)
      DV_TAGGED_UNION_CASE(8)
      DV_TAGGED_UNION_CASE(9)
      DV_TAGGED_UNION_CASE(10)
      DV_TAGGED_UNION_CASE(11)
      DV_TAGGED_UNION_CASE(12)
      DV_TAGGED_UNION_CASE(13)
      DV_TAGGED_UNION_CASE(14)
      DV_TAGGED_UNION_CASE(15)
      default:
        return f(tagged_union_detail::member<0>(members_));
    }
#undef DV_TAGGED_UNION_CASE
  }

 private:
  uint8_t tag_ = 0;
  tagged_union_detail::Members<Ts...> members_;
};

}  // namespace dv
