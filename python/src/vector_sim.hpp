#pragma once
// n independent worlds stepped together on a pool of threads (docs/python.md,
// "VectorSim"). Each world has its own seed and is stepped by one thread at a
// time; worlds share nothing, so the results do not depend on the number of
// threads or on which thread stepped which world.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "in_process_sim.hpp"
#include "worker_pool.hpp"

namespace ubersim::python {

class VectorSim {
 public:
  // World i gets seeds[i]. threads = 0: one per world, at most the machine's cores.
  VectorSim(const SimOptions& options, const std::vector<std::uint64_t>& seeds,
            std::size_t threads);

  std::size_t size() const { return worlds_.size(); }
  std::size_t threads() const { return pool_.threads(); }
  InProcessSim& world(std::size_t i) { return *worlds_.at(i); }

  // orders[i] for world i, checked already (InProcessSim::check_orders).
  // Call without the Python interpreter's lock: it only touches C++.
  void step(const std::vector<std::vector<RobotOrder>>& orders);
  // Resets the worlds named (each with its seed, or its own when none), in parallel.
  void reset(const std::vector<std::size_t>& worlds,
             const std::vector<std::optional<std::uint64_t>>& seeds);

 private:
  std::vector<std::unique_ptr<InProcessSim>> worlds_;
  WorkerPool pool_;
};

}  // namespace ubersim::python
