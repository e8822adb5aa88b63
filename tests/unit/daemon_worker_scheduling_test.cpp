// The stream workers' opt-in scheduling (worker_scheduling.hpp): the default leaves them as
// started, CPUs and a real-time policy are seen by the frames' own thread, a CPU the process
// may not use and a real-time policy without CAP_SYS_NICE fail the scheduler's construction
// with a message that names the key and the capability.

#include "litamin2/daemon/stream_scheduler.hpp"

#include <gtest/gtest.h>

#include <linux/capability.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace litamin2::daemon;
using namespace std::chrono_literals;

namespace {

/// What a frame's thread saw: its policy, priority and CPUs.
struct ThreadScheduling {
  int policy = -1;
  int priority = -1;
  std::vector<int> cpus;
};

/// Runs one frame on a scheduler built with `scheduling` and returns what its thread saw.
ThreadScheduling seen_by_a_frame(const WorkerScheduling& scheduling) {
  StreamScheduler scheduler(1, 4, scheduling);
  ThreadScheduling seen;
  const auto s = scheduler.add_stream("a", [&](Frame&) {
    sched_param param{};
    pthread_getschedparam(pthread_self(), &seen.policy, &param);
    seen.priority = param.sched_priority;
    cpu_set_t set;
    CPU_ZERO(&set);
    pthread_getaffinity_np(pthread_self(), sizeof(set), &set);
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
      if (CPU_ISSET(cpu, &set)) seen.cpus.push_back(cpu);
  });
  Frame frame;
  scheduler.submit(s, std::move(frame));
  EXPECT_TRUE(scheduler.drain(10s).complete);
  return seen;
}

std::vector<int> allowed_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  sched_getaffinity(0, sizeof(set), &set);
  std::vector<int> cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &set)) cpus.push_back(cpu);
  return cpus;
}

/// The construction's error message ("" if it succeeds).
std::string error_of(const WorkerScheduling& scheduling) {
  try {
    StreamScheduler scheduler(2, 4, scheduling);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

/// Removes CAP_SYS_NICE from this process's effective and permitted sets and sets its
/// RLIMIT_RTPRIO to 0: what an unprivileged daemon has. Returns false if it could not.
bool drop_realtime_rights() {
  __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
  __user_cap_data_struct data[_LINUX_CAPABILITY_U32S_3] = {};
  if (syscall(SYS_capget, &header, data) != 0) return false;
  const unsigned word = CAP_SYS_NICE / 32, bit = 1u << (CAP_SYS_NICE % 32);
  data[word].effective &= ~bit;
  data[word].permitted &= ~bit;
  data[word].inheritable &= ~bit;
  if (syscall(SYS_capset, &header, data) != 0) return false;
  const rlimit none{0, 0};
  return setrlimit(RLIMIT_RTPRIO, &none) == 0;
}

}  // namespace

TEST(StreamSchedulerWorkers, DefaultLeavesPolicyAndCpusAsInherited) {
  const ThreadScheduling seen = seen_by_a_frame(WorkerScheduling{});
  EXPECT_EQ(seen.policy, SCHED_OTHER);
  EXPECT_EQ(seen.priority, 0);
  EXPECT_EQ(seen.cpus, allowed_cpus());
}

TEST(StreamSchedulerWorkers, CpusAreTheFramesThreadsCpus) {
  const std::vector<int> allowed = allowed_cpus();
  ASSERT_FALSE(allowed.empty());
  WorkerScheduling scheduling;
  scheduling.cpus = {allowed.back()};
  const ThreadScheduling seen = seen_by_a_frame(scheduling);
  EXPECT_EQ(seen.policy, SCHED_OTHER);
  EXPECT_EQ(seen.cpus, std::vector<int>{allowed.back()});
}

TEST(StreamSchedulerWorkers, CpuTheProcessMayNotUseFailsConstruction) {
  const std::vector<int> allowed = allowed_cpus();
  ASSERT_FALSE(allowed.empty());
  ASSERT_LT(allowed.back(), CPU_SETSIZE - 1);
  WorkerScheduling scheduling;
  scheduling.cpus = {allowed.front(), CPU_SETSIZE - 1};
  EXPECT_EQ(error_of(scheduling), "scheduling.cpus [" + std::to_string(allowed.front()) +
                                      ", 1023]: CPU 1023 is not one this process may run on "
                                      "(its affinity, cpuset or the machine's CPUs)");
}

TEST(StreamSchedulerWorkers, InvalidSchedulingFailsConstruction) {
  WorkerScheduling scheduling;
  scheduling.policy = WorkerPolicy::kFifo;
  scheduling.priority = 0;
  EXPECT_EQ(error_of(scheduling), "scheduling.priority: 0 is out of range [1, 99] for fifo");
}

TEST(StreamSchedulerWorkers, RealtimePolicyIsTheFramesThreadsPolicy) {
  for (const auto& [policy, posix] : {std::pair{WorkerPolicy::kFifo, SCHED_FIFO},
                                      std::pair{WorkerPolicy::kRoundRobin, SCHED_RR}}) {
    WorkerScheduling scheduling;
    scheduling.policy = policy;
    scheduling.priority = 10;
    const std::string error = error_of(scheduling);
    if (error.find("Operation not permitted") != std::string::npos)
      GTEST_SKIP() << "this process may not use a real-time policy: " << error;
    const ThreadScheduling seen = seen_by_a_frame(scheduling);
    EXPECT_EQ(seen.policy, posix) << worker_policy_name(policy);
    EXPECT_EQ(seen.priority, 10) << worker_policy_name(policy);
  }
}

TEST(StreamSchedulerWorkers, RealtimePolicyWithoutCapSysNiceFailsNamingTheCapability) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // In a child process that gives up CAP_SYS_NICE (and RLIMIT_RTPRIO) first.
  EXPECT_EXIT(
      {
        if (!drop_realtime_rights()) std::_Exit(3);
        WorkerScheduling scheduling;
        scheduling.policy = WorkerPolicy::kFifo;
        scheduling.priority = 10;
        const std::string error = error_of(scheduling);
        const bool names_it =
            error.rfind(
                "scheduling.policy fifo (priority 10) cannot be applied to the stream "
                "workers: pthread_setschedparam: Operation not permitted; a real-time "
                "policy needs the capability CAP_SYS_NICE",
                0) == 0;
        std::_Exit(names_it ? 0 : 1);
      },
      testing::ExitedWithCode(0), "");
}

TEST(StreamSchedulerWorkers, ThreadsStartedAfterProcessScopeInheritIt) {
  // Scope process applies the policy to the thread that starts the daemon node, relying on the
  // threads it starts afterwards (Fast DDS's, the workers) inheriting it; checked on a thread
  // of its own so that the test's thread keeps its policy.
  WorkerScheduling scheduling;
  scheduling.scope = SchedulingScope::kProcess;
  scheduling.policy = WorkerPolicy::kFifo;
  scheduling.priority = 7;
  std::string error;
  int child_policy = -1, child_priority = -1;
  std::thread starter([&] {
    try {
      apply_worker_scheduling(pthread_self(), scheduling, "the starter");
    } catch (const std::runtime_error& e) {
      error = e.what();
      return;
    }
    std::thread child([&] {
      sched_param param{};
      pthread_getschedparam(pthread_self(), &child_policy, &param);
      child_priority = param.sched_priority;
    });
    child.join();
  });
  starter.join();
  if (error.find("Operation not permitted") != std::string::npos)
    GTEST_SKIP() << "this process may not use a real-time policy: " << error;
  EXPECT_EQ(error, "");
  EXPECT_EQ(child_policy, SCHED_FIFO);
  EXPECT_EQ(child_priority, 7);
}
