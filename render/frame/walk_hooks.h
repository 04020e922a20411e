// What a camera walk asks of its shadow source beyond the answers (render/frame/shading.h), with
// defaults for the sources that need none: the exact oracle's deferred walks
// (render/frame/oracle_passes.h) start each thread's cursor at its own queries, close it after
// the walk, and gather queries without writing pixels. Host and device code.
//   Source::cursor_for(thread)        the thread's first cursor (default: a value-initialized one)
//   Source::finish(cursor, thread)    called after the walk (in device code by every lane of a
//                                     pixel's group)
//   Source::kWritesPixels = false     a walk that writes no pixel and counts nothing
#pragma once

#include <cstdint>

#include "core/hd.h"

namespace dv {

template <class Source>
DV_HD typename Source::Cursor first_cursor(const Source& source, int64_t thread) {
  if constexpr (requires { source.cursor_for(thread); })
    return source.cursor_for(thread);
  else
    return typename Source::Cursor{};
}

template <class Source>
DV_HD void finish_walk(const Source& source, const typename Source::Cursor& cursor,
                       int64_t thread) {
  if constexpr (requires { source.finish(cursor, thread); }) source.finish(cursor, thread);
}

template <class Source>
constexpr bool writes_pixels() {
  if constexpr (requires { Source::kWritesPixels; })
    return Source::kWritesPixels;
  else
    return true;
}

}  // namespace dv
