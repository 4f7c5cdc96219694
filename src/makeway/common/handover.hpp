#pragma once
// Work handed to TBB's threads and back, made visible to ThreadSanitizer. Debian's oneTBB is not
// built with TSan (tests/tsan.supp), so its scheduler's hand-over of a loop body to a worker and
// the join afterwards are invisible to it: a body's writes read by the caller after the loop look
// like races. An atomic released before the hand-over and at the end of every body, acquired at
// the start of every body and after the join, states the happens-before the scheduler provides
// (a few atomic operations per chunk of work; nothing for the results). visible_parallel_for wraps
// a parallel loop in it.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>

namespace makeway {

class Handover {
  public:
    /// Before the work goes to other threads, and at the end of each piece of it.
    void release() { sequence_.fetch_add(1, std::memory_order_release); }
    /// At the start of each piece of work, and in the caller after the join.
    void acquire() const { (void)sequence_.load(std::memory_order_acquire); }

  private:
    std::atomic<unsigned> sequence_{0};
};

/// tbb::parallel_for(range, body) on `arena`'s threads, the hand-over each way made visible.
template <class Range, class Body>
void visible_parallel_for(tbb::task_arena& arena, const Range& range, const Body& body) {
    Handover handover;
    handover.release();
    arena.execute([&] {
        tbb::parallel_for(range, [&](const Range& part) {
            handover.acquire();
            body(part);
            handover.release();
        });
    });
    handover.acquire();
}

}  // namespace makeway
