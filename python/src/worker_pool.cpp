#include "worker_pool.hpp"

#include "ubersim/physics/ode_handles.hpp"

namespace ubersim::python {

WorkerPool::WorkerPool(std::size_t threads) {
  for (std::size_t i = 1; i < threads; ++i) workers_.emplace_back([this] { work_loop(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void WorkerPool::run(std::size_t count, const std::function<void(std::size_t)>& job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &job;
    count_ = count;
    next_ = 0;
    finished_ = 0;
    error_ = nullptr;
    ++batch_;
  }
  wake_.notify_all();
  take_jobs();
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return finished_ == count_; });
  job_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

void WorkerPool::take_jobs() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (job_ != nullptr && next_ < count_) {
    const std::size_t index = next_++;
    const auto* job = job_;
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job)(index);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error && !error_) error_ = error;
    if (++finished_ == count_) done_.notify_all();
  }
}

void WorkerPool::work_loop() {
  // ODE's collision code needs its per-thread data on every thread that steps a world.
  physics::ensure_ode_initialised();
  std::size_t seen_batch = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || batch_ != seen_batch; });
      if (stopping_) return;
      seen_batch = batch_;
    }
    take_jobs();
  }
}

}  // namespace ubersim::python
