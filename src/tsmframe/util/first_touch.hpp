#pragma once
// The first write to a page of fresh memory is a page fault; on a virtual machine each costs far
// more than the work done on the page, and the set-up's large arrays are thousands of pages.
// Asking the kernel to map a whole range at once (MADV_POPULATE_WRITE, Linux ≥ 5.14) costs a
// fraction of that per page, and two threads can ask side by side. Only
// memory about to be written is populated: the resident size stays what it would be.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace tsm::util {

/// Maps in every whole 4 KiB page of [data, data + bytes) for writing, shared out over the
/// threads; where the kernel cannot, touches each page instead. The contents are unspecified
/// afterwards (raw storage to be written).
void touch_pages(void* data, std::size_t bytes);

/// v.reserve(n), the storage beyond v's elements mapped in first (touch_pages).
template <class T>
void reserve_touched(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  touch_pages(v.data() + v.size(), (n - v.size()) * sizeof(T));  // raw storage: what follows constructs over it
}

/// v.resize(n), its new storage mapped in first.
template <class T>
void resize_touched(std::vector<T>& v, std::size_t n) {
  reserve_touched(v, n);
  v.resize(n);
}

/// v.assign(n, value), its new storage mapped in first.
template <class T>
void assign_touched(std::vector<T>& v, std::size_t n, const T& value) {
  if (n > v.capacity()) std::vector<T>().swap(v);  // nothing to keep: all of it new storage
  reserve_touched(v, n);
  v.assign(n, value);
}

/// v.resize(n) for an Eigen vector; new storage mapped in first (touch_pages).
inline void resize_touched(Eigen::VectorXd& v, Eigen::Index n) {
  if (v.size() == n) return;
  v.resize(n);
  touch_pages(v.data(), static_cast<std::size_t>(n) * sizeof(double));
}

/// An Eigen vector of n zeros, its storage mapped in first (touch_pages).
inline Eigen::VectorXd zeros_touched(Eigen::Index n) {
  Eigen::VectorXd v;
  resize_touched(v, n);
  v.setZero();
  return v;
}

}  // namespace tsm::util
