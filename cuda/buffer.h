// Owning arrays in host or device memory, and the non-owning views that kernels receive.
// Owning containers never enter kernels: pass `view()` (a pointer and a size) instead.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/hd.h"
#include "cuda/device_memory.h"
#include "cuda/execute.h"

namespace dv {

enum class Memory : uint8_t { host, device };

// Where a backend's data lives: host memory for the CPU threads, device memory for CUDA.
inline Memory memory_of(Backend backend) {
  return backend == Backend::cuda ? Memory::device : Memory::host;
}

// A plain pointer + size that is valid on the side its buffer lives on.
template <class T>
struct View {
  T* data = nullptr;
  int64_t size = 0;
  DV_HD T& operator[](int64_t i) const { return data[i]; }
  DV_HD bool empty() const { return size == 0; }
};

template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>, "Buffer holds plain data that can be memcpy'd");

 public:
  Buffer() = default;
  Buffer(Memory memory, int64_t count, const char* what = "buffer") {
    allocate(memory, count, what);
  }
  Buffer(Memory memory, std::span<const T> values, const char* what = "buffer") {
    allocate(memory, int64_t(values.size()), what);
    upload(values);
  }
  ~Buffer() { release(); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& other) noexcept { swap(other); }
  Buffer& operator=(Buffer&& other) noexcept {
    if (this != &other) {
      release();
      swap(other);
    }
    return *this;
  }

  Memory memory() const { return memory_; }
  int64_t size() const { return size_; }
  size_t bytes() const { return size_t(size_) * sizeof(T); }
  T* data() const { return data_; }
  View<T> view() const { return {data_, size_}; }
  View<const T> const_view() const { return {data_, size_}; }

  void upload(std::span<const T> values) {
    if (int64_t(values.size()) != size_) throw Error("Buffer::upload: size mismatch");
    if (memory_ == Memory::device)
      copy_to_device(data_, values.data(), bytes());
    else if (bytes())
      std::memcpy(data_, values.data(), bytes());
  }
  std::vector<T> to_vector() const {
    std::vector<T> out(static_cast<size_t>(size_));
    if (memory_ == Memory::device)
      copy_to_host(out.data(), data_, bytes());
    else if (bytes())
      std::memcpy(out.data(), data_, bytes());
    return out;
  }
  void fill_zero() {
    if (memory_ == Memory::device)
      device_memset(data_, 0, bytes());
    else if (bytes())
      std::memset(static_cast<void*>(data_), 0, bytes());
  }

 private:
  void allocate(Memory memory, int64_t count, const char* what) {
    memory_ = memory;
    size_ = count;
    if (count <= 0) return;
    if (memory == Memory::device)
      data_ = static_cast<T*>(device_allocate(bytes(), what));
    else
      data_ = static_cast<T*>(
          ::operator new(bytes(), std::align_val_t(alignof(T) < 64 ? 64 : alignof(T))));
  }
  void release() noexcept {
    if (!data_) return;
    if (memory_ == Memory::device)
      device_free(data_);
    else
      ::operator delete(data_, std::align_val_t(alignof(T) < 64 ? 64 : alignof(T)));
    data_ = nullptr;
    size_ = 0;
  }
  void swap(Buffer& o) noexcept {
    std::swap(memory_, o.memory_);
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
  }

  Memory memory_ = Memory::host;
  T* data_ = nullptr;
  int64_t size_ = 0;
};

// A host copy of what `view` points to in `memory` (views into a SceneData, for host planning).
template <class T>
std::vector<std::remove_const_t<T>> to_host_vector(View<T> view, Memory memory) {
  std::vector<std::remove_const_t<T>> out(static_cast<size_t>(view.size));
  if (view.size == 0) return out;
  if (memory == Memory::device)
    copy_to_host(out.data(), view.data, out.size() * sizeof(T));
  else
    std::memcpy(static_cast<void*>(out.data()), view.data, out.size() * sizeof(T));
  return out;
}

}  // namespace dv
