#pragma once
// An allocator like std::allocator, except that construction without arguments does nothing, so
// `resize` leaves the new elements as raw storage instead of initialising them on the calling
// thread. For arrays whose every element is written afterwards by the threads that own it (face
// samples, placed with placement new; BVH leaf blocks, trivial types written field by field):
// the memory is then first touched there, in parallel. push_back, insert and copies construct as
// usual. Nothing may read an element that `resize` added before it is written.
#include <memory>
#include <new>
#include <utility>

namespace meshdev {

template <class T>
struct RawStorageAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = RawStorageAllocator<U>;
  };
  RawStorageAllocator() = default;
  template <class U>
  RawStorageAllocator(const RawStorageAllocator<U>&) noexcept {}
  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace meshdev
