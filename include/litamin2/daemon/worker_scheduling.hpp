#pragma once
/// The scheduling class and CPU set of the stream scheduler's worker threads (YAML
/// `scheduling:`), its validation, and applying it to a thread. Opt-in: the default (policy
/// other, no cpus) leaves the workers as they are started. A real-time policy lets a frame's
/// worker preempt every SCHED_OTHER process on its core at once, instead of waiting for its
/// fair share (docs/benchmarks.md, "Streams per daemon core": on a shared core the p99 was set
/// by the worker losing the core, not by queueing).

#include <pthread.h>

#include <optional>
#include <string>
#include <vector>

namespace litamin2::daemon {

enum class WorkerPolicy {
  /// SCHED_OTHER: the kernel's fair scheduler, as every other process (the default).
  kOther,
  /// SCHED_FIFO: runs until it blocks or a higher priority is ready; needs CAP_SYS_NICE (or
  /// an RLIMIT_RTPRIO of at least `priority`). Bounded by the kernel's RT throttling
  /// (/proc/sys/kernel/sched_rt_runtime_us of sched_rt_period_us).
  kFifo,
  /// SCHED_RR: as kFifo, with a time slice among the workers of one priority.
  kRoundRobin,
};

/// Which threads get the policy and CPUs.
enum class SchedulingScope {
  /// The stream scheduler's workers only (threads named stream-worker): Fast DDS's receive
  /// threads, which take and convert the scans, stay as they are.
  kWorkers,
  /// The thread that starts the daemon node, before it starts any other, so every thread
  /// started after it inherits them: Fast DDS's receive and event threads and the workers (as
  /// systemd's CPUSchedulingPolicy= does for a whole process).
  kProcess,
};

struct WorkerScheduling {
  SchedulingScope scope = SchedulingScope::kWorkers;
  WorkerPolicy policy = WorkerPolicy::kOther;
  /// The real-time priority, 1-99, for fifo and rr; 0 (and no other value) with other.
  int priority = 0;
  /// CPUs the workers may run on (pthread_setaffinity_np); empty: left as inherited from the
  /// process (taskset, systemd's CPUAffinity=).
  std::vector<int> cpus;
};

/// The YAML name of a policy: other, fifo, rr.
const char* worker_policy_name(WorkerPolicy policy);

/// The YAML name of a scope: workers, process.
const char* scheduling_scope_name(SchedulingScope scope);

/// What is wrong with `scheduling`, naming the key relative to the section ("priority: ..."),
/// or nullopt: a priority outside 1-99 with fifo or rr, a priority other than 0 with other,
/// a cpu that is negative, not below CPU_SETSIZE or given twice. (An empty `cpus` list in the
/// YAML is rejected by the reader; here an empty list means "not given".)
std::optional<std::string> worker_scheduling_error(const WorkerScheduling& scheduling);

/// Applies `scheduling` to `thread`: its CPU set (every cpu must be in the calling process's
/// allowed set, sched_getaffinity: a CPU outside it is an error, not silently left out), then
/// its policy and priority. Nothing is changed for the default. Throws std::runtime_error
/// naming the `scheduling` key, `threads` (what the thread is, for the message) and the cause;
/// for EPERM the message names CAP_SYS_NICE.
void apply_worker_scheduling(pthread_t thread, const WorkerScheduling& scheduling,
                             const std::string& threads = "the stream workers");

}  // namespace litamin2::daemon
