// Per-call scratch arrays of the Mie core (template implementation detail).
//
// At x = 1e6 the core needs ~33 MB for one call.  Allocated with plain
// std::vector that memory is zero-filled (wasted: every entry is written
// before it is read) and faulted in 4 KiB at a time, which on a virtual
// machine costs as much as the series itself (~8000 faults, ~80 ms measured).
// For trivial element types we allocate 2 MiB-aligned blocks and ask for
// transparent huge pages, and never initialise.  The buffers are per thread
// and reused; the series gives back those above 8 MB after each call
// (DownwardTables::release_large, log_derivative.hpp).
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace attenuvis::mie::detail {

// Complex value as stored between the downward pass and the series: a
// trivial pair, so arrays of it need no construction.
template <class T>
struct StoredComplex {
  T re, im;
  const T& real() const { return re; }
  const T& imag() const { return im; }
};

// w = v for a stored slot (rounding to the stored precision is intended).
template <class T, class V>
inline void store(StoredComplex<T>& w, const V& v) {
  w.re = static_cast<T>(v.real());
  w.im = static_cast<T>(v.imag());
}
template <class W, class V>
inline void store(W& w, const V& v) {
  w = W(v.real(), v.imag());
}

template <class T>
class HugeBuffer {
  static_assert(std::is_trivial_v<T>, "HugeBuffer holds trivial types only");

 public:
  HugeBuffer() = default;
  HugeBuffer(const HugeBuffer&) = delete;
  HugeBuffer& operator=(const HugeBuffer&) = delete;
  ~HugeBuffer() { std::free(data_); }

  // Makes room for n elements; contents are unspecified (not initialised).
  void resize(std::size_t n) {
    if (n > capacity_) {
      std::free(data_);
      data_ = nullptr;
      capacity_ = 0;
      // Small arrays: ordinary pages (a huge page would have to be zeroed by
      // the kernel on every first touch); large ones: whole huge pages.
      constexpr std::size_t kHuge = std::size_t(2) << 20;
      const bool huge = n * sizeof(T) >= 4 * kHuge;
      const std::size_t align = huge ? kHuge : 64;
      const std::size_t bytes = (n * sizeof(T) + align - 1) / align * align;
      void* p = std::aligned_alloc(align, bytes);
      if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
      if (huge) ::madvise(p, bytes, MADV_HUGEPAGE);  // a hint; ignored where unsupported
#endif
      data_ = static_cast<T*>(p);
      capacity_ = bytes / sizeof(T);
    }
    size_ = n;
  }
  void release() {
    std::free(data_);
    data_ = nullptr;
    size_ = capacity_ = 0;
  }
  std::size_t capacity_bytes() const { return capacity_ * sizeof(T); }
  std::size_t size() const { return size_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

// std::vector for non-trivial types (the 50-digit referee), with release().
template <class T>
class VectorBuffer : public std::vector<T> {
 public:
  void release() { std::vector<T>().swap(*this); }
  std::size_t capacity_bytes() const { return this->capacity() * sizeof(T); }
};

template <class T>
using Scratch = std::conditional_t<std::is_trivial_v<T>, HugeBuffer<T>, VectorBuffer<T>>;

}  // namespace attenuvis::mie::detail
