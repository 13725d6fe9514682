// A first-in first-out buffer of samples (a time and a fixed number of values each) in one flat
// array that grows by doubling and is otherwise reused: the envelope recorder keeps the samples of
// the last fast period in it, one push and about one pop per sample, without allocating.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace metrosync {

class SampleRing {
 public:
  explicit SampleRing(int width) : stride_(static_cast<size_t>(width) + 1) {}

  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  // the k-th oldest sample
  double time(size_t k) const { return buf_[slot(k)]; }
  const double* values(size_t k) const { return &buf_[slot(k) + 1]; }

  // appends a sample: `parts` arrays of `lengths` values each, laid end to end
  template <size_t P>
  void push(double t, const double* const (&parts)[P], const int (&lengths)[P]) {
    if (count_ == capacity_) grow();
    double* out = &buf_[slot(count_)];
    *out++ = t;
    for (size_t p = 0; p < P; ++p) out = std::copy(parts[p], parts[p] + lengths[p], out);
    ++count_;
  }
  void popFront() {
    head_ = (head_ + 1) % capacity_;
    --count_;
  }

 private:
  size_t slot(size_t k) const { return ((head_ + k) % capacity_) * stride_; }
  void grow() {
    const size_t cap = std::max<size_t>(16, 2 * capacity_);
    std::vector<double> bigger(cap * stride_);
    for (size_t k = 0; k < count_; ++k)
      std::copy(&buf_[slot(k)], &buf_[slot(k)] + stride_, &bigger[k * stride_]);
    buf_.swap(bigger);
    capacity_ = cap;
    head_ = 0;
  }

  size_t stride_;
  std::vector<double> buf_;
  size_t capacity_ = 0, head_ = 0, count_ = 0;
};

}  // namespace metrosync
