#include "worker_pool.hpp"

#include "ubersim/physics/ode_handles.hpp"

namespace ubersim::python {

WorkerPool::WorkerPool(std::size_t threads) {
  for (std::size_t i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work_loop(i); });
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
    finished_ = 0;
    error_ = nullptr;
    ++batch_;
  }
  wake_.notify_all();
  do_share(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return finished_ == threads(); });
  job_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

void WorkerPool::do_share(std::size_t participant) {
  std::exception_ptr error;
  for (std::size_t index = participant; index < count_; index += threads()) {
    try {
      (*job_)(index);
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (error && !error_) error_ = error;
  if (++finished_ == threads()) done_.notify_all();
}

void WorkerPool::work_loop(std::size_t participant) {
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
    do_share(participant);
  }
}

}  // namespace ubersim::python
