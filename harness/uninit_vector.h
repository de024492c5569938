#pragma once
// A vector whose resize leaves new elements uninitialised, for the terrain-sized buffers (4.3 G
// heights, 8.6 G normal-map halves at 65537^2) that parallel row bands fill right after: a
// value-initialising resize is one thread zeroing every page first (tens of seconds at that size),
// and the bands' first writes then fault the pages in on every thread instead.
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace lb {

template <class T>
struct UninitAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() noexcept = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  // Default construction leaves the element as it is (new U without parentheses: no zeroing);
  // anything else constructs as usual.
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(p)) U;
    else
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T, class U>
bool operator==(const UninitAllocator<T>&, const UninitAllocator<U>&) noexcept {
  return true;
}
template <class T, class U>
bool operator!=(const UninitAllocator<T>&, const UninitAllocator<U>&) noexcept {
  return false;
}

template <class T>
using UninitVector = std::vector<T, UninitAllocator<T>>;

}  // namespace lb
