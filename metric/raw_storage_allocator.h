#pragma once
// An allocator like std::allocator, except that construction without arguments does nothing, so
// `resize` leaves the new elements as raw storage instead of initialising them on the calling
// thread. For arrays whose every element is written afterwards by the threads that own it (face
// samples, placed with placement new; BVH leaf blocks, trivial types written field by field):
// the memory is then first touched there, in parallel. push_back, insert and copies construct as
// usual. Nothing may read an element that `resize` added before it is written.
//
// Checked in the sanitizer builds (scripts/sanitize.sh): there every block is filled with
// all-ones bytes when allocated (NaN doubles and floats, 0xffffffff integers), so an element
// read before it is written shows up in the tests' comparisons with their oracles and their
// checks of finite results.
#include <cstddef>
#include <cstring>
#include <memory>
#include <new>
#include <utility>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MESHDEV_POISON_RAW_STORAGE 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MESHDEV_POISON_RAW_STORAGE 1
#endif
#endif

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
  T* allocate(std::size_t n) {
    T* p = std::allocator<T>::allocate(n);
#ifdef MESHDEV_POISON_RAW_STORAGE
    std::memset(static_cast<void*>(p), 0xff, n * sizeof(T));
#endif
    return p;
  }
  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace meshdev
