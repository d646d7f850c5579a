#pragma once
// Raw storage: arrays whose elements are left unwritten until the threads that own them write
// them, so that their memory is first touched there, in parallel.
//
// RawStorageAllocator: an allocator like std::allocator, except that construction without
// arguments does nothing, so `resize` leaves the new elements as raw storage instead of
// initialising them on the calling thread. For arrays whose every element is written afterwards
// by the threads that own it (face samples, placed with placement new; the deviations'
// per-sample arrays). push_back, insert and copies construct as usual. Nothing may read an
// element that `resize` added before it is written.
//
// RawArray (below): the same contract for a plain owned array of a trivial type.
//
// Checked in the sanitizer builds (scripts/sanitize.sh): there every block is filled with
// all-ones bytes when allocated (NaN doubles and floats, 0xffffffff integers), so an element
// read before it is written shows up in the tests' comparisons with their oracles and their
// checks of finite results.
#include <cassert>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
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

// An owned array of `size()` elements of a trivial type in raw storage from std::malloc: the
// elements are left unwritten, as RawStorageAllocator leaves them (poisoned the same way in the
// sanitizer builds), and whoever fills them writes every byte. Its storage can pass to an array
// of another type: the BVH build writes its leaf blocks over the memory of its binary tree once
// the tree is spent, so a build needs no fresh pages for them where the tree's pages are already
// the process's (TriangleBvh::build). Move-only.
template <class T>
class RawArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "raw storage holds trivial types only");
  static_assert(alignof(T) <= alignof(std::max_align_t), "std::malloc's alignment");

 public:
  RawArray() = default;
  // `count` unwritten elements. Throws std::bad_alloc. O(1) (O(count) in the sanitizer builds).
  explicit RawArray(std::size_t count) : size_(count) {
    if (count > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_alloc();
    data_ = static_cast<T*>(std::malloc(count == 0 ? 1 : count * sizeof(T)));
    if (data_ == nullptr) throw std::bad_alloc();
    poison();
  }
  // `count` unwritten elements in `from`'s storage, which is cut to their bytes (std::realloc:
  // glibc shrinks in place, keeping the pages already touched and releasing the rest of an
  // mmapped block; where a shrink fails, the block stays as it was); `from` is left empty.
  // Precondition: count * sizeof(T) <= from.size() * sizeof(U). O(1) (O(count) in the sanitizer
  // builds).
  template <class U>
  RawArray(RawArray<U>&& from, std::size_t count) : size_(count) {
    assert(count * sizeof(T) <= from.size_ * sizeof(U));
    void* const shrunk = std::realloc(from.data_, count == 0 ? 1 : count * sizeof(T));
    data_ = static_cast<T*>(shrunk != nullptr ? shrunk : static_cast<void*>(from.data_));
    from.data_ = nullptr;
    from.size_ = 0;
    poison();
  }
  RawArray(RawArray&& other) noexcept { swap(other); }
  RawArray& operator=(RawArray&& other) noexcept {
    RawArray(std::move(other)).swap(*this);
    return *this;
  }
  RawArray(const RawArray&) = delete;
  RawArray& operator=(const RawArray&) = delete;
  ~RawArray() { std::free(data_); }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  T& operator[](std::size_t i) {
    assert(i < size_);
    return data_[i];
  }
  const T& operator[](std::size_t i) const {
    assert(i < size_);
    return data_[i];
  }

 private:
  template <class U>
  friend class RawArray;
  void swap(RawArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
  }
  void poison() {
#ifdef MESHDEV_POISON_RAW_STORAGE
    if (data_ != nullptr) std::memset(static_cast<void*>(data_), 0xff, size_ * sizeof(T));
#endif
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace meshdev
