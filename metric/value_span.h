#pragma once
// A read-only view of `size` contiguous values (C++17 has no std::span). The statistics take
// their values through it, so they read a measure's per-sample values whichever vector holds them:
// a std::vector<double>, or compute_deviations's DeviationArray, whose storage is left raw
// (metric/attribute_deviation.h). A span does not own its values: they must outlive it.
#include <cstddef>
#include <type_traits>
#include <utility>

namespace meshdev {

template <class T>
class ConstSpan {
 public:
  ConstSpan() = default;
  ConstSpan(const T* data, std::size_t size) : data_(data), size_(size) {}
  // Any contiguous container of T (std::vector with any allocator); implicit, as std::span's.
  template <class Container, class = std::enable_if_t<std::is_convertible_v<
                                 decltype(std::declval<const Container&>().data()), const T*>>>
  ConstSpan(const Container& c)  // NOLINT(google-explicit-constructor)
      : data_(c.data()), size_(c.size()) {}

  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

 private:
  const T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace meshdev
