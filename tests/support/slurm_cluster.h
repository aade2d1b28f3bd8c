// A real single-node Slurm for tests: munged, slurmctld and slurmd started as root from a
// temporary directory (key, sockets, state, spool, logs, slurm.conf on free ports), with
// SLURM_CONF set in this process so sbatch, squeue and every strand run by the test talk to
// it. Stopped and removed by the destructor. Header-only: only slurm_cluster_test uses it.
#pragma once

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/cli_runner.h"

namespace strand::testing {

class SlurmCluster {
 public:
  // Why no cluster can be started here ("" when it can): not root, or a program missing.
  static std::string why_not() {
    if (::geteuid() != 0) return "the Slurm daemons need root (run make test as root)";
    for (const char* p : {"/usr/sbin/munged", "/usr/sbin/mungekey", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                          "/usr/bin/sbatch", "/usr/bin/squeue", "/usr/bin/sinfo", "/usr/bin/scancel"}) {
      if (!std::filesystem::exists(p)) return std::string(p) + " is missing (apt-get install slurm-wlm munge)";
    }
    return "";
  }

  // Starts the daemons and waits (up to 60 s) for the node to be idle; error() says why not.
  SlurmCluster() : dir_(fresh_dir("slurm-cluster")) {
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all);  // munged checks
    for (const char* d : {"munge", "state", "spool"}) std::filesystem::create_directories(dir_ + "/" + d);
    std::filesystem::permissions(dir_ + "/munge", std::filesystem::perms::owner_all);
    const std::string m = dir_ + "/munge/";
    if (!sh("/usr/sbin/mungekey -c -k " + m + "munge.key") ||
        !sh("/usr/sbin/munged -f --key-file=" + m + "munge.key --socket=" + m + "sock --pid-file=" + m +
            "munged.pid --log-file=" + m + "munged.log --seed-file=" + m + "seed")) {
      error_ = "munged did not start: " + slurp(m + "munged.log");
      return;
    }
    write_conf();
    ::setenv("SLURM_CONF", (dir_ + "/slurm.conf").c_str(), 1);
    if (!sh("/usr/sbin/slurmctld -i") || !sh("/usr/sbin/slurmd")) {
      error_ = "slurmctld/slurmd did not start: " + logs();
      return;
    }
    for (int i = 0; i < 600; ++i) {
      if (shell_out("sinfo -h -o %t") == "idle\n") return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    error_ = "the node did not become idle within 60 s: " + shell_out("sinfo") + logs();
  }

  ~SlurmCluster() {
    sh("scancel --full --quiet --user=root");
    // All three at once: each takes about 2 s to shut down.
    std::vector<pid_t> pids;
    for (const char* pid_file : {"slurmd.pid", "slurmctld.pid", "munge/munged.pid"}) {
      std::ifstream in(dir_ + "/" + pid_file);
      pid_t pid = 0;
      if (in >> pid && pid > 1 && ::kill(pid, SIGTERM) == 0) pids.push_back(pid);
    }
    for (const pid_t pid : pids) {
      for (int i = 0; i < 100 && ::kill(pid, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (::kill(pid, 0) == 0) ::kill(pid, SIGKILL);  // still there after 10 s
    }
    ::unsetenv("SLURM_CONF");
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  const std::string& error() const { return error_; }
  std::string logs() const {
    return "\n--- slurmctld.log\n" + slurp(dir_ + "/slurmctld.log") + "\n--- slurmd.log\n" + slurp(dir_ + "/slurmd.log");
  }

  // Waits until job `id` has left the queue (finished, failed or cancelled); false after the
  // timeout.
  bool wait_for(const std::string& id, int timeout_s) const {
    for (int i = 0; i < timeout_s * 5; ++i) {
      if (shell_out("squeue -h -j " + id + " -o %i").empty()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return false;
  }

  // stdout of a shell command (run in the cluster's directory).
  std::string shell_out(const std::string& command) const { return run_in_shell(command + " 2>/dev/null", dir_).out; }

 private:
  bool sh(const std::string& command) const { return run_in_shell(command, dir_).exit_code == 0; }

  static int free_port() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    ::close(fd);
    return ntohs(a.sin_port);
  }

  void write_conf() const {
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    const std::string name = std::string(host).substr(0, std::string(host).find('.'));  // as slurmd names itself
    long mem_kb = 0;
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
      if (key == "MemTotal:") {
        meminfo >> mem_kb;
        break;
      }
    }
    const int ctld = free_port();
    int slurmd = free_port();
    while (slurmd == ctld) slurmd = free_port();
    std::ofstream(dir_ + "/slurm.conf")
        << "ClusterName=strandtest\nSlurmctldHost=" << name << "(127.0.0.1)\nSlurmctldPort=" << ctld
        << "\nSlurmdPort=" << slurmd << "\nSlurmUser=root\nSlurmdUser=root\nAuthType=auth/munge\nAuthInfo=socket="
        << dir_ << "/munge/sock\nCredType=cred/munge\nMpiDefault=none\n"
        // No cgroups in a container: processes tracked through /proc, tasks not bound.
        << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSelectType=select/cons_tres\n"
        << "SelectTypeParameters=CR_CPU\nSchedulerType=sched/builtin\nJobCompType=jobcomp/none\n"
        // Schedule on every submission and job end at once: a dependent merge waits seconds less.
        << "SchedulerParameters=sched_min_interval=0,batch_sched_delay=0\n"
        << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
        << "StateSaveLocation=" << dir_ << "/state\nSlurmdSpoolDir=" << dir_ << "/spool\nSlurmctldPidFile=" << dir_
        << "/slurmctld.pid\nSlurmdPidFile=" << dir_ << "/slurmd.pid\nSlurmctldLogFile=" << dir_
        << "/slurmctld.log\nSlurmdLogFile=" << dir_ << "/slurmd.log\nReturnToService=2\nMinJobAge=600\n"
        << "NodeName=" << name << " NodeAddr=127.0.0.1 CPUs=2 RealMemory=" << mem_kb / 2048 << " State=UNKNOWN\n"
        << "PartitionName=debug Nodes=" << name << " Default=YES MaxTime=INFINITE State=UP\n";
  }

  std::string dir_;
  std::string error_;
};

}  // namespace strand::testing
