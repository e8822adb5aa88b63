#include "litamin2/daemon/worker_scheduling.hpp"

#include <sched.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>

namespace litamin2::daemon {
namespace {

int posix_policy(WorkerPolicy policy) {
  switch (policy) {
    case WorkerPolicy::kFifo:
      return SCHED_FIFO;
    case WorkerPolicy::kRoundRobin:
      return SCHED_RR;
    case WorkerPolicy::kOther:
      break;
  }
  return SCHED_OTHER;
}

bool is_realtime(WorkerPolicy policy) {
  return policy != WorkerPolicy::kOther;
}

std::string cpu_list(const std::vector<int>& cpus) {
  std::string out;
  for (int cpu : cpus) out += (out.empty() ? "" : ", ") + std::to_string(cpu);
  return "[" + out + "]";
}

}  // namespace

const char* worker_policy_name(WorkerPolicy policy) {
  switch (policy) {
    case WorkerPolicy::kFifo:
      return "fifo";
    case WorkerPolicy::kRoundRobin:
      return "rr";
    case WorkerPolicy::kOther:
      break;
  }
  return "other";
}

const char* scheduling_scope_name(SchedulingScope scope) {
  return scope == SchedulingScope::kProcess ? "process" : "workers";
}

std::optional<std::string> worker_scheduling_error(const WorkerScheduling& scheduling) {
  if (is_realtime(scheduling.policy)) {
    if (scheduling.priority < 1 || scheduling.priority > 99)
      return "priority: " + std::to_string(scheduling.priority) + " is out of range [1, 99] for " +
             worker_policy_name(scheduling.policy);
  } else if (scheduling.priority != 0) {
    return "priority: " + std::to_string(scheduling.priority) +
           " given with policy other (a priority is for fifo and rr; other has none)";
  }
  std::set<int> seen;
  for (std::size_t i = 0; i < scheduling.cpus.size(); ++i) {
    const int cpu = scheduling.cpus[i];
    const std::string item = "cpus[" + std::to_string(i) + "]: ";
    if (cpu < 0 || cpu >= CPU_SETSIZE)
      return item + std::to_string(cpu) + " is out of range [0, " +
             std::to_string(CPU_SETSIZE - 1) + "]";
    if (!seen.insert(cpu).second) return item + "CPU " + std::to_string(cpu) + " is given twice";
  }
  return std::nullopt;
}

void apply_worker_scheduling(pthread_t thread, const WorkerScheduling& scheduling,
                             const std::string& threads) {
  if (const auto why = worker_scheduling_error(scheduling))
    throw std::runtime_error("scheduling." + *why);
  if (!scheduling.cpus.empty()) {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0)
      throw std::runtime_error(std::string("scheduling.cpus: cannot read the allowed CPUs: ") +
                               std::strerror(errno));
    cpu_set_t set;
    CPU_ZERO(&set);
    for (int cpu : scheduling.cpus) {
      if (!CPU_ISSET(cpu, &allowed))
        throw std::runtime_error("scheduling.cpus " + cpu_list(scheduling.cpus) + ": CPU " +
                                 std::to_string(cpu) +
                                 " is not one this process may run on (its affinity, cpuset or "
                                 "the machine's CPUs)");
      CPU_SET(cpu, &set);
    }
    if (const int err = pthread_setaffinity_np(thread, sizeof(set), &set))
      throw std::runtime_error("scheduling.cpus " + cpu_list(scheduling.cpus) +
                               ": pthread_setaffinity_np: " + std::strerror(err));
  }
  if (!is_realtime(scheduling.policy)) return;
  sched_param param{};
  param.sched_priority = scheduling.priority;
  if (const int err = pthread_setschedparam(thread, posix_policy(scheduling.policy), &param)) {
    std::string message = std::string("scheduling.policy ") +
                          worker_policy_name(scheduling.policy) + " (priority " +
                          std::to_string(scheduling.priority) + ") cannot be applied to " +
                          threads + ": pthread_setschedparam: " + std::strerror(err);
    if (err == EPERM)
      message +=
          "; a real-time policy needs the capability CAP_SYS_NICE (systemd: "
          "AmbientCapabilities=CAP_SYS_NICE, CapabilityBoundingSet=CAP_SYS_NICE and "
          "RestrictRealtime=no, docs/deploy.md) or an RLIMIT_RTPRIO of at least " +
          std::to_string(scheduling.priority) + " (LimitRTPRIO=)";
    throw std::runtime_error(message);
  }
}

}  // namespace litamin2::daemon
