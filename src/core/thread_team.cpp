// The calling thread's team of workers (thread_team.hpp).
#include "thread_team.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <pthread.h>
#include <strings.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace ragdoll_sim {
namespace {

void pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

using Clock = std::chrono::steady_clock;
// How long an idle worker spins before it sleeps: longer than the serial parts between a step's
// regions, short enough that a World stepped in real time leaves its cores idle between steps
// of a few milliseconds. A team with more threads than the machine has cores sleeps after a few
// microseconds, as libgomp's throttled spin does: a spinning worker would take the core of one
// still working. So does every team under OMP_WAIT_POLICY=passive (OpenMP's "do not spin").
constexpr auto kSpinTime = std::chrono::microseconds(1000);

bool passiveWait() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  return policy && strcasecmp(policy, "passive") == 0;
}

// A region's size rides in the generation word's low 16 bits, so that a worker reads the size of
// the region it woke for, never the next one's.
constexpr int kSizeBits = 16;
constexpr uint64_t kSizeMask = (uint64_t(1) << kSizeBits) - 1;

thread_local std::pair<int, int> current_slot{0, 1};

// Forks of this process so far, counted in each child (from the first team on): a child has its
// parent's team objects but not their threads.
std::atomic<int> forks{0};
void countFork() { forks.fetch_add(1, std::memory_order_relaxed); }

class Team {
 public:
  Team() : fork_(forks.load(std::memory_order_relaxed)) {}
  ~Team() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true, std::memory_order_relaxed);
      generation_.fetch_add(uint64_t(1) << kSizeBits, std::memory_order_seq_cst);
    }
    wake_.notify_all();
    for (std::thread& w : workers_) w.join();
  }
  bool forked() const { return fork_ != forks.load(std::memory_order_relaxed); }

  void run(int threads, thread_team_detail::Call call, void* body) {
    grow(threads);
    call_ = call;
    body_ = body;
    finished_ += uint64_t(threads - 1);
    const uint64_t next = ((generation_.load(std::memory_order_relaxed) >> kSizeBits) + 1);
    generation_.store(next << kSizeBits | uint64_t(threads), std::memory_order_seq_cst);
    if (sleepers_.load(std::memory_order_seq_cst) > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      wake_.notify_all();
    }
    current_slot = {0, threads};
    call(body, 0);
    current_slot = {0, 1};
    for (int spins = 0; done_.load(std::memory_order_acquire) != finished_; ++spins) {
      if (spins < (sleep_at_once_.load(std::memory_order_relaxed) ? kYieldSleeping
                                                                    : kYieldAfter))
        pause();
      else std::this_thread::yield();  // a worker was preempted
    }
  }

 private:
  static constexpr int kYieldAfter = 1 << 16, kYieldSleeping = 64;

  void grow(int threads) {
    static const unsigned cores = std::thread::hardware_concurrency();
    static const bool passive = passiveWait();
    const bool sleep = passive || unsigned(threads) > cores;
    if (sleep != sleep_at_once_.load(std::memory_order_relaxed)) sleep_at_once_.store(sleep);
    while (int(workers_.size()) < threads - 1) {
      const int t = int(workers_.size()) + 1;
      // the generation before this region's: the new worker takes this region
      const uint64_t seen = generation_.load(std::memory_order_relaxed);
      workers_.emplace_back([this, t, seen] { work(t, seen); });
    }
  }

  uint64_t waitForNext(uint64_t seen) {
    Clock::time_point start;
    for (int spins = 0;; ++spins) {
      const uint64_t g = generation_.load(std::memory_order_acquire);
      if (g != seen) return g;
      pause();
      if ((spins & 255) != 255) continue;
      if (sleep_at_once_.load(std::memory_order_relaxed)) break;
      if (spins == 255) start = Clock::now();
      else if (Clock::now() - start > kSpinTime) break;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    sleepers_.fetch_add(1, std::memory_order_seq_cst);
    wake_.wait(lock, [&] { return generation_.load(std::memory_order_seq_cst) != seen; });
    sleepers_.fetch_sub(1, std::memory_order_relaxed);
    return generation_.load(std::memory_order_acquire);
  }

  void work(int t, uint64_t seen) {
    for (;;) {
      seen = waitForNext(seen);
      if (stop_.load(std::memory_order_relaxed)) return;
      const int threads = int(seen & kSizeMask);
      if (t >= threads) continue;
      current_slot = {t, threads};
      call_(body_, t);
      current_slot = {0, 1};
      done_.fetch_add(1, std::memory_order_release);
    }
  }

  const int fork_;
  std::vector<std::thread> workers_;
  uint64_t finished_ = 0;  // the workers' count of finished regions once this one is done
  std::atomic<bool> sleep_at_once_{false};  // no spin: passive, or more threads than cores
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  // The region's body beside the word that announces it: a worker reads them in one transfer.
  alignas(64) std::atomic<uint64_t> generation_{0};
  thread_team_detail::Call call_ = nullptr;
  void* body_ = nullptr;
  alignas(64) std::atomic<uint64_t> done_{0};
  alignas(64) std::atomic<int> sleepers_{0};
};

}  // namespace

std::pair<int, int> teamSlot() { return current_slot; }

void thread_team_detail::run(int threads, Call call, void* body) {
  if (threads <= 1 || current_slot.second > 1 || threads > int(kSizeMask)) {
    // alone, nested in a region, or beyond the generation word's size field
    const std::pair<int, int> outer = current_slot;
    current_slot = {0, 1};
    call(body, 0);
    current_slot = outer;
    return;
  }
  static const int fork_counted = pthread_atfork(nullptr, nullptr, countFork);
  (void)fork_counted;
  thread_local std::unique_ptr<Team> team;
  if (team && team->forked()) (void)team.release();  // its threads are not in this process
  if (!team) team = std::make_unique<Team>();
  team->run(threads, call, body);
}

}  // namespace ragdoll_sim
