#pragma once
// A fixed set of threads that run one batch of independent jobs at a time
// (VectorSim steps its worlds on them). The calling thread works too, so a
// pool of n threads starts n - 1. Thread k of n runs jobs k, k + n, k + 2n ...:
// a fixed share, so that a worker the kernel wakes late (a busy machine)
// still does its part instead of the caller doing everything alone. The jobs
// must not depend on which thread runs them (each world is stepped by one
// thread per batch and shares nothing with the others).
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace ubersim::python {

class WorkerPool {
 public:
  explicit WorkerPool(std::size_t threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  std::size_t threads() const { return workers_.size() + 1; }
  // Runs job(0) .. job(count - 1), returns when all are done; rethrows the
  // first exception a job threw (the other jobs still run to their end).
  void run(std::size_t count, const std::function<void(std::size_t)>& job);

 private:
  void work_loop(std::size_t participant);
  // Runs this participant's share of the batch (participant 0: the caller).
  void do_share(std::size_t participant);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t count_ = 0;
  std::size_t finished_ = 0;  // participants done with their share of this batch
  std::size_t batch_ = 0;     // batch number, to wake workers once per batch
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace ubersim::python
