// OnOneCpu: a process started in its scope runs on that one CPU (as launch.sh
// places physics, vision and radio in real time); the starter gets its CPUs back.
#include <gtest/gtest.h>
#include <sched.h>

#include <string>

#include "allowed_cpus.hpp"
#include "ubersim/child_process.hpp"
#include "ubersim/cpu_placement.hpp"

using ubersim::test::allowed_cpus;

TEST(CpuPlacement, AChildStartedInTheScopeRunsOnThatCpuAndTheStarterGetsItsCpusBack) {
  const int cpu = ubersim::last_allowed_cpu();
  ASSERT_GE(cpu, 0);
  cpu_set_t mine;
  ASSERT_EQ(::sched_getaffinity(0, sizeof mine, &mine), 0);
  EXPECT_TRUE(CPU_ISSET(cpu, &mine));
  for (int later = cpu + 1; later < CPU_SETSIZE; ++later) EXPECT_FALSE(CPU_ISSET(later, &mine));
  const std::string before = allowed_cpus(::getpid());

  std::unique_ptr<ubersim::ChildProcess> child;
  {
    const ubersim::OnOneCpu placed(cpu);
    child =
        std::make_unique<ubersim::ChildProcess>(std::vector<std::string>{"/bin/sleep", "30"}, "");
    EXPECT_EQ(allowed_cpus(::gettid()), std::to_string(cpu));
  }
  EXPECT_EQ(allowed_cpus(child->pid()), std::to_string(cpu));
  EXPECT_EQ(allowed_cpus(::getpid()), before);
  child->stop();

  // A negative CPU changes nothing.
  {
    const ubersim::OnOneCpu nowhere(-1);
    EXPECT_EQ(allowed_cpus(::getpid()), before);
  }
}
