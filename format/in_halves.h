// Runs a step over a range in two halves, the second half on another thread.
#pragma once

#include <future>
#include <system_error>

namespace srcodec {

// step(begin, end) when `two_threads` is false; else step(begin, middle) on
// this thread and step(middle, end) on another, joined before returning. If
// no thread can be made, this thread does the whole range. Index is an
// integer or a pointer. Either way the same elements are stepped over, so
// the result does not depend on the threads when the two halves do not
// touch each other's data.
template <class Index, class Step>
void run_in_halves(Index begin, Index end, bool two_threads, const Step& step) {
  if (!two_threads) return step(begin, end);
  const Index middle = begin + (end - begin) / 2;
  std::future<void> other;
  try {
    other = std::async(std::launch::async, [&step, middle, end] { step(middle, end); });
  } catch (const std::system_error&) {
    return step(begin, end);
  }
  step(begin, middle);
  other.get();
}

}  // namespace srcodec
