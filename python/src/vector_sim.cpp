#include "vector_sim.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace ubersim::python {
namespace {

std::size_t pool_size(std::size_t requested, std::size_t worlds) {
  if (requested > 0) return requested;
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  return std::max<std::size_t>(1, std::min(worlds, cores));
}

}  // namespace

VectorSim::VectorSim(const SimOptions& options, const std::vector<std::uint64_t>& seeds,
                     std::size_t threads)
    : pool_(pool_size(threads, seeds.size())) {
  if (seeds.empty()) throw std::invalid_argument("a VectorSim needs at least one world");
  for (std::uint64_t seed : seeds) {
    SimOptions world_options = options;
    world_options.seed = seed;
    worlds_.push_back(std::make_unique<InProcessSim>(world_options));
  }
}

void VectorSim::step(const std::vector<std::vector<RobotOrder>>& orders) {
  if (orders.size() != worlds_.size()) {
    throw std::invalid_argument("one list of orders per world expected");
  }
  pool_.run(worlds_.size(), [&](std::size_t i) { worlds_[i]->step(orders[i]); });
}

void VectorSim::reset(const std::vector<std::size_t>& worlds,
                      const std::vector<std::optional<std::uint64_t>>& seeds) {
  std::vector<bool> named(worlds_.size(), false);
  for (std::size_t w : worlds) {
    if (w >= worlds_.size()) {
      throw std::out_of_range("world " + std::to_string(w) + " does not exist (" +
                              std::to_string(worlds_.size()) + " worlds)");
    }
    if (named[w]) throw std::invalid_argument("world " + std::to_string(w) + " named twice");
    named[w] = true;
  }
  if (seeds.size() != worlds.size()) {
    throw std::invalid_argument("one seed (or None) per world to reset expected");
  }
  pool_.run(worlds.size(), [&](std::size_t k) { worlds_[worlds[k]]->reset(seeds.at(k)); });
}

}  // namespace ubersim::python
