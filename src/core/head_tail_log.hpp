#pragma once
// An append-only log whose memory is bounded: it keeps every record while it holds at most
// `limit`, and beyond that the first limit/2 (the head, kept for good) and the last limit - limit/2
// (the tail, a ring). The records in between are elided. Indices are absolute positions in the
// whole sequence (0 = the first record ever appended), so an index handed out once stays the
// same record's for as long as that record is kept (docs/report.md "Long runs").
// push_back allocates only while the head and the ring fill (warm-up); afterwards it overwrites
// the ring's oldest slot: nothing per record.
#include <cassert>
#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <vector>

namespace virtcom {

// The default bound of Trace::activities and Trace::cycles (sim::SimOptions::traceWindow).
inline constexpr size_t kDefaultTraceWindow = 100'000;

template <class T>
class HeadTailLog {
 public:
  HeadTailLog() = default;
  HeadTailLog(std::initializer_list<T> records) {
    for (const T& r : records) push_back(r);
  }
  HeadTailLog& operator=(std::initializer_list<T> records) {
    clear();
    for (const T& r : records) push_back(r);
    return *this;
  }

  // The bound (at least 2). Changing it keeps the records only while nothing was elided; set it
  // before the first append.
  void setLimit(size_t limit) {
    assert(elided() == 0 && size_ <= limit);
    headCap_ = limit < 2 ? 1 : limit / 2;
    tailCap_ = (limit < 2 ? 2 : limit) - headCap_;
  }
  size_t limit() const { return headCap_ + tailCap_; }
  size_t tailCapacity() const { return tailCap_; }

  // Records appended in all (kept or elided).
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Kept: [0, headEnd()) and [tailBegin(), size()); elided: [headEnd(), tailBegin()).
  size_t headEnd() const { return size_ < headCap_ ? size_ : headCap_; }
  size_t tailBegin() const { return size_ - ring_.size() < headEnd() ? headEnd() : size_ - ring_.size(); }
  size_t elided() const { return tailBegin() - headEnd(); }
  bool kept(size_t i) const { return i < headEnd() || (i >= tailBegin() && i < size_); }

  // The record at absolute index i; i must be kept.
  const T& operator[](size_t i) const {
    assert(kept(i));
    return i < headCap_ ? head_[i] : ring_[(i - headCap_) % tailCap_];
  }
  T& operator[](size_t i) {
    assert(kept(i));
    return i < headCap_ ? head_[i] : ring_[(i - headCap_) % tailCap_];
  }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }
  T& back() { return (*this)[size_ - 1]; }

  // Appends; returns the record this append elided (the ring's oldest), or null.
  const T* push_back(const T& record) {
    const size_t i = size_++;
    if (i < headCap_) {
      head_.push_back(record);
      return nullptr;
    }
    const size_t slot = (i - headCap_) % tailCap_;
    if (ring_.size() < tailCap_) {
      ring_.push_back(record);
      return nullptr;
    }
    evicted_ = ring_[slot];
    ring_[slot] = record;
    return &evicted_;
  }
  // Reserves up to n records of the head and the ring.
  void reserve(size_t n) {
    head_.reserve(n < headCap_ ? n : headCap_);
    if (n > headCap_) ring_.reserve(n - headCap_ < tailCap_ ? n - headCap_ : tailCap_);
  }
  size_t capacity() const { return head_.capacity() + ring_.capacity(); }
  void clear() {
    head_.clear();
    ring_.clear();
    size_ = 0;
  }

  // Iterates the kept records in index order (the head, then the tail); index() is absolute.
  class const_iterator {
   public:
    using iterator_category = std::bidirectional_iterator_tag;
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using pointer = const T*;
    using reference = const T&;
    const_iterator() = default;
    const_iterator(const HeadTailLog* log, size_t i) : log_(log), i_(i) {}
    reference operator*() const { return (*log_)[i_]; }
    pointer operator->() const { return &(*log_)[i_]; }
    size_t index() const { return i_; }
    const_iterator& operator++() {
      if (++i_ == log_->headEnd()) i_ = log_->tailBegin();
      return *this;
    }
    const_iterator operator++(int) {
      const_iterator before = *this;
      ++*this;
      return before;
    }
    const_iterator& operator--() {
      if (i_ == log_->tailBegin()) i_ = log_->headEnd();
      --i_;
      return *this;
    }
    const_iterator operator--(int) {
      const_iterator before = *this;
      --*this;
      return before;
    }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }

   private:
    const HeadTailLog* log_ = nullptr;
    size_t i_ = 0;
  };
  using iterator = const_iterator;
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size_}; }
  std::reverse_iterator<const_iterator> rbegin() const { return std::reverse_iterator(end()); }
  std::reverse_iterator<const_iterator> rend() const { return std::reverse_iterator(begin()); }

 private:
  size_t headCap_ = kDefaultTraceWindow / 2, tailCap_ = kDefaultTraceWindow - kDefaultTraceWindow / 2;
  size_t size_ = 0;
  std::vector<T> head_;
  std::vector<T> ring_;  // record i >= headCap_ at slot (i - headCap_) % tailCap_
  T evicted_{};
};

}  // namespace virtcom
