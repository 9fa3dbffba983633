// An allocator under which a vector's new elements of a trivially copyable type, sized without a
// value (resize(n)), are left as the memory holds them: not zeroed and not touched. A large array
// can then be sized serially and written by every thread in parallel, each touching (and so
// faulting in) its own pages first. The owner must write every element before it is read. Used
// for the pair results of the active list, 64 bytes per entry: zeroed serially as they were
// sized, they took a third of a list refresh, which every thread of a step waits for
// (NeighborSearch::allocate_results; docs/performance.md sec. 31).
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace grainlab {

template <class T>
struct UninitializedAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() noexcept = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

  // Without arguments: nothing for a trivially copyable type (an implicit-lifetime type: the
  // allocation holds its objects), default initialization otherwise.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    if constexpr (!(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>))
      ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T, class U>
bool operator==(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) noexcept {
  return true;
}

}  // namespace grainlab
